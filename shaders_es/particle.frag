#version 300 es
// The volumetric particle of the spherical-billboards seed, equation (1):
//   out = in * (1 - alpha) + alpha * albedo * C_in + alpha * (1 - albedo) * L_e
// written premultiplied into the particle target (rgb = added light, a = alpha; the blend
// multiplies the target's alpha, which holds transmittance). Specialised at load by defines:
//   MEDIUM_SCATTERS  dust/smoke: in-scattering through the phase-function table
//   MEDIUM_EMITS     fire: black-body emission at T = (T0 + T1 * detail), cooled as the
//                    particle's intensity (its density scale) falls
//   HAS_DETAIL       perturbation by the animated detail volume
//   OPACITY_PLANAR | OPACITY_SOFT | OPACITY_SPHERICAL | OPACITY_EXACT
//   OPACITY_FLOOR    benchmark only: the same quads, a trivial shader (the fill-rate floor)
//   BLACKBODY_ANALYTIC, PHASE_ANALYTIC   evaluate per fragment instead of fetching the tables
//   LIGHT_PER_PARTICLE  (phase model) in-scattering computed once per particle on the CPU
//   FIRE_LIGHT       (with MEDIUM_SCATTERS) the frame's fire light, in-scattered at the
//                    particle's centre on the CPU, falling off across it from the fire; lit
//                    media take it shaded by their brightness map, as a light without direction
//   LIGHTING_LIT     (with MEDIUM_SCATTERS) the lit-smoke seed instead of the phase function:
//                    per-pixel normals, wrap-around Lambert, back-lighting, up to 4 lights
//   LIT_SHADOW       (with LIGHTING_LIT) ray-marched self-shadowing through the height field,
//                    toward the key light (the first) only
//   TABLE_PROBE      diagnostics: main() writes blackbody(T) and phase(cos) for the probe and
//                    the tests (src/diagnostics.c) instead of shading a particle
// Light and colour are mediump (what a Mali-class GPU runs at half precision); geometry,
// depth and opacity stay highp.
precision highp float;
precision highp sampler2D;
precision highp sampler3D;
#ifndef FILTER_BITS   // SBFX_FILTER_BITS (shaders_es/filtered.frag): else the texture unit filters
#define filtered_3d_repeat(s, p) texture(s, p)
#define filtered_array_lod(s, p, lod) textureLod(s, p, lod)
#endif
#if defined(FILTER_BITS) && defined(DETAIL_NEAREST)
#define detail_fetch(s, p) texture(s, p)   // an R32F volume is sampled NEAREST: nothing to filter
#else
#define detail_fetch(s, p) filtered_3d_repeat(s, p)
#endif

#ifndef TABLE_PROBE
flat in vec4 v_center_radius;
flat in vec4 v_detail;
#endif
#ifdef LIGHT_PER_PARTICLE
flat in vec3 v_light;            // in-scattered light evaluated once at the particle's centre
#endif
#ifdef HAS_MOTION_TARGET
flat in vec2 v_velocity;
#endif
#if defined(FIRE_LIGHT) && !defined(LIGHTING_LIT)
flat in mediump vec3 v_fire;          // fire light in-scattered at the centre (phase model)
flat in mediump vec2 v_fire_gradient; // its relative change per metre across the particle
#endif
#ifdef MEDIUM_HEAT
uniform float u_heat_strength;   // largest shimmer offset, UV units
#endif

uniform sampler2D u_depth;       // low-res opaque near / distance (depth texture; 0: no surface)
uniform float u_near;
uniform vec4 u_projection;       // projection[0], [5], [8], [9]
uniform vec2 u_target_size;
uniform float u_tau;
uniform float u_soft_scale;

#ifdef HAS_DETAIL
uniform sampler3D u_detail;
uniform float u_detail_window;
uniform float u_detail_strength;
uniform float u_time;            // in detail-volume loops
#endif
#ifdef MEDIUM_SCATTERS
uniform sampler2D u_phase_lut;   // R32F, row m: medium m's phase function (src/tables.c)
uniform int u_phase_row;
uniform vec4 u_phase_warp;       // sign(g), (1-|g|)^2, 2|g| (0: unwarped), 1/ln((1-|g|)^2/(1+|g|)^2)
uniform vec2 u_phase_shift;      // -ln((1+|g|)^2) * u_phase_warp.w, entries - 1
uniform float u_g;
uniform vec3 u_albedo_color;     // albedo * tint
#define MAX_LIGHTS 8
#ifndef LIGHT_SLOTS
#define LIGHT_SLOTS MAX_LIGHTS   // set at load to the scene's lights + one effect's flashes
#endif
uniform int u_light_count;
uniform vec4 u_light_vector[MAX_LIGHTS]; // view space: w = 0 direction of travel, w = 1 position
uniform vec3 u_light_color[MAX_LIGHTS];  // irradiance (point lights: at 1 m) x 4 pi (passes.c)
uniform vec3 u_ambient;
#endif
#ifdef LIGHTING_LIT
precision highp sampler2DArray;
uniform sampler2DArray u_smoke;  // per variant v: layer 2v normal*0.5+0.5, height; 2v+1 brightness, translucency
#ifdef FIRE_LIGHT   // with the fire's light at the centre in the free components (particle.vert)
flat in vec4 v_lit;              // layer 2v, level of detail, the fire's light's red and green
flat in vec4 v_view;             // unit, from the centre toward the eye; the fire's light's blue
#else
flat in vec2 v_lit;              // the particle's layer 2v and level of detail (particle.vert)
flat in vec3 v_view;             // unit, from the particle's centre toward the eye
#endif
uniform vec3 u_wrap;             // wrap-around scale 1/(1+w), bias w/(1+w); 1+w
uniform float u_translucency;
uniform float u_direct;          // 1 - dampening: the lights' direct term is scaled by it
uniform vec2 u_steps;            // nMin + 1/2, nMax - nMin of the ray march
#define MAX_LIT_LIGHTS 4
#define LIT_SLOTS (LIGHT_SLOTS < MAX_LIT_LIGHTS ? LIGHT_SLOTS : MAX_LIT_LIGHTS)
#if LIGHT_SLOTS > 1
flat in vec4 v_fill[LIT_SLOTS - 1]; // lights 1.. seen from the particle's centre: direction, falloff
flat in float v_fill_back[LIT_SLOTS - 1]; // ... and falloff x max(0, -V.L)
#endif
#define MAX_STEPS 64             // SBFX_LIT_MAX_STEPS
#endif
#ifdef BLACKBODY_ANALYTIC
#define MAX_BANDS 96
uniform int u_cmf_count;
uniform vec3 u_cmf_rgb[MAX_BANDS]; // sRGB weight of each band (CMF, trapezoid, 2hc², norm)
uniform float u_cmf_band[MAX_BANDS]; // wavelength [µm]
#endif
#ifdef MEDIUM_EMITS
uniform sampler2D u_blackbody;   // RGBA32F, uniform in 1/T: rgb / Y, ln(Y / T) (src/blackbody.c)
uniform vec3 u_blackbody_map;    // 1/T at entry 0, entries per unit of 1/T, entries - 2
uniform vec4 u_temperature;      // T0, T1, cooling, the cool share's soot (media.fire.soot)
uniform float u_emission_scale;   // includes (1 - albedo)
// Per-fragment radiance ceiling, in pre-exposed units: back-to-front "over" never sums layers
// above their largest one, so the target stays inside half-float's 65504 (docs/look-fire.md).
const float RADIANCE_CEILING = 16384.0;
#endif

// 0: premultiplied light, alpha; 1: shimmer offset (heat adds, others occlude by alpha);
// 2: premultiplied screen velocity and view distance, alpha (motion blur, depth of field)
layout(location = 0) out vec4 o_color;
#ifdef HAS_DISTORTION_TARGET
layout(location = 1) out vec4 o_distortion;
#endif
#ifdef HAS_MOTION_TARGET
layout(location = 2) out vec4 o_velocity;
#endif

float soft_fade(float x)
{
    x = clamp(x, 0.0, 1.0);
    return x < 0.5 ? 2.0 * x * x : 1.0 - 2.0 * (1.0 - x) * (1.0 - x);
}

// h * asinh(u / sqrt(h)), odd in u, -> 0 as h -> 0 without dividing by sqrt(h).
float h_asinh(float h, float u)
{
    if (h <= 1e-30) return 0.0;
    float au = abs(u);
    float v = h * (log(au + sqrt(h + au * au)) - 0.5 * log(h));
    return u < 0.0 ? -v : v;
}

float chord_integral(float h, float a, float b)
{
    float fa = a * sqrt(h + a * a) + h_asinh(h, a);
    float fb = b * sqrt(h + b * b) + h_asinh(h, b);
    return 0.5 * (fb - fa);
}

// Optical depth along this pixel's ray; `ray` has z = -1, zs = opaque distance along -z.
// `chord`: the length of the ray inside the particle, clipped the same way (fire's soot).
float optical_depth(vec3 c, float r, vec3 ray, float zs, out float chord)
{
    float zc = -c.z;
    chord = 0.0;
#ifdef OPACITY_EXACT
    vec3 u = normalize(ray);
    float t0 = dot(c, u);
    vec3 closest = c - t0 * u;
    float h = dot(closest, closest);
    float dist = sqrt(h);
    if (dist >= r) return 0.0;
    float w = sqrt((r - dist) * (r + dist));
    float to_t = 1.0 / -u.z;               // distance along -z -> ray parameter
    float a = clamp(u_near * to_t - t0, -w, w);
    float b = clamp(zs * to_t - t0, -w, w);
    if (b <= a) return 0.0;
    chord = b - a;
    return u_tau * max((b - a) - chord_integral(h, a, b) / r, 0.0);
#else
    vec2 q = ray.xy * zc;                  // the ray's point in the centre's depth plane
    float d = length(q - c.xy);
    if (d >= r) return 0.0;
    float w = sqrt((r - d) * (r + d));
    float profile = u_tau * (1.0 - d / r);
#if defined(OPACITY_PLANAR) || defined(OPACITY_SOFT)
    if (zc < u_near) return 0.0;           // the flat billboard is clipped by the near plane
#ifdef OPACITY_PLANAR
    if (zs < zc) return 0.0;               // the depth test of a flat billboard
#endif
    chord = 2.0 * w;
    return profile * 2.0 * w;
#else
    float ds = max(0.0, clamp(zs - zc, -w, w) - clamp(u_near - zc, -w, w));
    chord = ds;
    return profile * ds;
#endif
#endif
}

#ifdef HAS_DETAIL
float detail_sample(vec3 c, float r, vec3 ray)
{
    vec2 q = ray.xy * (-c.z);
    vec2 local = (q - c.xy) / (2.0 * r) + 0.5;   // 0..1 across the particle
    vec3 uvw = vec3(v_detail.xy + local * u_detail_window, v_detail.z + u_time);
    return detail_fetch(u_detail, uvw).r;
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

#ifdef MEDIUM_SCATTERS
// 1 + g^2 - 2 g cos, written (1-|g|)^2 + 2|g| (1 - sign(g) cos): no cancellation at the peak
float phase_base(float cos_theta, float g)
{
    float a = abs(g), s = g < 0.0 ? -cos_theta : cos_theta;
    return (1.0 - a) * (1.0 - a) + 2.0 * a * (1.0 - s);
}

mediump float phase(float cos_theta)
{
#ifdef PHASE_ANALYTIC
    // Cornette-Shanks, cos_theta between the light's travel and the way to the eye
    float g = u_g, gg = g * g;
    float denom = max(phase_base(cos_theta, g), 1e-6);
    return 3.0 * (1.0 - gg) * (1.0 + cos_theta * cos_theta) /
           (25.132741229 * (2.0 + gg) * denom * sqrt(denom));
#else
    // The table's coordinate (sbfx_phase_coordinate): ln of the base for a peaked function,
    // cos itself for a nearly flat one; then the two entries around it, interpolated here.
    float s = u_phase_warp.x * cos_theta;
    float t = u_phase_warp.z > 0.0 ? log(u_phase_warp.y + u_phase_warp.z * (1.0 - s)) * u_phase_warp.w + u_phase_shift.x
                                   : 0.5 * s + 0.5;
    float pos = clamp(t, 0.0, 1.0) * u_phase_shift.y;
    float i = min(floor(pos), u_phase_shift.y - 1.0);
    float a = texelFetch(u_phase_lut, ivec2(int(i), u_phase_row), 0).r;
    float b = texelFetch(u_phase_lut, ivec2(int(i) + 1, u_phase_row), 0).r;
    return mix(a, b, pos - i);
#endif
}

// Single scattering of every light toward the eye at point p; the 4π (folded into the colours
// by the CPU) makes a light of colour E scattered isotropically give back E. Point lights fall off as 1/d², no closer than 0.5 m
// (a flash inside the particle stays finite).
mediump vec3 in_scattered(vec3 ray, vec3 p)
{
    vec3 to_eye = -normalize(ray);
    mediump vec3 sum = u_ambient;
    for (int i = 0; i < LIGHT_SLOTS; i++) {
        if (i >= u_light_count) break;
        vec4 l = u_light_vector[i];
        vec3 travel = l.xyz;
        float falloff = 1.0;
        if (l.w > 0.5) {
            vec3 d = p - l.xyz;
            float d2 = max(dot(d, d), 0.25);
            travel = d * inversesqrt(d2);
            falloff = 1.0 / d2;
        }
        sum += u_light_color[i] * (falloff * phase(dot(travel, to_eye)));
    }
    return sum;
}
#endif

#if defined(FIRE_LIGHT) && !defined(LIGHTING_LIT)
// The fire's light (src/fire_light.h, sbfx_fire_scatter_instance): the phase model evaluated at
// the centre on the CPU; across the particle (its centre's depth plane) the first-order change of
// 1/d² from the fire, so smoke above a fireball glows from below. Zero without live fire. In
// mediump, like the light it adds to (the gradient is at most 1 / radius: never negative).
mediump vec3 fire_scattered(vec3 ray, vec3 c)
{
    mediump vec2 e = ray.xy * (-c.z) - c.xy;
    return v_fire * (1.0 + dot(e, v_fire_gradient));
}
#endif

#ifdef LIGHTING_LIT
// The lit-smoke seed, mirrored by src/lit_ref.c (see there for the texture space). The view
// matrix is the tangent basis of these screen-aligned particles: tangent = view x, bitangent =
// view y, normal = view +z (toward the eye), so a normal-map texel is already a view-space normal.
#ifdef LIT_SHADOW
// Transmittance toward the key light: midpoint samples of the slab density max(0, h - 2|z|)
// over one diameter (1 in texture units, the longest chord of the particle's sphere, which holds
// all of the slab) from the front surface, n = nMin + (N.V)(nMax - nMin) steps (the seed's eq.
// 5.2.5, rounded half up). tau_2r = extinction x diameter. Stops once the optical depth passes
// 20 (transmittance < 2e-9: nothing left to see, the rest is cost).
float lit_shadow(vec3 start, vec3 l, float layer, float lod, float n_dot_v, float tau_2r)
{
    float n = floor(u_steps.x + clamp(n_dot_v, 0.0, 1.0) * u_steps.y);
    if (n < 0.5) return 1.0;
    float dt = 1.0 / n, w = tau_2r * dt, sum = 0.0;
    vec3 step = dt * l, p = start + 0.5 * step;
    for (int k = 0; k < MAX_STEPS; k++) {
        if (float(k) >= n) break;
        sum += max(filtered_array_lod(u_smoke, vec3(p.xy, layer), lod).w - 2.0 * abs(p.z), 0.0);
        if (w * sum > 20.0) break;
        p += step;
    }
    return exp(-w * sum);
}
#endif

// albedo is applied by the caller: B (ambient + (1 - dampening) sum_i E_i F_i (wrap_i + back_i)
// S_i), wrap_i = max(0, N.L/(1+w) + w/(1+w)) (N the filtered normal 2 rgb - 1 as it is, not
// renormalised), back_i = translucency x map x max(0, -V.L) with V the particle's centre toward
// the eye (the seed prints min(0, E.L) x map, which would darken smoke lit from behind; its
// magnitude brightens the thin rim of backlit smoke and adds nothing for a light in front). The
// key light, the frame's first (the scene's first light), is lit at the relief's front surface
// p (direction and falloff F_0 = 1/max(d², 1/4) per pixel; one at p itself has no direction,
// only the wrap's bias lights it) and self-shadowed (S_0, the march). The others (S_i = 1) are
// seen from the particle's centre: direction, falloff and back-light per particle
// (particle.vert), the wrap per pixel.
// With FIRE_LIGHT the fire's light at the particle's centre (isotropic for lit media: no phase
// function) joins the lights' sum, per particle like the fill lights. It rides in v_lit and
// v_view's free components: that keeps 32 registers on both Malis (a vec3 varying of its own
// took the G52 to 64, the per-pixel gradient both), at 9.29 G52 / 3.00 G610 cycles against the
// lit variant's 9.29 / 2.48 (docs/gpus.md; the G610's varying unit bounds it). The fire is
// gathered per particle without a direction, so it lights the relief the way a light wrapped
// all around it would: through the brightness map, not the normals, unshadowed, with the
// lights' dampening (ref/lit_ref.c, sbfx_lit_fire_radiance).
vec3 lit_scattered(vec3 ray, vec3 c, float r, float tau_scale)
{
    vec2 q = ray.xy * (-c.z);
    vec2 st = (q - c.xy) / (2.0 * r) + 0.5;
    float layer = v_lit.x, lod = v_lit.y;
    vec4 a = filtered_array_lod(u_smoke, vec3(st, layer), lod);   // normal * 0.5 + 0.5, height
    vec2 maps = filtered_array_lod(u_smoke, vec3(st, layer + 1.0), lod).xy;   // brightness, translucency
    vec3 wn = a.xyz * (2.0 * u_wrap.x) - u_wrap.x;     // N / (1 + w)
    float translucency = u_translucency * maps.y;
    vec3 sum = vec3(0.0);
#if LIGHT_SLOTS > 1
    for (int i = 1; i < LIT_SLOTS; i++) {
        if (i >= u_light_count) break;
        vec4 f = v_fill[i - 1];
        sum += u_light_color[i] * (f.w * max(dot(wn, f.xyz) + u_wrap.y, 0.0) + translucency * v_fill_back[i - 1]);
    }
#endif
    if (u_light_count > 0) {
        vec4 lv = u_light_vector[0];
        bool point = lv.w > 0.5;
        vec3 d = point ? lv.xyz - vec3(q, c.z + r * a.w) : -lv.xyz;
        float s = inversesqrt(max(dot(d, d), 1e-24));
        vec3 l = d * s;
        float key = (point ? min(s * s, 4.0) : 1.0) *
                    (max(dot(wn, l) + u_wrap.y, 0.0) + translucency * max(-dot(v_view.xyz, l), 0.0));
#ifdef LIT_SHADOW
        key *= lit_shadow(vec3(st, 0.5 * a.w), l, layer, lod, dot(wn, v_view.xyz) * u_wrap.z, u_tau * tau_scale * 2.0 * r);
#endif
        sum += u_light_color[0] * key;
    }
#ifdef FIRE_LIGHT
    sum += vec3(v_lit.zw, v_view.w);   // the fire's light at the centre, like the fill lights
#endif
    return maps.x * (u_ambient + u_direct * sum);
}
#endif

// -expm1(-x) = 1 - e^-x, accurate for small x too
float expm1_safe(float x)
{
    return abs(x) < 1e-3 ? x * (1.0 + 0.5 * x) : exp(x) - 1.0;
}

#ifdef MEDIUM_EMITS
// Normalised linear sRGB of the black body (luminance 1 at desc.blackbody_max_kelvin); 0 at
// T <= 0. Hotter than 1e7 K the colour no longer changes (Y/T is constant to 1e-5).
vec3 blackbody(float kelvin)
{
    if (!(kelvin > 0.0)) return vec3(0.0);
    float t = min(kelvin, 1e7);
#ifdef BLACKBODY_ANALYTIC
    // Planck x CIE 1931 per band (λ in µm, C2 = hc/k = 14387.77 µm K), like the table's rows.
    vec3 rgb = vec3(0.0);
    for (int i = 0; i < MAX_BANDS; i++) {
        if (i >= u_cmf_count) break;
        float lambda = u_cmf_band[i];
        float x = 14387.77 / (lambda * t);
        if (x > 80.0) continue;                   // e^-x underflows: no light in this band
        float l2 = lambda * lambda;
        rgb += u_cmf_rgb[i] * (exp(-x) / (-expm1_safe(-x) * l2 * l2 * lambda));
    }
    return max(rgb, vec3(0.0));                   // out of gamut: clipped like the table
#else
    // Entries uniform in 1/T, interpolated here (and carried on along the end cells outside the
    // table: Wien's law for ln(Y/T) below it), the clip to the gamut after interpolation.
    float pos = (1.0 / t - u_blackbody_map.x) * u_blackbody_map.y;
    float i = clamp(floor(pos), 0.0, u_blackbody_map.z), f = pos - i;
    vec4 a = texelFetch(u_blackbody, ivec2(int(i), 0), 0);
    vec4 b = texelFetch(u_blackbody, ivec2(int(i) + 1, 0), 0);
    return max(mix(a.rgb, b.rgb, f) * (exp(mix(a.w, b.w, f)) * t), vec3(0.0));
#endif
}

mediump vec3 emitted(float kelvin)
{
    return min(blackbody(kelvin) * u_emission_scale, vec3(RADIANCE_CEILING));
}
#endif

// 1 - exp(-x) without losing the small values to cancellation.
float opacity_from_depth(float x)
{
    return x < 1e-3 ? x * (1.0 - 0.5 * x) : 1.0 - exp(-x);
}

#ifdef TABLE_PROBE
uniform vec2 u_probe;            // kelvin, cos theta
void main()
{
    vec3 rgb = vec3(0.0);
    float p = 0.0;
#ifdef MEDIUM_EMITS
    rgb = blackbody(u_probe.x);
#endif
#ifdef MEDIUM_SCATTERS
    p = phase(u_probe.y);
#endif
    o_color = vec4(rgb, p);
}
#else
void main()
{
#ifdef OPACITY_FLOOR
    o_color = vec4(0.01, 0.01, 0.01, 0.05);   // the cheapest fragment that still blends
#ifdef HAS_DISTORTION_TARGET
    o_distortion = vec4(0.0);
#endif
#ifdef HAS_MOTION_TARGET
    o_velocity = vec4(0.0);
#endif
    return;
#endif
    vec3 c = v_center_radius.xyz;
    float r = v_center_radius.w;
    vec2 ndc = gl_FragCoord.xy / u_target_size * 2.0 - 1.0;
    vec3 ray = vec3((ndc + u_projection.zw) / u_projection.xy, -1.0);
    float e = texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r;
    float zs = e > 0.0 ? u_near / e : 1e30;   // no surface: nothing clips the ray
    float intensity = v_detail.w;

    float tau_scale = 1.0;
    float detail = 0.5;
#ifdef HAS_DETAIL
    detail = detail_sample(c, r, ray);
#if defined(MEDIUM_SCATTERS) || defined(MEDIUM_EMITS)
    tau_scale = detail_density_scale(detail, intensity, u_detail_strength);
#endif
#ifdef MEDIUM_EMITS
    detail = detail_fire_temperature(detail, particle_rho(c, r, ray), intensity, u_detail_strength);
#endif
#endif
    tau_scale *= intensity;
    float chord;
    float depth = optical_depth(c, r, ray, zs, chord) * tau_scale;
    float alpha = opacity_from_depth(depth);   // what emits (and scatters)
    float coverage = alpha;                    // what absorbs: the same, but for fire's soot
#ifdef MEDIUM_EMITS
    float cooled = 1.0 - u_temperature.z * (1.0 - intensity);
    float glow = 1.0;                          // the share of the opacity that glows
#ifdef HAS_DETAIL   // soot is part of the detail's look: strength 0 (or no detail) has none
    glow = fire_glow_share(detail, intensity, u_detail_strength);
    float soot = u_detail_strength * fire_soot(detail, cooled, intensity);
    coverage = opacity_from_depth(depth * (1.0 + u_temperature.w * (1.0 - glow)) +
                                  soot * u_tau * tau_scale * (chord * chord / (2.0 * r)));
#endif
#endif
#ifdef OPACITY_SOFT
    // RTR's soft particle: the flat billboard's alpha faded by the depth left behind it.
    float fade = soft_fade((zs + c.z) / (u_soft_scale > 0.0 ? u_soft_scale : r));
    alpha *= fade;
    coverage *= fade;
#endif
    mediump vec3 light = vec3(0.0);
    float shade = 1.0;
#if defined(MEDIUM_SCATTERS) && defined(HAS_DETAIL) && !defined(LIGHTING_LIT)
    shade = detail_light_scale(detail, u_detail_strength);   // lit smoke shades by its own maps
#endif
    mediump vec3 fire = vec3(0.0);
#if defined(FIRE_LIGHT) && !defined(LIGHTING_LIT)   // lit media add it in lit_scattered
    fire = fire_scattered(ray, c);
#endif
#if defined(MEDIUM_SCATTERS) && defined(LIGHT_PER_PARTICLE)
    light += u_albedo_color * (shade * (v_light + fire));
#elif defined(MEDIUM_SCATTERS) && defined(LIGHTING_LIT)
    light += u_albedo_color * lit_scattered(ray, c, r, tau_scale);
#elif defined(MEDIUM_SCATTERS)
    light += u_albedo_color * (shade * (in_scattered(ray, c) + fire));
#endif
#ifdef MEDIUM_EMITS
    light += emitted((u_temperature.x + u_temperature.y * detail) * cooled) * glow;
#endif
#ifdef MEDIUM_HEAT
    // Heat neither absorbs nor lights: it adds a screen offset, two decorrelated detail
    // samples shaped by the particle's opacity profile (zero where the sphere is clipped). The
    // shimmer is the detail's turbulence, so it scales with the detail strength like every
    // medium's perturbation: 0 leaves the picture behind the heat as it was (docs/look.md).
#ifdef HAS_DETAIL
    vec2 noise = u_detail_strength * (vec2(detail, detail_sample(c + vec3(0.37, 0.61, 0.0) * r, r, ray)) - 0.5);
#else
    vec2 noise = v_detail.xy - 0.5;   // without the volume: one random direction per particle
#endif
    o_color = vec4(0.0);
#ifdef HAS_DISTORTION_TARGET
    o_distortion = vec4(2.0 * u_heat_strength * alpha * noise, 0.0, 0.0);
#endif
#ifdef HAS_MOTION_TARGET
    o_velocity = vec4(0.0);
#endif
#else
    o_color = vec4(light * alpha, coverage);
#ifdef HAS_DISTORTION_TARGET
    o_distortion = vec4(0.0, 0.0, 0.0, coverage);   // shimmer behind this particle is covered
#endif
#ifdef HAS_MOTION_TARGET
    o_velocity = vec4(v_velocity * coverage, -c.z * coverage, coverage);
#endif
#endif
}
#endif
