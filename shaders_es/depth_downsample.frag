#version 300 es
// Opaque depth -> particle-target resolution. Each low-res texel keeps the closest opaque
// surface of its block as near / distance: 0 means no surface (the host's clear value), and the
// encoding needs no far plane and keeps float's relative precision at every distance (a depth
// attachment is renderable in core ES 3.0, a float colour target is not).
// near / distance is a monotone function of window depth, in float too (every step of
// inverse_distance is), so the block's closest surface is its largest (or, where a smaller
// window depth is closer, smallest) window depth, converted once: the same value as the largest
// of the converted ones, for one comparison per texel instead of a conversion.
//   SINGLE_TEXEL  divisor 1: the texel is the pixel (no block, no loop)
precision highp float;
precision highp sampler2D;

uniform sampler2D u_scene_depth;   // host depth texture, window depth in [0,1]
uniform int u_divisor;
uniform ivec2 u_full_size;
uniform vec3 u_near_model;         // near / distance = x (d - y) + z; d = y: no surface (src/render/projection.c)
uniform float u_closer;            // 1: a larger window depth is closer (x / w > 0), else -1

// near / distance of one window depth; linear in d, so nothing cancels (its constants folded on
// the CPU in double: sbfx_near_model_uniform).
float inverse_distance(float d)
{
    if (d == u_near_model.y) return 0.0;
    return clamp(u_near_model.x * (d - u_near_model.y) + u_near_model.z, 0.0, 1.0);
}

void main()
{
#ifdef SINGLE_TEXEL
    // the output's own resolution (mixed resolution's refinement, src/render/refine.c): one texel
    gl_FragDepth = inverse_distance(texelFetch(u_scene_depth, ivec2(gl_FragCoord.xy), 0).r);
    return;
#endif
    ivec2 base = ivec2(gl_FragCoord.xy) * u_divisor;
    float closest = -1e30;   // the closest window depth, times u_closer (negating is exact)
    for (int j = 0; j < u_divisor; j++) {
        for (int i = 0; i < u_divisor; i++) {
            ivec2 q = min(base + ivec2(i, j), u_full_size - 1);
            closest = max(closest, u_closer * texelFetch(u_scene_depth, q, 0).r);
        }
    }
    gl_FragDepth = inverse_distance(u_closer * closest);
}
