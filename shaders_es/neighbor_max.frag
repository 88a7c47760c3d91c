#version 300 es
// Velocity blur, step 3: the longest tile velocity among the 3x3 neighbouring tiles, so blur
// from a fast object reaches into the tiles next to it; beside it (z) the shortest velocity's
// squared length among them (tile_max.frag's z): whether the neighbourhood moves as one.
precision highp float;
precision highp sampler2D;

uniform sampler2D u_tiles;
uniform ivec2 u_tiles_size;
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
    vec2 best = vec2(0.0);
    float best_len = -1.0, shortest = 1e30;
    for (int j = -1; j <= 1; j++)
        for (int i = -1; i <= 1; i++) {
            vec4 t = texelFetch(u_tiles, clamp(p + ivec2(i, j), ivec2(0), u_tiles_size - 1), 0);
            vec2 v = decode(t);
            float len = dot(v, v);
            if (len > best_len) { best = v; best_len = len; }
            shortest = min(shortest, t.z);   // stored as tile_max.frag stored it
        }
    o_velocity = encode ? vec4(best / (2.0 * u_max_radius) + 0.5, shortest, 1.0) : vec4(best, shortest, 1.0);
}
