#version 300 es
// Velocity blur, step 3: the longest tile velocity among the 3x3 neighbouring tiles, so blur
// from a fast object reaches into the tiles next to it.
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
    float best_len = -1.0;
    for (int j = -1; j <= 1; j++)
        for (int i = -1; i <= 1; i++) {
            vec2 v = decode(texelFetch(u_tiles, clamp(p + ivec2(i, j), ivec2(0), u_tiles_size - 1), 0));
            float len = dot(v, v);
            if (len > best_len) { best = v; best_len = len; }
        }
    o_velocity = encode ? vec4(best / (2.0 * u_max_radius) + 0.5, 0.0, 1.0) : vec4(best, 0.0, 1.0);
}
