#version 300 es
// Full-resolution composite of the low-res particle target over the host's framebuffer,
// which already holds the opaque scene: the blend computes dst * T + C (GL_ONE, GL_SRC_ALPHA)
// from this pass's output (C, T). Upsampling:
//   UPSAMPLE_BILINEAR       plain bilinear of the four nearest low-res texels;
//   UPSAMPLE_NEAREST_DEPTH  bilinear where the four low-res depths agree with this pixel's
//                           depth or all lie beyond the particles, else the texel whose depth is
//                           closest (no halos at edges).
// Bilinear is done by hand (the targets' NEAREST texels) so RGBA32F targets (not filterable in
// ES 3.0) take the same path as RGBA16F and RGBA8.
//   OWN_SCENE     post effects follow: read the scene colour texture instead of blending over
//                 the host's framebuffer, and write an opaque image
//   HAS_SHIMMER   (with OWN_SCENE) heat particles' screen offsets displace the scene lookup
//   TRANSMITTANCE_ALPHA (with OWN_SCENE) the image's alpha is the particles' transmittance, not 1:
//                 depth of field follows and weighs its CoC by it (dof_composite.frag)
//   TONE_MAP_NONE | TONE_MAP_HUE_PRESERVING | TONE_MAP_PER_CHANNEL | TONE_MAP_FILMIC   the
//                 particles' light on the display (sbfx_tone_map in sbfx.h; ref/reference_frame.c
//                 mirrors it; docs/look-fire.md)
//   REFINED       (with UPSAMPLE_NEAREST_DEPTH: mixed resolution, src/render/refine.c) where
//                 the full-resolution refinement holds a pixel (its alpha >= 0) it replaces the
//                 upsampled coarse target
//   SCENE_ONLY    (with OWN_SCENE) the pixels outside the particles' tiles (src/render/tiles.c):
//                 what main() writes where no particle reaches (transmittance 1, no light, no
//                 shimmer offset), the scene read the same way
precision highp float;
precision highp sampler2D;
#ifndef FILTER_BITS   // SBFX_FILTER_BITS (shaders_es/filtered.frag): else the texture unit filters
#define filtered_2d(s, uv) textureLod(s, uv, 0.0)
#endif

// mediump: the particle target is read at half precision, which is what an RGBA16F target holds
// and what sanitize() clamps an RGBA32F one to (docs/gpus.md, "Precision"); a Mali keeps two
// such values in a register, which keeps this shader within 32 registers (full occupancy)
uniform mediump sampler2D u_particles; // low-res: premultiplied light, transmittance
uniform sampler2D u_low_depth;    // low-res opaque near / distance (0: no surface)
uniform sampler2D u_scene_depth;  // full-res host depth, window depth
// Folded on the CPU (render/passes.c), so that no fragment divides by a uniform:
uniform float u_inv_divisor;      // 1 / the target's divisor (a power of 2: exact)
uniform vec2 u_low_texel;         // 1 / the low-res target's size: one texel in UV units
uniform vec3 u_near_model;        // window depth -> near / distance, A (d - d_far) + B (near_over_distance)
uniform float u_depth_threshold;  // relative depth difference that counts as an edge
uniform sampler2D u_scene_color;  // full res, LINEAR filtering for the shimmer offset
uniform bool u_scene_known;       // u_scene_color may be read (given, and not being drawn into)
#ifdef OWN_SCENE
uniform vec2 u_full_texel;        // 1 / the output's size (passes.c)
#endif
#ifdef LOW_CORNERS
uniform sampler2D u_low_corners;  // low-res + 1: the four low-res depths around a texel (low_corners.frag)
uniform vec2 u_corners_texel;     // 1 / its size
#endif
#ifdef REFINED
uniform mediump sampler2D u_refined; // full res: the refined particles; alpha -1 where not refined
#endif
#ifdef HAS_SHIMMER
uniform sampler2D u_distortion;   // low-res RGBA16F, LINEAR: offset of the scene lookup in UV units (rg)
#endif

out vec4 o_color;

const float HALF_MAX = 65504.0;

// Window depth -> near / view distance (src/render/projection.c: the distance is p14 / (scale (d -
// d_far) + offset), solved around the far end so nothing cancels; its reciprocal times near is
// linear in d, A = near scale / p14, B = near offset / p14, folded in double on the CPU), as the
// low-res depths store it. The clear value (no surface) gives B = near / the far plane's distance,
// which the upsampling clamps to the particles' reach like every farther value: the reach is at
// most the far plane's distance (passes.c), so it lands on the reach, as 0 (no surface) does.
float near_over_distance(float d)
{
    return u_near_model.x * (d - u_near_model.y) + u_near_model.z;
}

// The low-res texels are read by texture coordinate (NEAREST, CLAMP_TO_EDGE: the sampler clamps
// a corner off the target to its edge, no integer arithmetic here). Corner k of the four around
// a pixel is at base_uv + offset_k: (0, 0), (t.x, 0), (0, t.y), t, t = one low-res texel.
float low_near_over_distance(vec2 uv)
{
    return textureLod(u_low_depth, uv, 0.0).r;
}

// ---- tone mapping: the particle layer's light (pre-exposed) before it meets the host's picture ----
uniform vec3 u_tone_curve;        // knee, steepness, 1 / ln(1 + steepness x_white) (src/tables/tonemap.c)

// The identity up to the knee, a logarithmic shoulder above it reaching 1 at the white point.
float tone_curve(float v)
{
    float k = u_tone_curve.x;
    if (v <= k) return max(v, 0.0);
    return min(k + (1.0 - k) * log(1.0 + u_tone_curve.y * (v - k) / (1.0 - k)) * u_tone_curve.z, 1.0);
}

#ifdef TONE_MAP_FILMIC
// Filmic, a path to white for emitters (src/tables/tonemap.c, docs/look-fire.md), on q = light / room.
// Light the display can show (every channel of q at most 1) keeps its hue exactly: its largest
// channel goes through the curve and the colour is scaled with it. Brighter light blends, over
// two stops (q from 1 to 4), into the crossover: each channel takes a share of the channels'
// mean (TONE_INSET), goes through the curve, and the share is given back, so light too bright
// for its hue turns orange -> yellow -> white, arriving at white smoothly at 1024.
const float TONE_INSET = 0.06;
uniform vec4 u_tone_filmic;       // steepness / (1 - k), -k steepness / (1 - k), log2(1 + steepness x_white), knee k
uniform vec2 u_tone_shoulder;     // 2 (1 - k) c, (1 - k) c^2 with c = ln 2 / ln(1 + steepness x_white) (render/passes.c)
// tone_curve's shoulder u as k + (1 - k)(2u - u^2), on four values at once (the peak and the
// three channels of the crossover), u = c L with L = log2(1 + x), x = (v - k) steepness / (1 - k):
// k + L (2 (1 - k) c - (1 - k) c^2 L), the constants folded on the CPU. Without a branch: below
// the knee x = max(., 0) = 0 gives L = 0, and min(v, k) is v (v >= 0 here). From the white point
// on, L is held at its value there (u = 1, the shoulder's top: v is not clamped before the log).
vec4 tone_curve_smooth_white(vec4 v)
{
    vec4 x = max(v * u_tone_filmic.x + u_tone_filmic.y, 0.0);
    vec4 L = min(log2(1.0 + x), u_tone_filmic.z);
    return min(v, u_tone_filmic.w) + L * (u_tone_shoulder.x - u_tone_shoulder.y * L);
}
vec3 tone_filmic(vec3 q)
{
    float peak = max(max(q.r, q.g), q.b);
    vec3 y = (1.0 - TONE_INSET) * q + (TONE_INSET / 3.0) * (q.r + q.g + q.b);
    vec4 z = tone_curve_smooth_white(vec4(peak, y));
    // peak 0: q and z.x are 0, and so is the kept colour
    vec3 kept = q * (z.x / max(peak, 1e-30));
    vec3 crossed = clamp(z.yzw * (1.0 / (1.0 - TONE_INSET)) - (TONE_INSET / (3.0 * (1.0 - TONE_INSET))) * (z.y + z.z + z.w), 0.0, 1.0);
    // smoothstep over two stops, of h = log2(peak) / 2 in [0, 1] already: h^2 (3 - 2h) = t^2 (3/4 - t/4), t = 2h
    float t = log2(clamp(peak, 1.0, 4.0));
    return mix(kept, crossed, (t * t) * (0.75 - 0.25 * t));
}
#endif

// The light C is brought within the room the host's picture leaves: over a pixel dst seen through
// transmittance T, dst * T + C stays within [0, 1] when C_k <= room_k = 1 - T dst_k. Hue
// preserving: C scaled by curve(r) / r, r = max_k C_k / room_k, so no channel clips on its own
// and the light keeps its chromaticity; per channel: C_k = room_k curve(C_k / room_k). dst is the
// scene colour when sbfx may read it (u_scene_known), else black (room 1).
vec4 tone_map(vec4 p, vec3 dst)
{
    vec3 c = p.rgb;
#ifndef TONE_MAP_NONE
    vec3 room = max(1.0 - p.a * dst, vec3(1.0 / 1024.0));
#if defined(TONE_MAP_FILMIC)
    c = room * tone_filmic(c * (1.0 / room));
#elif defined(TONE_MAP_PER_CHANNEL)
    c = room * vec3(tone_curve(c.r / room.r), tone_curve(c.g / room.g), tone_curve(c.b / room.b));
#else
    vec3 q = c / room;
    float r = max(max(q.r, q.g), q.b);
    if (r > u_tone_curve.x) c *= tone_curve(r) / r;
#endif
#endif
    return vec4(c, p.a);
}
// ---- end of tone mapping ----

// A texel made finite and in range (docs/gpus.md "Precision"): light clamped to [0, the largest
// half] (Inf), transmittance to [0, 1], and a transmittance that is not a number (or below 0) is
// 1: the scene shows through. A NaN light is caught once, on the weighted sum (sanitize, in
// upsample()): a zero weight times a clamped texel is 0, so where min and max pass a NaN on, it
// reaches the sum, which is then transparent; where they return the number, the light is 0.
mediump vec4 clamp_texel(mediump vec4 p)
{
    mediump vec3 light = clamp(p.rgb, vec3(0.0), vec3(HALF_MAX));
    return vec4(light, p.a >= 0.0 ? min(p.a, 1.0) : 1.0);
}

// A NaN never reaches the screen: one test for the four channels, on their sum (NaN when any is;
// non-negative values only overflow to +Inf, never to NaN).
mediump vec4 sanitize(mediump vec4 p)
{
    mediump vec2 pair = p.rg + p.ba;
    return isnan(pair.x + pair.y) ? vec4(0.0, 0.0, 0.0, 1.0) : p;
}

mediump vec4 fetch(vec2 uv)
{
    return clamp_texel(textureLod(u_particles, uv, 0.0));
}

// Weights of the four low-res texels around this pixel (x: base, y: +x, z: +y, w: +x+y).
mediump vec4 bilinear_weights(vec2 f)
{
    return vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
}

#ifdef UPSAMPLE_NEAREST_DEPTH
uniform float u_near_over_far;    // near / the particles' reach: the farthest distance a drawn particle
                                  // reaches (render/frame.c), at most the far plane's (passes.c)

// Bilinear where the four low-res depths agree with this pixel's, else all weight on the texel
// whose depth is closest. Depths are compared up to the particles' reach: surfaces that all lie
// behind every particle hide none of them, so the four texels hold the same particles (a far
// floor meeting the sky at the horizon is no edge), and a surface just inside the reach hides
// only the few particles in front of it.
// In near / distance (e), without a division: with E this pixel's and e_k a texel's, both
// clamped at the reach (no surface, 0, lands on it), the distances differ by
// near |E - e_k| / (E e_k), which exceeds the threshold times this pixel's distance (near / E)
// exactly when |E - e_k| > threshold e_k; the closest texel is the least |E - e_k| / e_k.
mediump vec4 nearest_depth_weights(vec2 base, vec2 uv, vec2 t, vec2 f)
{
    float E = max(near_over_distance(texelFetch(u_scene_depth, ivec2(gl_FragCoord.xy), 0).r), u_near_over_far);
    // the four low-res depths as near / distance (0: no surface)
#ifdef LOW_CORNERS
    // one fetch: the corners texel of base is base + 1 (the texture starts at texel -1)
    vec4 e = textureLod(u_low_corners, (base + 1.5) * u_corners_texel, 0.0);
#else
    vec4 e = vec4(low_near_over_distance(uv), low_near_over_distance(uv + vec2(t.x, 0.0)),
                  low_near_over_distance(uv + vec2(0.0, t.y)), low_near_over_distance(uv + t));
#endif
    e = max(e, vec4(u_near_over_far));
    vec4 r = abs(E - e);
    vec4 over = r - u_depth_threshold * e;
    if (!(max(max(over.x, over.y), max(over.z, over.w)) > 0.0)) return bilinear_weights(f);
    vec4 dz = r / e;   // each texel's distance difference over this pixel's distance
    mediump vec4 w = vec4(1.0, 0.0, 0.0, 0.0);
    float best = dz.x;
    if (dz.y < best) { best = dz.y; w = vec4(0.0, 1.0, 0.0, 0.0); }
    if (dz.z < best) { best = dz.z; w = vec4(0.0, 0.0, 1.0, 0.0); }
    if (dz.w < best) { w = vec4(0.0, 0.0, 0.0, 1.0); }
    return w;
}
#endif

// The weighted sum of the four texels, one at a time: one running sum stays live, not four
// texels (a sanitized texel is finite, so a zero weight adds exactly nothing).
mediump vec4 upsample(vec2 uv, vec2 t, mediump vec4 w)
{
    mediump vec4 sum = fetch(uv) * w.x;
    sum += fetch(uv + vec2(t.x, 0.0)) * w.y;
    sum += fetch(uv + vec2(0.0, t.y)) * w.z;
    sum += fetch(uv + t) * w.w;
    return sanitize(sum);
}

#ifdef OWN_SCENE
// The scene behind this pixel, displaced by the shimmer's offset (UV units).
vec3 scene_behind(vec2 offset)
{
    vec2 scene_uv = gl_FragCoord.xy * u_full_texel;
#ifdef HAS_SHIMMER
    scene_uv = clamp(scene_uv + offset, 0.5 * u_full_texel, 1.0 - 0.5 * u_full_texel);
#endif
    return filtered_2d(u_scene_color, scene_uv).rgb;
}
#endif

#ifdef SCENE_ONLY
void main()
{
    o_color = vec4(scene_behind(vec2(0.0)), 1.0);
}
#else
void main()
{
    vec2 low = gl_FragCoord.xy * u_inv_divisor - 0.5;
    vec2 base = floor(low);
    vec2 f = low - base;
    vec2 t = u_low_texel;
    vec2 uv = (base + 0.5) * t;   // the base texel's centre
#if defined(REFINED)
    mediump vec4 fine = texelFetch(u_refined, ivec2(gl_FragCoord.xy), 0);
    vec4 result;
    if (fine.a >= 0.0) result = sanitize(clamp_texel(fine));   // refined: the coarse texels are not read
    else result = upsample(uv, t, nearest_depth_weights(base, uv, t, f));
#elif defined(UPSAMPLE_NEAREST_DEPTH)
    vec4 result = upsample(uv, t, nearest_depth_weights(base, uv, t, f));
#else
    vec4 result = upsample(uv, t, bilinear_weights(f));
#endif
#ifdef OWN_SCENE
    vec2 offset = vec2(0.0);
#ifdef HAS_SHIMMER
    // bilinear, like the particles (nearest low-res offsets would tear the image into blocks), by
    // the sampler: the offsets are RGBA16F (filterable) and read through a LINEAR sampler
    offset = filtered_2d(u_distortion, uv + f * t).rg;
    if (!(abs(offset.x) < 1.0 && abs(offset.y) < 1.0)) offset = vec2(0.0);   // NaN, Inf, absurd
#endif
    vec3 scene = scene_behind(offset);
    result = tone_map(result, scene);
#ifdef TRANSMITTANCE_ALPHA
    o_color = vec4(scene * result.a + result.rgb, result.a);
#else
    o_color = vec4(scene * result.a + result.rgb, 1.0);
#endif
#else
    vec3 dst = u_scene_known ? clamp(texelFetch(u_scene_color, ivec2(gl_FragCoord.xy), 0).rgb, 0.0, 1.0) : vec3(0.0);
    o_color = tone_map(result, dst);
#endif
}
#endif
