#version 300 es
// Depth of field, step 2: one direction of a separable gather blur of both fields at the blur
// resolution. The far field gathers only samples whose own CoC reaches this texel (a sharp
// object does not bleed into the blurred background); the near field is blurred uniformly with
// its coverage so it spreads over its own silhouette.
//   PAIRS   float fields (post.c): neighbouring taps are fetched in pairs, one bilinear fetch at
//           the edge they share (their mean; the fields are LINEAR and CLAMP_TO_EDGE, which
//           repeats the edge texel as clamped taps do): the near field's exactly, the far
//           field's weighed for the mean's CoC (exact where the two share it). RGBA8 fields,
//           whose filtering rounds to 8 bits, take every tap.
//   RADIUS  the scene's radius in blur-resolution texels, ceil(u_max_radius) at most 16, set at
//           load (src/render/post.c): the loops the compilers unroll, so that their static
//           estimates count every tap (docs/gpus.md)
precision highp float;
precision highp sampler2D;

uniform sampler2D u_far_field;
uniform sampler2D u_near_field;
uniform ivec2 u_direction;         // (1,0) then (0,1)
uniform ivec2 u_low_size;
uniform float u_max_radius;        // in blur-resolution texels

#ifndef RADIUS
#define RADIUS 3                   // post.c sets it: ceil(u_max_radius)
#endif

layout(location = 0) out vec4 o_far;
layout(location = 1) out vec4 o_near;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 far_sum = texelFetch(u_far_field, p, 0), near_sum = vec4(0.0);
    float far_weight = 1.0;
#ifdef PAIRS
    vec2 texel = 1.0 / vec2(u_low_size), along = vec2(u_direction);
    // the far field's taps j and j + 1 on each side (the last alone): their mean, by the two's
    // weights for its CoC
    for (int j = 1; j <= RADIUS; j += 2) {
        bool pair = j < RADIUS;
        for (int side = -1; side <= 1; side += 2) {
            vec4 f = pair ? textureLod(u_far_field, (vec2(p) + 0.5 + along * float(side) * (float(j) + 0.5)) * texel, 0.0)
                          : texelFetch(u_far_field, clamp(p + u_direction * side * j, ivec2(0), u_low_size - 1), 0);
            float reach = f.a * u_max_radius;            // the blur radius of the taps' mean
            float w = clamp(reach - float(j) + 1.0, 0.0, 1.0) + (pair ? clamp(reach - float(j), 0.0, 1.0) : 0.0);
            far_sum += f * w;
            far_weight += w;
        }
    }
    // the near field's taps k and k + 1 from -RADIUS on (the last alone)
    for (int k = -RADIUS; k < RADIUS; k += 2)
        near_sum += 2.0 * textureLod(u_near_field, (vec2(p) + 0.5 + along * (float(k) + 0.5)) * texel, 0.0);
    near_sum += texelFetch(u_near_field, clamp(p + u_direction * RADIUS, ivec2(0), u_low_size - 1), 0);
#else
    near_sum = texelFetch(u_near_field, p, 0);
    for (int k = -RADIUS; k <= RADIUS; k++) {
        if (k == 0) continue;
        ivec2 q = clamp(p + u_direction * k, ivec2(0), u_low_size - 1);
        vec4 f = texelFetch(u_far_field, q, 0);
        float reach = f.a * u_max_radius;            // this sample's blur radius
        float w = clamp(reach - float(abs(k)) + 1.0, 0.0, 1.0);
        far_sum += f * w;
        far_weight += w;
        near_sum += texelFetch(u_near_field, q, 0);
    }
#endif
    o_far = far_sum / far_weight;
    o_near = near_sum / float(2 * RADIUS + 1);
}
