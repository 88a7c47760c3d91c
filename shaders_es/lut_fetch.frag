#version 300 es
// Diagnostic pass (probe and tests): fetches the black-body and phase tables exactly as the
// particle shader does and writes (rgb, phase) to a 1x1 float target.
precision highp float;
precision highp sampler2D;

uniform sampler2D u_blackbody;
uniform float u_blackbody_size;
uniform float u_max_kelvin;
uniform float u_kelvin;
uniform sampler2D u_phase_lut;
uniform vec2 u_phase_lut_size;
uniform float u_cos_theta;
uniform float u_g;

out vec4 o_color;

void main()
{
    float x = clamp(u_kelvin / u_max_kelvin, 0.0, 1.0);
    float s = (x * (u_blackbody_size - 1.0) + 0.5) / u_blackbody_size;
    vec3 rgb = texture(u_blackbody, vec2(s, 0.5)).rgb;
    vec2 lut = (vec2(u_cos_theta * 0.5 + 0.5, u_g / (2.0 * 0.99) + 0.5) * (u_phase_lut_size - 1.0) + 0.5)
               / u_phase_lut_size;
    o_color = vec4(rgb, texture(u_phase_lut, lut).r);
}
