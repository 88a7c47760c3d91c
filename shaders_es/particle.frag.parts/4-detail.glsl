#version 300 es
// particle.frag, part 4 of 7: the detail's perturbation: density, fire temperature, soot
#ifdef HAS_DETAIL
// This pixel's place in the detail volume: the particle's window, 0..1 across the particle.
vec3 detail_coordinate(vec3 c, float r, vec3 ray)
{
    vec2 q = ray.xy * (-c.z);
    vec2 local = (q - c.xy) / (2.0 * r) + 0.5;   // 0..1 across the particle
    return vec3(v_detail.xy + local * u_detail_window, v_detail.z + u_time);
}

float detail_sample(vec3 c, float r, vec3 ray)
{
    return detail_fetch(u_detail, detail_coordinate(c, r, ray)).r;
}
#endif

// The detail's perturbation (docs/look.md; ref/reference_frame.c mirrors it, constants
// SBFX_RF_EROSION_* there). Erosion: density x saturate((detail - threshold) * sharpness) x gain,
// the threshold rising as the particle's intensity falls (it ages), so parts of a particle thin
// out to nothing and others thicken; strength 0 leaves the density alone.
const float EROSION_THRESHOLD = 0.30;    // at full intensity
const float EROSION_AGE = 0.25;          // added as the intensity falls to 0
const float EROSION_SHARPNESS = 1.8;
const float EROSION_GAIN = 2.2;
float detail_density_scale(float detail, float intensity, float strength)
{
    float threshold = EROSION_THRESHOLD + EROSION_AGE * (1.0 - clamp(intensity, 0.0, 1.0));
    float eroded = clamp((detail - threshold) * EROSION_SHARPNESS, 0.0, 1.0) * EROSION_GAIN;
    return mix(1.0, eroded, strength);
}

// Fire's temperature coordinate (T = T0 + T1 * this): the detail's fluctuation at half its
// amplitude (FIRE_DETAIL), hotter toward the particle's core and cooler toward its edge (rho =
// distance from the centre / radius, in the centre's depth plane); 0.5 without detail
// (strength 0). Black-body luminance is steep in T: the full fluctuation made speckle whose
// spectrum was flatter than turbulent fire's (docs/look.md). As the fire cools (its intensity
// falls) the hot core fades and the detail's share grows (FIRE_DETAIL_AGE): cooling fire breaks
// into the detail's glowing and sooty parts instead of reading as a disc with a bright centre
// (docs/look-fire.md).
const float FIRE_CORE = 0.6;
const float FIRE_DETAIL = 0.5;
const float FIRE_DETAIL_AGE = 1.0;
float detail_fire_temperature(float detail, float rho, float intensity, float strength)
{
    float fresh = clamp(intensity, 0.0, 1.0);
    float spread = FIRE_DETAIL * (1.0 + FIRE_DETAIL_AGE * (1.0 - fresh));
    return mix(0.5, clamp(0.5 + spread * (detail - 0.5) + FIRE_CORE * fresh * (0.5 - rho), 0.0, 1.0), strength);
}

// Fire's soot (docs/look-fire.md), by Kirchhoff: what glows also absorbs, and soot too cool to
// glow still absorbs. Two parts, both keyed to the temperature coordinate (the detail-perturbed,
// rim-cooled one that sets T) and to the particle's age, so they follow the same fields that cool
// the fire:
// - fire_glow_share: the share of the column's soot hot enough to glow. Soot whose coordinate is
//   below a threshold (FIRE_GLOW_THRESHOLD, rising by FIRE_GLOW_AGE as the particle's intensity
//   falls) is cold; the column's emission is that share times its opacity (a mixed column of hot
//   and cold soot emits h (1 - e^-tau) and absorbs 1 - e^-tau). The thin, cool rim of a fireball
//   then darkens the sky behind it instead of adding red light to it (the pink edges of issue 27).
//   Over FIRE_GLOW_WIDTH of the coordinate the share rises from 0 to 1; strength 0: 1.
// - fire_soot: extra optical depth that absorbs and does not glow, where the fire is old and
//   cool: FIRE_SOOT ((1 - hot) (1 - intensity)^2)^2 times the peak extinction times chord^2 / 2r
//   (2r (1 - rho^2) for a whole chord: it reaches further out than the glowing part, whose depth
//   falls as (1 - rho)^1.5; an even spread, the chord itself, drew the spheres' edges). hot = the
//   temperature coordinate times the cooling factor (1: the fresh, hottest core). Old fire turns
//   into the smoke it makes; young fire carries little of it, so it stays light (DESIGN §8).
// - the cool share's soot (u_temperature.w, media.fire.soot, default 2): the share of the column
//   too cool to glow (1 - glow share) carries that many times the column's optical depth on top,
//   absorbing and not glowing: the soot that wraps a luminous flame. Where a young fireball's rim
//   starts to glow its column is thin, and red light 50 times the sky's added to sky that nothing
//   absorbs turns it pink; this soot darkens the sky there instead. An effect whose soot is smoke
//   particles (the seed's explosion) sets 0.
const float FIRE_GLOW_THRESHOLD = 0.45;
const float FIRE_GLOW_AGE = 0.4;
const float FIRE_GLOW_WIDTH = 0.2;
float fire_glow_share(float coordinate, float intensity, float strength)
{
    float threshold = FIRE_GLOW_THRESHOLD + FIRE_GLOW_AGE * (1.0 - clamp(intensity, 0.0, 1.0));
    return mix(1.0, clamp((coordinate - threshold) / FIRE_GLOW_WIDTH, 0.0, 1.0), strength);
}
const float FIRE_SOOT = 16.0;
float fire_soot(float coordinate, float cooled, float intensity)
{
    float age = 1.0 - clamp(intensity, 0.0, 1.0);
    float cool = (1.0 - coordinate * cooled) * age * age;
    return FIRE_SOOT * cool * cool;
}

// The scattered light's share of the detail: denser detail is darker (it shades itself), so the
// inside of a cloud too thick to show holes still shows its structure. Mean about 1.
const float DETAIL_SHADE = 1.8;
float detail_light_scale(float detail, float strength)
{
    return mix(1.0, 1.0 + DETAIL_SHADE * (0.5 - detail), strength);
}

float particle_rho(vec3 c, float r, vec3 ray)
{
    return length(ray.xy * (-c.z) - c.xy) / r;
}

