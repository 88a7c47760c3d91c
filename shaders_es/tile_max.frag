#version 300 es
// Velocity blur, step 2: the longest velocity in each tile x tile block.
precision highp float;
precision highp sampler2D;

uniform sampler2D u_velocity;
uniform int u_tile;
uniform ivec2 u_size;
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
    ivec2 base = ivec2(gl_FragCoord.xy) * u_tile;
    vec2 best = vec2(0.0);
    float best_len = -1.0;
    for (int j = 0; j < 32; j++) {
        if (j >= u_tile) break;
        for (int i = 0; i < 32; i++) {
            if (i >= u_tile) break;
            ivec2 q = min(base + ivec2(i, j), u_size - 1);
            vec2 v = decode(texelFetch(u_velocity, q, 0));
            float len = dot(v, v);
            if (len > best_len) { best = v; best_len = len; }
        }
    }
    o_velocity = encode ? vec4(best / (2.0 * u_max_radius) + 0.5, 0.0, 1.0) : vec4(best, 0.0, 1.0);
}
