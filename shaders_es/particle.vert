#version 300 es
// Spherical billboard: each instance is a screen-aligned quad emitted directly as the
// screen-space bounding rectangle of its sphere at clip z = 0, w = 1. The near plane can never
// clip it (the seed places the quad at the sphere's far point for the same reason), and the
// fragment shader rebuilds the view ray from gl_FragCoord, so nothing needs interpolating.
precision highp float;

layout(location = 0) in vec4 a_center_radius; // view-space centre, radius
layout(location = 1) in vec4 a_detail;        // detail window u, v, time offset; intensity
#ifdef LIGHT_PER_PARTICLE
layout(location = 3) in vec4 a_light;           // in-scattered light at the centre (CPU)
flat out vec3 v_light;
#endif
#ifdef HAS_MOTION_TARGET
flat out vec2 v_velocity;                       // screen motion of the centre, full-res pixels
#endif
#ifdef HAS_PARTICLE_MOTION
layout(location = 2) in vec4 a_previous_center; // view-space centre one frame ago
uniform vec2 u_full_size;
#endif

uniform vec4 u_projection;  // projection[0], projection[5], projection[8], projection[9]
uniform float u_near;
uniform vec2 u_pixel;       // size of one target pixel in NDC units

flat out vec4 v_center_radius;
flat out vec4 v_detail;

// Range of slope x / (-z) over a sphere seen from the origin (tangent lines in the x-z plane).
vec2 slope_range(float cx, float zc, float r)
{
    float denom = (zc - r) * (zc + r);
    float root = r * sqrt(max(cx * cx + denom, 0.0));
    return vec2(cx * zc - root, cx * zc + root) / denom;
}

bool finite4(vec4 v)
{
    return !any(isnan(v)) && !any(isinf(v));
}

void main()
{
    v_center_radius = a_center_radius;
    v_detail = a_detail;
#ifdef LIGHT_PER_PARTICLE
    v_light = a_light.rgb;
#endif
#ifdef HAS_MOTION_TARGET
    v_velocity = vec2(0.0);
#endif
#ifdef HAS_PARTICLE_MOTION
    vec3 p0 = a_previous_center.xyz, p1 = a_center_radius.xyz;
    bool visible = p0.z < 0.0 && p1.z < 0.0 && finite4(a_previous_center);
    vec2 ndc1 = p1.xy / -p1.z * u_projection.xy - u_projection.zw;
    vec2 ndc0 = p0.xy / -p0.z * u_projection.xy - u_projection.zw;
    v_velocity = visible ? (ndc1 - ndc0) * 0.5 * u_full_size : vec2(0.0);
#endif
    vec3 c = a_center_radius.xyz;
    float r = a_center_radius.w;
    float zc = -c.z;
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));

    // Invalid particles (the CPU side skips them already) and spheres wholly behind the near
    // plane collapse to a point outside the view volume: no fragment.
    if (!finite4(a_center_radius) || !finite4(a_detail) || !(r > 0.0) || zc + r <= u_near) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        return;
    }
    vec4 rect = vec4(-1.0, -1.0, 1.0, 1.0);
    if (zc - r > u_near) {
        vec2 sx = slope_range(c.x, zc, r);
        vec2 sy = slope_range(c.y, zc, r);
        rect = vec4(sx.x, sy.x, sx.y, sy.y) * u_projection.xyxy - u_projection.zwzw;
        rect += vec4(-u_pixel, u_pixel);
        rect = clamp(rect, -1.0, 1.0);
    }
    gl_Position = vec4(mix(rect.xy, rect.zw, corner), 0.0, 1.0);
}
