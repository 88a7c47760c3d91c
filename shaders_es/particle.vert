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
#ifdef FIRE_LIGHT
layout(location = 4) in vec4 a_fire;            // fire light in-scattered at the centre (CPU)
layout(location = 5) in vec4 a_fire_gradient;   // its relative change per metre across the particle
#ifndef LIGHTING_LIT   // lit media take it at the centre, in v_lit and v_view
flat out mediump vec3 v_fire;
flat out mediump vec2 v_fire_gradient;
#endif
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
#ifdef LIGHTING_LIT
uniform float u_smoke_size;     // texels across level 0
uniform float u_smoke_variants;
#ifdef FIRE_LIGHT   // the fire's light at the centre rides in the free components: no varying more
flat out vec4 v_lit;            // layer, level of detail (below), the fire's light's red and green
flat out vec4 v_view;           // the direction below, the fire's light's blue
#else
flat out vec2 v_lit;            // the particle's smoke texture layer and level of detail
flat out vec3 v_view;           // unit, from the particle's centre toward the eye
#endif
#define MAX_LIGHTS 8             // as particle.frag's
#ifndef LIGHT_SLOTS
#define LIGHT_SLOTS MAX_LIGHTS
#endif
#define MAX_LIT_LIGHTS 4
#define LIT_SLOTS (LIGHT_SLOTS < MAX_LIT_LIGHTS ? LIGHT_SLOTS : MAX_LIT_LIGHTS)
#if LIGHT_SLOTS > 1
uniform vec4 u_light_vector[MAX_LIGHTS]; // view space: w = 0 direction of travel, w = 1 position
flat out vec4 v_fill[LIT_SLOTS - 1];     // lights 1.. from the centre: unit direction, falloff
flat out float v_fill_back[LIT_SLOTS - 1]; // ... and falloff x max(0, -V.L)
#endif
#endif

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
#if defined(FIRE_LIGHT) && !defined(LIGHTING_LIT)
    v_fire = a_fire.rgb;
    v_fire_gradient = a_fire_gradient.xy;
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
#ifdef LIGHTING_LIT
    // layer 2v of its variant v = floor(u * variants); one level of detail per particle, log2 of
    // texels per target pixel at the centre's depth (explicit: the march's fetches sit in a loop
    // where derivatives are undefined)
    float texels = u_smoke_size * (u_pixel.x / u_projection.x) * zc / (2.0 * r);
    vec3 view = -normalize(c);
    vec2 lit = vec2(2.0 * min(floor(clamp(a_detail.x, 0.0, 1.0) * u_smoke_variants), u_smoke_variants - 1.0),
                    texels > 1.0 ? min(log2(texels), 30.0) : 0.0);
#ifdef FIRE_LIGHT
    v_view = vec4(view, a_fire.b);
    v_lit = vec4(lit, a_fire.rg);
#else
    v_view = view;
    v_lit = lit;
#endif
#if LIGHT_SLOTS > 1
    // the lights after the key light, seen from the centre: a point light at the centre lights
    // it from the eye's side (+z); falloff 1/max(d², 1/4)
    for (int i = 1; i < LIT_SLOTS; i++) {
        vec4 lv = u_light_vector[i];
        vec3 d = lv.w > 0.5 ? lv.xyz - c : -lv.xyz;
        float d2 = dot(d, d);
        vec3 l = d2 > 1e-12 ? d * inversesqrt(d2) : vec3(0.0, 0.0, 1.0);
        float falloff = lv.w > 0.5 ? 1.0 / max(d2, 0.25) : 1.0;
        v_fill[i - 1] = vec4(l, falloff);
        v_fill_back[i - 1] = falloff * max(-dot(view, l), 0.0);
    }
#endif
#endif
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
