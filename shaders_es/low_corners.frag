#version 300 es
// The nearest-depth upsampling's four depths, gathered once per frame at low resolution: texel
// (i, j) holds the low-res depth target's near / distance (0: no surface) at (i - 1, j - 1),
// (i, j - 1), (i - 1, j) and (i, j), each clamped to the target, so the composite reads the four
// texels around a pixel in one fetch instead of four. The target is one texel larger than the
// low-res one in each direction (a pixel's lower-left texel may be -1) and RGBA32F: a copy of
// the DEPTH_COMPONENT32F values, bit for bit.
precision highp float;
precision highp sampler2D;

uniform sampler2D u_low_depth;
uniform ivec2 u_low_size;

out vec4 o_corners;

float inverse_distance(ivec2 q) { return texelFetch(u_low_depth, clamp(q, ivec2(0), u_low_size - 1), 0).r; }

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    o_corners = vec4(inverse_distance(p - 1), inverse_distance(p + ivec2(0, -1)),
                     inverse_distance(p + ivec2(-1, 0)), inverse_distance(p));
}
