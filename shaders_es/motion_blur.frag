#version 300 es
// Velocity blur, step 4 (McGuire, Hennessy, Bukowski, Osman 2012; RTR 12.5): gather along the
// neighbourhood's dominant velocity; each sample's weight says whether it can blur over this
// pixel (cones of its own and this pixel's velocity) and which is in front (soft depth
// compare). A half-pixel jitter per pixel hides the sample pattern. Below half a pixel of
// motion the pixel is returned unchanged.
//   FAST     the blocks whose neighbourhoods move as one (tile_class.frag: every velocity within
//            half a pixel of the longest's length): every sample is taken to move as the
//            neighbour max and to lie at this pixel's depth, so its weight follows from its
//            distance alone, without its velocity and depth (Jimenez's fast path, CoD: AW)
//   SAMPLES  the scene's sample count, set at load (src/render/post.c): a loop the compilers can
//            unroll (Mesa does up to 7 samples of the full path, 15 of the fast one; the boards'
//            table prices the rest per sample: docs/gpus.md, "The post chain")
precision highp float;
precision highp sampler2D;

uniform sampler2D u_color;
uniform sampler2D u_velocity;
uniform sampler2D u_neighbor_max;
uniform sampler2D u_scene_depth;
uniform ivec2 u_size;
uniform int u_tile;
uniform int u_samples;
uniform float u_max_radius;
uniform vec4 u_depth_model;       // window depth -> distance (view_distance)
#ifdef ENCODE_UNORM
const bool encode = true;
#else
const bool encode = false;
#endif

out vec4 o_color;

#ifndef SAMPLES
#define SAMPLES 63                 // the most samples; the loop stops at u_samples
#endif
const float SOFT_Z = 0.1;          // metres over which depth ordering fades

vec2 decode(vec4 t) { return encode ? (t.xy - 0.5) * 2.0 * u_max_radius : t.xy; }

// Window depth -> view distance (src/render/projection.c): the matrix's own depth row, solved around
// the far end so nothing cancels; the clear value means no surface.
float view_distance(float d)
{
    if (d == u_depth_model.y) return 1e30;
    return u_depth_model.w / (u_depth_model.x * (d - u_depth_model.y) + u_depth_model.z);
}

// The view distance at q, whose velocity texel is t: a float velocity target holds it in z
// (velocity.frag, dof_composite.frag: at most 6e4), one fetch a sample for both; RGBA8 does not.
#ifdef ENCODE_UNORM
float view_depth(ivec2 q, vec4 t) { return view_distance(texelFetch(u_scene_depth, q, 0).r); }
#else
float view_depth(ivec2 q, vec4 t) { return t.z; }
#endif

// The cone and the cylinder of a sample at `distance` from this pixel, with velocity of length
// speed (>= 0.5), on x = distance / speed: 1 - x, and 1 - smoothstep(0.95 speed, 1.05 speed, distance).
float cone(float x) { return clamp(1.0 - x, 0.0, 1.0); }
float cylinder(float x) { return 1.0 - smoothstep(0.95, 1.05, x); }

float soft_depth_compare(float za, float zb) { return clamp(1.0 - (za - zb) / SOFT_Z, 0.0, 1.0); }

// Interleaved gradient noise in [-0.5, 0.5): a cheap per-pixel jitter.
float jitter(vec2 p) { return fract(52.9829189 * fract(dot(p, vec2(0.06711056, 0.00583715)))) - 0.5; }

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 center = texelFetch(u_color, p, 0);
    // the tile under this pixel: floor((p + 0.5) / tile) = p / tile, without an integer division
    vec2 vmax = decode(texelFetch(u_neighbor_max, ivec2(gl_FragCoord.xy / float(u_tile)), 0));
    if (length(vmax) < 0.5) {
        o_color = center;
        return;
    }
#ifdef FAST
    float inv_speed = 1.0 / max(length(vmax), 0.5);
    float weight = inv_speed;
    vec3 sum = center.rgb * weight;
    float j = jitter(gl_FragCoord.xy);
    int middle = (u_samples - 1) >> 1;
    for (int i = 0; i < SAMPLES; i++) {
        if (i >= u_samples) break;
        if (i == middle) continue;
        float t = mix(-1.0, 1.0, (float(i) + j + 1.0) / float(u_samples + 1));
        ivec2 y = clamp(ivec2(floor(vec2(p) + 0.5 + vmax * t)), ivec2(0), u_size - 1);
        float x = length(vec2(y - p)) * inv_speed;
        float a = 2.0 * cone(x) + 2.0 * cylinder(x) * cylinder(x);   // the full path's, one velocity and depth
        weight += a;
        sum += a * texelFetch(u_color, y, 0).rgb;
    }
    o_color = vec4(sum / weight, 1.0);
#else
    vec4 tc = texelFetch(u_velocity, p, 0);
    vec2 vc = decode(tc);
    float inv_speed_c = 1.0 / max(length(vc), 0.5);
    float zc = view_depth(p, tc);
    float weight = inv_speed_c;
    vec3 sum = center.rgb * weight;
    float j = jitter(gl_FragCoord.xy);
    int middle = (u_samples - 1) >> 1;   // (samples - 1) / 2, the centre sample (this pixel)
    for (int i = 0; i < SAMPLES; i++) {
        if (i >= u_samples) break;
        if (i == middle) continue;
        float t = mix(-1.0, 1.0, (float(i) + j + 1.0) / float(u_samples + 1));
        ivec2 y = clamp(ivec2(floor(vec2(p) + 0.5 + vmax * t)), ivec2(0), u_size - 1);
        float distance = length(vec2(y - p));
        vec4 ty = texelFetch(u_velocity, y, 0);
        vec2 vy = decode(ty);
        float xy = distance / max(length(vy), 0.5), xc = distance * inv_speed_c;
        float zy = view_depth(y, ty);
        // distances grow away from the eye: "front" = the sample is nearer than this pixel
        float front = soft_depth_compare(zy, zc), back = soft_depth_compare(zc, zy);
        float a = front * cone(xy) + back * cone(xc) + cylinder(xy) * cylinder(xc) * 2.0;
        weight += a;
        sum += a * texelFetch(u_color, y, 0).rgb;
    }
    o_color = vec4(sum / weight, 1.0);
#endif
}
