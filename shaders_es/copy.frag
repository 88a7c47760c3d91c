#version 300 es
// Copies a full-resolution texture to the bound framebuffer (history -> host framebuffer).
precision highp float;
precision highp sampler2D;

uniform sampler2D u_source;

out vec4 o_color;

void main()
{
    o_color = texelFetch(u_source, ivec2(gl_FragCoord.xy), 0);
}
