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
// The scene without the particles (the host's colour, LINEAR): the far field takes it instead of
// the image where particles are sharper than the far field (see main), so in-focus particles
// never reach the blurred field and the sky behind them blurs on its own.
uniform sampler2D u_scene_color;

layout(location = 0) out vec4 o_far;   // rgb, far CoC in [0,1]
layout(location = 1) out vec4 o_near;  // rgb * coverage, coverage (= near CoC in [0,1])

// Window depth -> view distance (src/projection.c): the matrix's own depth row, solved around
// the far end so nothing cancels; the clear value means no surface.
float view_distance(float d)
{
    if (d == u_depth_model.y) return 1e30;
    return u_depth_model.w / (u_depth_model.x * (d - u_depth_model.y) + u_depth_model.z);
}

// Signed CoC in [-1, 1]: negative in the near field, positive in the far field. ramps: the
// reciprocals of the near and far ranges' lengths (once per fragment, not per texel).
float signed_coc(float z, vec2 ramps)
{
    if (z < u_near.y) return -clamp((u_near.y - z) * ramps.x, 0.0, 1.0);
    return clamp((z - u_far.x) * ramps.y, 0.0, 1.0);
}

// The particles' coverage and distance where they cover the block: the particle texel under
// the block's centre. That is the texel of every pixel of the block whenever the particle
// target's divisor is a multiple of the block's size (4 or 8 with blocks of 2 or 4); with a
// finer particle target the block takes its centre's texel (one fetch per block, not per pixel).
vec2 particle_cover(vec2 centre)
{
    if (!u_particles_drawn) return vec2(0.0);
    vec4 m = textureLod(u_particle_motion, centre / (u_divisor * vec2(u_particle_size)), 0.0);
    float coverage = clamp(1.0 - m.a, 0.0, 1.0);
    return vec2(coverage, coverage > 1e-3 ? m.b / coverage : 0.0);
}

// The block's texels are read by coordinate at their centres: the samplers (NEAREST, or the
// host colour's LINEAR exactly at a centre; CLAMP_TO_EDGE) clamp a block past the image's edge.
void main()
{
    vec2 base = floor(gl_FragCoord.xy) * float(u_scale) + 0.5;   // the first pixel's centre
    vec2 texel = 1.0 / vec2(u_size);
    vec2 ramps = 1.0 / max(vec2(u_near.y - u_near.x, u_far.y - u_far.x), 1e-4);
    vec2 centre = base + 0.5 * float(u_scale - 1);
    vec2 cover = particle_cover(centre);
    float particle_coc = signed_coc(cover.y, ramps);
    vec3 far_sum = vec3(0.0), near_sum = vec3(0.0);
    float far_coc = 0.0, near_coc = 0.0, scene_far = 0.0, n = 0.0;
    for (int j = 0; j < DOF_SCALE; j++) {
        if (j >= u_scale) break;
        for (int i = 0; i < DOF_SCALE; i++) {
            if (i >= u_scale) break;
            vec2 q = base + vec2(i, j);
            vec3 c = textureLod(u_color, q * texel, 0.0).rgb;
            float coc = signed_coc(view_distance(textureLod(u_scene_depth, q * texel, 0.0).r), ramps);
            scene_far += max(coc, 0.0);
            if (cover.x > 1e-3) coc = mix(coc, particle_coc, cover.x);
            far_sum += c;
            far_coc += max(coc, 0.0);
            near_sum += c * max(-coc, 0.0);
            near_coc = max(near_coc, -coc);   // the near field's coverage spreads, never shrinks
            n += 1.0;
        }
    }
    // What the far field holds: the image where the particles are as far as the far field (keep
    // 1), the scene behind them where they are in focus or near (keep 0), between by their far
    // CoC; its CoC likewise (the scene's, or the block's). dof_composite.frag takes the same mix
    // at full resolution. The scene: the block's mean for blocks of 1 and 2 (one bilinear
    // fetch at the block's centre), its centre 2 x 2 for larger ones.
    float keep = cover.x > 1e-3 ? max(particle_coc, 0.0) : 1.0;
    vec3 scene = textureLod(u_scene_color, centre * texel, 0.0).rgb;
    o_far = vec4(mix(scene, far_sum / n, keep), mix(scene_far, far_coc, keep) / n);
    o_near = vec4(near_coc > 0.0 ? near_sum / n : vec3(0.0), near_coc);
}
