#version 300 es
// Depth of field, step 1 (RTR 12.4): at the blur resolution, split the image by the signed
// circle of confusion into a far field (colour, far radius) and a near field (colour
// premultiplied by its coverage, coverage), so the near field can later blur over its own
// edges onto whatever is behind it.
//   CoC from the artist's ranges: full near blur at u_near.x, sharp from u_near.y to u_far.x,
//   full far blur at u_far.y; radius in full-resolution pixels, at most u_max_radius.
//   DOF_SCALE  the scene's blur resolution divisor, set at load (src/render/post.c): the loops the
//              compilers unroll are as long as the block, and the block's size is a constant
//              (without it: blocks of u_scale, loops as long as the largest, 4)
//   NO_PARTICLES  drawn outside the particles' tiles (src/render/tiles.c) where each block lies in
//              one tile (post.c): their target is clear under the block, and main() gives what
//              it gives with no particles, without their fetches
precision highp float;
precision highp sampler2D;
#ifndef FILTER_BITS   // SBFX_FILTER_BITS (shaders_es/filtered.frag): else the texture unit filters
#define filtered_2d(s, uv) textureLod(s, uv, 0.0)
#endif

#ifdef DOF_SCALE
#define SCALE DOF_SCALE
#else
#define DOF_SCALE 4                // the largest scale; the loops stop at u_scale
#define SCALE u_scale
#endif
uniform sampler2D u_color;         // full resolution, LINEAR (block_mean)
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

// Window depth -> view distance (src/render/projection.c): the matrix's own depth row, solved around
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
#ifdef NO_PARTICLES
    return vec2(0.0);
#endif
    if (!u_particles_drawn) return vec2(0.0);
    vec4 m = textureLod(u_particle_motion, centre / (u_divisor * vec2(u_particle_size)), 0.0);
    float coverage = clamp(1.0 - m.a, 0.0, 1.0);
    return vec2(coverage, coverage > 1e-3 ? m.b / coverage : 0.0);
}

// The block's mean of t (LINEAR): one bilinear fetch per 2 x 2 of the block, at its centre, weighed
// by its pixels (CLAMP_TO_EDGE: a block past the image's edge repeats the edge, as a fetch per
// pixel would).
vec3 block_mean(sampler2D t, vec2 base, vec2 texel)
{
    vec3 sum = vec3(0.0);
    for (int j = 0; j < DOF_SCALE; j += 2) {
        if (j >= SCALE) break;
        for (int i = 0; i < DOF_SCALE; i += 2) {
            if (i >= SCALE) break;
            vec2 size = min(vec2(float(SCALE - i), float(SCALE - j)), 2.0);
            sum += size.x * size.y * filtered_2d(t, (base + vec2(i, j) + 0.5 * (size - 1.0)) * texel).rgb;
        }
    }
    return sum / float(SCALE * SCALE);
}

// The block's depths are read by coordinate at their centres (NEAREST, CLAMP_TO_EDGE: clamped
// past the image's edge); its colours as means (block_mean).
void main()
{
    vec2 base = floor(gl_FragCoord.xy) * float(SCALE) + 0.5;   // the first pixel's centre
    vec2 texel = 1.0 / vec2(u_size);
    vec2 ramps = 1.0 / max(vec2(u_near.y - u_near.x, u_far.y - u_far.x), 1e-4);
    vec2 centre = base + 0.5 * float(SCALE - 1);
    vec2 cover = particle_cover(centre);
    float particle_coc = signed_coc(cover.y, ramps);
    float far_coc = 0.0, near_weight = 0.0, near_coc = 0.0;
    for (int j = 0; j < DOF_SCALE; j++) {
        if (j >= SCALE) break;
        for (int i = 0; i < DOF_SCALE; i++) {
            if (i >= SCALE) break;
            float coc = signed_coc(view_distance(textureLod(u_scene_depth, (base + vec2(i, j)) * texel, 0.0).r), ramps);
            if (cover.x > 1e-3) coc = mix(coc, particle_coc, cover.x);
            far_coc += max(coc, 0.0);
            near_weight += max(-coc, 0.0);
            near_coc = max(near_coc, -coc);   // the near field's coverage spreads, never shrinks
        }
    }
    float n = float(SCALE * SCALE);
    far_coc /= n;
    vec3 color = block_mean(u_color, base, texel);
    // What the far field holds: the image where the particles are as far as the far field (keep
    // 1), the scene behind them where they are in focus or near (keep 0), between by their far
    // CoC; dof_composite.frag takes the same mix at full resolution. The scene's CoC where
    // particles in focus cover it: the block's, which their coverage c scaled by 1 - c (their
    // own CoC is 0), scaled back; unknown (0) where they are opaque.
    float keep = cover.x > 1e-3 ? max(particle_coc, 0.0) : 1.0;
    o_far = vec4(color, far_coc);
#ifndef NO_PARTICLES
    if (keep < 1.0) {   // the scene's fetches only where particles cover the block
        float scene_coc = cover.x < 0.999 ? min(far_coc / (1.0 - cover.x), 1.0) : 0.0;
        o_far = mix(vec4(block_mean(u_scene_color, base, texel), scene_coc), o_far, keep);
    }
#endif
    // The near field: the block's colour by its mean near CoC (the mean of the product where the
    // block's pixels share a CoC, as they do but at a near object's edge)
    o_near = vec4(near_coc > 0.0 ? color * (near_weight / n) : vec3(0.0), near_coc);
}
