#version 300 es
// Velocity blur, step 4: which blocks of BLOCK x BLOCK tiles the gather can change, and how. A
// pixel's gather returns it unchanged where its tile's neighbour max is under half a pixel
// (motion_blur.frag), so a block whose tiles are all under it is still: 0 here, and
// blur_tiles.vert draws a copy over it (the same test on the same texels: the two never
// disagree). A block whose moving tiles' neighbourhoods all move as one (their shortest velocity
// within UNIFORM pixels of their longest) gets the gather's fast path: 0.5; any other, 1.
//   BLOCK  tiles per block side, set at load (src/render/post.c): the loop the compilers unroll
precision highp float;
precision highp sampler2D;

#ifndef BLOCK
#define BLOCK 4
#endif
uniform sampler2D u_neighbor_max;
uniform ivec2 u_tiles_size;      // of u_neighbor_max
uniform float u_max_radius;
#ifdef ENCODE_UNORM
const bool encode = true;
#else
const bool encode = false;
#endif
const float UNIFORM = 0.5;       // pixels

out vec4 o_class;

vec2 decode(vec4 t) { return encode ? (t.xy - 0.5) * 2.0 * u_max_radius : t.xy; }

void main()
{
    ivec2 base = ivec2(gl_FragCoord.xy) * BLOCK;
    bool moving = false, varied = false;
    for (int j = 0; j < BLOCK; j++)
        for (int i = 0; i < BLOCK; i++) {
            vec4 t = texelFetch(u_neighbor_max, min(base + ivec2(i, j), u_tiles_size - 1), 0);
            float longest = length(decode(t)), shortest = sqrt(encode ? t.z * u_max_radius * u_max_radius : t.z);
            bool tile_moves = !(longest < 0.5);
            moving = moving || tile_moves;
            varied = varied || (tile_moves && !(longest - shortest < UNIFORM));
        }
    o_class = vec4(varied ? 1.0 : moving ? 0.5 : 0.0, 0.0, 0.0, 1.0);
}
