#version 300 es
// Full-resolution composite of the low-res particle target over the host's framebuffer,
// which already holds the opaque scene: the blend computes dst * T + C (GL_ONE, GL_SRC_ALPHA)
// from this pass's output (C, T). Upsampling:
//   UPSAMPLE_BILINEAR       plain bilinear of the four nearest low-res texels;
//   UPSAMPLE_NEAREST_DEPTH  bilinear where the four low-res depths agree with this pixel's
//                           depth, else the texel whose depth is closest (no halos at edges).
// Bilinear is done by hand with texelFetch so RGBA32F targets (not filterable in ES 3.0)
// take the same path as RGBA16F and RGBA8.
//   OWN_SCENE     post effects follow: read the scene colour texture instead of blending over
//                 the host's framebuffer, and write an opaque image
//   HAS_SHIMMER   (with OWN_SCENE) heat particles' screen offsets displace the scene lookup
//   TONE_MAP_NONE | TONE_MAP_HUE_PRESERVING | TONE_MAP_PER_CHANNEL | TONE_MAP_FILMIC   the
//                 particles' light on the display (sbfx_tone_map in sbfx.h; ref/reference_frame.c
//                 mirrors it; docs/look-fire.md)
precision highp float;
precision highp sampler2D;

// mediump: the particle target is read at half precision, which is what an RGBA16F target holds
// and what sanitize() clamps an RGBA32F one to (docs/gpus.md, "Precision"); a Mali keeps two
// such values in a register, which keeps this shader within 32 registers (full occupancy)
uniform mediump sampler2D u_particles; // low-res: premultiplied light, transmittance
uniform sampler2D u_low_depth;    // low-res opaque near / distance (0: no surface)
uniform sampler2D u_scene_depth;  // full-res host depth, window depth
uniform ivec2 u_low_size;
uniform float u_divisor;
uniform vec4 u_depth_model;       // window depth -> distance (view_distance)
uniform float u_near;
uniform float u_depth_threshold;  // relative depth difference that counts as an edge
uniform sampler2D u_scene_color;  // full res, LINEAR filtering for the shimmer offset
uniform bool u_scene_known;       // u_scene_color may be read (given, and not being drawn into)
#ifdef OWN_SCENE
uniform vec2 u_full_size;
#endif
#ifdef HAS_SHIMMER
uniform sampler2D u_distortion;   // low-res: offset of the scene lookup in UV units (rg)
#endif

out vec4 o_color;

const float HALF_MAX = 65504.0;

// Window depth -> view distance (src/projection.c): the matrix's own depth row, solved around
// the far end so nothing cancels; the clear value means no surface.
const float NO_SURFACE = 1e30;
float view_distance(float d)
{
    if (d == u_depth_model.y) return NO_SURFACE;
    return u_depth_model.w / (u_depth_model.x * (d - u_depth_model.y) + u_depth_model.z);
}

// The four low-res texels around a pixel, clamped to the target once: (x0, y0, x1, y1).
ivec4 corners(ivec2 base)
{
    return clamp(ivec4(base, base + 1), ivec4(0), ivec4(u_low_size - 1, u_low_size - 1));
}

float low_distance(ivec2 q)
{
    float e = texelFetch(u_low_depth, q, 0).r;
    return e > 0.0 ? u_near / e : NO_SURFACE;
}

// ---- tone mapping: the particle layer's light (pre-exposed) before it meets the host's picture ----
uniform vec3 u_tone_curve;        // knee, steepness, 1 / ln(1 + steepness x_white) (src/tonemap.c)

// The identity up to the knee, a logarithmic shoulder above it reaching 1 at the white point.
float tone_curve(float v)
{
    float k = u_tone_curve.x;
    if (v <= k) return max(v, 0.0);
    return min(k + (1.0 - k) * log(1.0 + u_tone_curve.y * (v - k) / (1.0 - k)) * u_tone_curve.z, 1.0);
}

#ifdef TONE_MAP_FILMIC
// Filmic, a path to white for emitters (src/tonemap.c, docs/look-fire.md), on q = light / room.
// Light the display can show (every channel of q at most 1) keeps its hue exactly: its largest
// channel goes through the curve and the colour is scaled with it. Brighter light blends, over
// two stops (q from 1 to 4), into the crossover: each channel takes a share of the channels'
// mean (TONE_INSET), goes through the curve, and the share is given back, so light too bright
// for its hue turns orange -> yellow -> white, arriving at white smoothly at 1024.
const float TONE_INSET = 0.06;
float tone_curve_smooth_white(float v)   // tone_curve's shoulder u as k + (1 - k)(2u - u^2)
{
    float k = u_tone_curve.x;
    if (v <= k) return max(v, 0.0);
    float u = min(log(1.0 + u_tone_curve.y * (v - k) / (1.0 - k)) * u_tone_curve.z, 1.0);
    return k + (1.0 - k) * u * (2.0 - u);
}
vec3 tone_filmic(vec3 q)
{
    float peak = max(max(q.r, q.g), q.b);
    if (peak <= u_tone_curve.x) return q;
    vec3 kept = q * (tone_curve_smooth_white(peak) / peak);
    if (peak <= 1.0) return kept;
    vec3 y = (1.0 - TONE_INSET) * q + TONE_INSET * ((q.r + q.g + q.b) / 3.0);
    vec3 z = vec3(tone_curve_smooth_white(y.r), tone_curve_smooth_white(y.g), tone_curve_smooth_white(y.b));
    vec3 crossed = clamp((z - TONE_INSET * ((z.r + z.g + z.b) / 3.0)) / (1.0 - TONE_INSET), 0.0, 1.0);
    return mix(kept, crossed, smoothstep(0.0, 1.0, 0.5 * log2(peak)));
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
    c = room * tone_filmic(c / room);
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

mediump vec4 sanitize(mediump vec4 p)
{
    // A NaN never reaches the screen; Inf is clamped to the largest half.
    if (any(isnan(p))) return vec4(0.0, 0.0, 0.0, 1.0);
    return vec4(clamp(p.rgb, 0.0, HALF_MAX), clamp(p.a, 0.0, 1.0));
}

mediump vec4 fetch(ivec2 q)
{
    return sanitize(texelFetch(u_particles, q, 0));
}

// Weights of the four low-res texels around this pixel (x: base, y: +x, z: +y, w: +x+y).
mediump vec4 bilinear_weights(vec2 f)
{
    return vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
}

#ifdef UPSAMPLE_NEAREST_DEPTH
// Bilinear where the four low-res depths agree with this pixel's, else all weight on the texel
// whose depth is closest.
mediump vec4 nearest_depth_weights(ivec4 c, vec2 f)
{
    float z = view_distance(texelFetch(u_scene_depth, ivec2(gl_FragCoord.xy), 0).r);
    vec4 dz = abs(vec4(low_distance(c.xy), low_distance(c.zy), low_distance(c.xw), low_distance(c.zw)) - z);
    if (!(max(max(dz.x, dz.y), max(dz.z, dz.w)) > u_depth_threshold * z)) return bilinear_weights(f);
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
mediump vec4 upsample(ivec4 c, mediump vec4 w)
{
    mediump vec4 sum = fetch(c.xy) * w.x;
    sum += fetch(c.zy) * w.y;
    sum += fetch(c.xw) * w.z;
    sum += fetch(c.zw) * w.w;
    return sum;
}

void main()
{
    vec2 low = gl_FragCoord.xy / u_divisor - 0.5;
    ivec2 base = ivec2(floor(low));
    vec2 f = low - vec2(base);
    ivec4 c = corners(base);
#ifdef UPSAMPLE_NEAREST_DEPTH
    vec4 result = upsample(c, nearest_depth_weights(c, f));
#else
    vec4 result = upsample(c, bilinear_weights(f));
#endif
#ifdef OWN_SCENE
    vec2 uv = gl_FragCoord.xy / u_full_size;
#ifdef HAS_SHIMMER
    // bilinear, like the particles: nearest low-res offsets would tear the image into blocks
    vec2 d00 = texelFetch(u_distortion, c.xy, 0).rg;
    vec2 d10 = texelFetch(u_distortion, c.zy, 0).rg;
    vec2 d01 = texelFetch(u_distortion, c.xw, 0).rg;
    vec2 d11 = texelFetch(u_distortion, c.zw, 0).rg;
    vec2 offset = mix(mix(d00, d10, f.x), mix(d01, d11, f.x), f.y);
    if (!(abs(offset.x) < 1.0 && abs(offset.y) < 1.0)) offset = vec2(0.0);   // NaN, Inf, absurd
    uv = clamp(uv + offset, 0.5 / u_full_size, 1.0 - 0.5 / u_full_size);
#endif
    vec3 scene = texture(u_scene_color, uv).rgb;
    result = tone_map(result, scene);
    o_color = vec4(scene * result.a + result.rgb, 1.0);
#else
    vec3 dst = u_scene_known ? clamp(texelFetch(u_scene_color, ivec2(gl_FragCoord.xy), 0).rgb, 0.0, 1.0) : vec3(0.0);
    o_color = tone_map(result, dst);
#endif
}
