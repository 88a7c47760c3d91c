#version 300 es
// Opaque depth -> particle-target resolution. Each low-res texel keeps the closest opaque
// surface of its block, stored linearly as distance / far so the particle pass can read view
// distances at full float precision (a depth attachment is renderable in core ES 3.0,
// a float colour target is not).
precision highp float;
precision highp sampler2D;

uniform sampler2D u_scene_depth;   // host depth texture, window-space depth in [0,1]
uniform int u_divisor;
uniform ivec2 u_full_size;
uniform vec2 u_depth_params;       // projection[10], projection[14]
uniform float u_far;

float view_distance(float window_depth)
{
    float ndc = window_depth * 2.0 - 1.0;
    return u_depth_params.y / (ndc + u_depth_params.x);
}

void main()
{
    ivec2 base = ivec2(gl_FragCoord.xy) * u_divisor;
    float closest = 1.0;
    for (int j = 0; j < u_divisor; j++) {
        for (int i = 0; i < u_divisor; i++) {
            ivec2 q = min(base + ivec2(i, j), u_full_size - 1);
            closest = min(closest, texelFetch(u_scene_depth, q, 0).r);
        }
    }
    float distance = closest >= 1.0 ? u_far : view_distance(closest);
    gl_FragDepth = clamp(distance / u_far, 0.0, 1.0);
}
