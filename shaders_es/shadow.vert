#version 300 es
// Transmittance shadow map (RTR 13.8.1): each particle is a quad around its sphere, seen from
// the light along parallel rays (an orthographic projection of the light's view space).
precision highp float;

layout(location = 0) in vec4 a_center_radius; // light-view-space centre, radius
layout(location = 1) in float a_tau;          // extinction at the centre x intensity

uniform mat4 u_matrix;                        // light view -> the map's clip space (xy; z = 0)
uniform vec2 u_depth;                         // light view -z -> the map's depth in [0, 1]: scale, offset

out vec2 v_offset;                            // from the centre, in the light's image plane
flat out vec2 v_radius_tau;
flat out vec2 v_depth;                        // the centre's map depth, map depth per metre

void main()
{
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    float r = a_center_radius.w;
    v_offset = corner * r;
    v_radius_tau = vec2(r, a_tau);
    v_depth = vec2(u_depth.x * -a_center_radius.z + u_depth.y, u_depth.x);
    gl_Position = u_matrix * vec4(a_center_radius.xyz + vec3(v_offset, 0.0), 1.0);
}
