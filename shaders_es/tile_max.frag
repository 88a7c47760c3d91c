#version 300 es
// Velocity blur, step 2: the longest velocity in each tile x tile block, separably: first along
// rows (u_direction (1, 0): each fragment of a tiles-wide, full-height target takes the longest
// of `tile` texels of its row), then along the columns of that ((0, 1)). Ties keep the first
// texel in row-major order, as one scan of the block would. A fragment fetches `tile` texels,
// not tile x tile (docs/gpus.md). Beside it (z) the shortest velocity's squared length in the
// block: the rows take it from the velocities, the columns from the rows' z (motion_blur.frag's
// fast path, tile_class.frag). RGBA8 (ENCODE_UNORM) stores it over the tile size squared.
//   TILE  the scene's tile size, set at load (src/render/post.c): the loop the compilers unroll
precision highp float;
precision highp sampler2D;

#ifndef TILE
#define TILE 32                  // the largest tile; the loop stops at u_tile
#endif
uniform sampler2D u_velocity;
uniform int u_tile;
uniform ivec2 u_size;            // of u_velocity
uniform ivec2 u_direction;
uniform float u_max_radius;
#ifdef ENCODE_UNORM
const bool encode = true;
#else
const bool encode = false;
#endif

out vec4 o_velocity;

vec2 decode(vec4 t) { return encode ? (t.xy - 0.5) * 2.0 * u_max_radius : t.xy; }

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 base = p + u_direction * p * (u_tile - 1);   // p x tile along the direction
    vec2 best = vec2(0.0);
    float best_len = -1.0, shortest = 1e30;   // squared lengths
    for (int i = 0; i < TILE; i++) {
        if (i >= u_tile) break;
        ivec2 q = min(base + u_direction * i, u_size - 1);
        vec4 t = texelFetch(u_velocity, q, 0);
        vec2 v = decode(t);
        float len = dot(v, v);
        if (len > best_len) { best = v; best_len = len; }
        shortest = min(shortest, u_direction.y == 1 ? (encode ? t.z * u_max_radius * u_max_radius : t.z) : len);
    }
    o_velocity = encode ? vec4(best / (2.0 * u_max_radius) + 0.5, clamp(shortest / (u_max_radius * u_max_radius), 0.0, 1.0), 1.0)
                        : vec4(best, shortest, 1.0);
}
