#version 300 es
// Depth of field, step 2: one direction of a separable gather blur of both fields at the blur
// resolution. The far field gathers only samples whose own CoC reaches this texel (a sharp
// object does not bleed into the blurred background); the near field is blurred uniformly with
// its coverage so it spreads over its own silhouette.
//   RADIUS  the scene's radius in blur-resolution texels (at most 16), set at load
//           (src/render/post.c): the loop the compilers unroll, so that their static estimates
//           count every tap (docs/gpus.md)
precision highp float;
precision highp sampler2D;

uniform sampler2D u_far_field;
uniform sampler2D u_near_field;
uniform ivec2 u_direction;         // (1,0) then (0,1)
uniform ivec2 u_low_size;
uniform float u_max_radius;        // in blur-resolution texels

#ifndef RADIUS
#define RADIUS 16                  // the largest radius; taps past u_max_radius are skipped
#endif

layout(location = 0) out vec4 o_far;
layout(location = 1) out vec4 o_near;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    int radius = min(int(ceil(u_max_radius)), RADIUS);
    vec4 far_sum = vec4(0.0), near_sum = vec4(0.0);
    float far_weight = 0.0, near_weight = 0.0;
    for (int k = -RADIUS; k <= RADIUS; k++) {
        if (k < -radius || k > radius) continue;   // only the taps needed (none with RADIUS set)
        ivec2 q = clamp(p + u_direction * k, ivec2(0), u_low_size - 1);
        vec4 f = texelFetch(u_far_field, q, 0);
        float reach = f.a * u_max_radius;            // this sample's blur radius
        float w = k == 0 ? 1.0 : clamp(reach - float(abs(k)) + 1.0, 0.0, 1.0);
        far_sum += f * w;
        far_weight += w;
        near_sum += texelFetch(u_near_field, q, 0);
        near_weight += 1.0;
    }
    o_far = far_sum / far_weight;
    o_near = near_sum / near_weight;
}
