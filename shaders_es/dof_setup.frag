#version 300 es
// Depth of field, step 1 (RTR 12.4): at the blur resolution, split the image by the signed
// circle of confusion into a far field (colour, far radius) and a near field (colour
// premultiplied by its coverage, coverage), so the near field can later blur over its own
// edges onto whatever is behind it.
//   CoC from the artist's ranges: full near blur at u_near.x, sharp from u_near.y to u_far.x,
//   full far blur at u_far.y; radius in full-resolution pixels, at most u_max_radius.
//   DOF_SCALE  the scene's blur resolution divisor, set at load (src/post.c): the loops the
//              compilers unroll are as long as the block
precision highp float;
precision highp sampler2D;

#ifndef DOF_SCALE
#define DOF_SCALE 4                // the largest scale; the loops stop at u_scale
#endif
uniform sampler2D u_color;         // full resolution
uniform sampler2D u_scene_depth;   // full resolution window depth
uniform int u_scale;               // blur resolution divisor
uniform ivec2 u_size;              // full resolution
uniform vec4 u_depth_model;       // window depth -> distance (view_distance)
uniform vec2 u_near;               // [full blur, sharp] distances
uniform vec2 u_far;                // [sharp, full blur] distances
// Particles are not in the depth buffer: where they cover the scene, their own (coverage-
// weighted) distance sets the CoC, or a sharp explosion over a far sky would be blurred.
uniform bool u_particles_drawn;
uniform sampler2D u_particle_motion; // low-res: premultiplied velocity, distance; transmittance
uniform float u_divisor;
uniform ivec2 u_particle_size;

layout(location = 0) out vec4 o_far;   // rgb, far CoC in [0,1]
layout(location = 1) out vec4 o_near;  // rgb * coverage, coverage (= near CoC in [0,1])

// Window depth -> view distance (src/projection.c): the matrix's own depth row, solved around
// the far end so nothing cancels; the clear value means no surface.
float view_distance(float d)
{
    if (d == u_depth_model.y) return 1e30;
    return u_depth_model.w / (u_depth_model.x * (d - u_depth_model.y) + u_depth_model.z);
}

float view_depth(ivec2 q) { return view_distance(texelFetch(u_scene_depth, q, 0).r); }

// Signed CoC in [-1, 1]: negative in the near field, positive in the far field.
float signed_coc(float z)
{
    if (z < u_near.y) return -clamp((u_near.y - z) / max(u_near.y - u_near.x, 1e-4), 0.0, 1.0);
    if (z > u_far.x) return clamp((z - u_far.x) / max(u_far.y - u_far.x, 1e-4), 0.0, 1.0);
    return 0.0;
}

void main()
{
    ivec2 base = ivec2(gl_FragCoord.xy) * u_scale;
    vec3 far_sum = vec3(0.0), near_sum = vec3(0.0);
    float far_coc = 0.0, near_coc = 0.0, n = 0.0;
    for (int j = 0; j < DOF_SCALE; j++) {
        if (j >= u_scale) break;
        for (int i = 0; i < DOF_SCALE; i++) {
            if (i >= u_scale) break;
            ivec2 q = min(base + ivec2(i, j), u_size - 1);
            vec3 c = texelFetch(u_color, q, 0).rgb;
            float coc = signed_coc(view_depth(q));
            if (u_particles_drawn) {
                ivec2 t = clamp(ivec2(vec2(q) / u_divisor), ivec2(0), u_particle_size - 1);
                vec4 m = texelFetch(u_particle_motion, t, 0);
                float coverage = clamp(1.0 - m.a, 0.0, 1.0);
                if (coverage > 1e-3) coc = mix(coc, signed_coc(m.b / coverage), coverage);
            }
            far_sum += c;
            far_coc += max(coc, 0.0);
            near_sum += c * max(-coc, 0.0);
            near_coc = max(near_coc, -coc);   // the near field's coverage spreads, never shrinks
            n += 1.0;
        }
    }
    o_far = vec4(far_sum / n, far_coc / n);
    o_near = vec4(near_coc > 0.0 ? near_sum / n : vec3(0.0), near_coc);
}
