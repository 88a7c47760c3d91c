#version 300 es
// Motion blur, the seed's version: the new frame fades into a history of the previous ones.
// u_keep = exp(-dt / persistence), so the look does not depend on the frame rate.
precision highp float;
precision highp sampler2D;

uniform sampler2D u_current;
uniform sampler2D u_history;
uniform float u_keep;

out vec4 o_color;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 current = texelFetch(u_current, p, 0);
    vec4 history = texelFetch(u_history, p, 0);
    o_color = vec4(mix(current.rgb, history.rgb, u_keep), 1.0);
}
