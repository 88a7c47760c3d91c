#version 300 es
// Spherical billboard: each instance is a screen-aligned octagon emitted directly at clip z = 0,
// w = 1: the screen-space bounding rectangle of its sphere with the corners cut along the
// diagonals, where the sphere's outline leaves about a sixth of the rectangle empty (no ray
// there meets the sphere: those fragments would add nothing). Eight vertices, a strip. The near
// plane can never clip it (the seed places the quad at the sphere's far point for the same
// reason), and the fragment shader rebuilds the view ray from gl_FragCoord, so nothing needs
// interpolating.
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
uniform bool u_octagon;     // cut the rectangle's corners (false: the rectangle, as before issue 33)

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

// The sphere's range of u = x + y and v = x - y in the target's pixels (x = (ndc + 1) / u_pixel),
// as ndc: each the slope range along the view-space direction the diagonal is, times its length,
// widened by a pixel of x and one of y (the rectangle's pixel each way).
vec4 diagonal_cuts(vec3 c, float zc, float r)
{
    vec2 a = u_projection.xy / u_pixel;     // pixels per unit of slope, x and y
    float len = length(a);
    vec2 du = a / len, dv = vec2(du.x, -du.y);
    vec2 su = slope_range(dot(du, c.xy), zc, r) * len;
    vec2 sv = slope_range(dot(dv, c.xy), zc, r) * len;
    // in pixels the shift is (1 - p8) / u_pixel.x, (1 - p9) / u_pixel.y
    vec2 shift = (1.0 - u_projection.zw) / u_pixel;
    return vec4(su.x + shift.x + shift.y - 2.0, sv.x + shift.x - shift.y - 2.0,
                su.y + shift.x + shift.y + 2.0, sv.y + shift.x - shift.y + 2.0);
}

// Vertex i of the strip over the rectangle (ndc) with its corners cut by u >= cut.x, v >= cut.y,
// u <= cut.z, v <= cut.w (pixels): the octagon's vertices, two on each edge, each kept on its
// edge and in order along it, so that the strip (0 1 7 2 6 3 5 4) covers a convex polygon
// once, never less than the rectangle within the cuts.
vec2 octagon_vertex(vec4 rect, vec4 cut, int i)
{
    vec4 px = (rect + 1.0) / u_pixel.xyxy;  // x0, y0, x1, y1 in pixels
    float b0 = clamp(cut.x - px.y, px.x, px.z), b1 = max(clamp(cut.w + px.y, px.x, px.z), b0); // bottom: x
    float r0 = clamp(px.z - cut.w, px.y, px.w), r1 = max(clamp(cut.z - px.z, px.y, px.w), r0); // right: y
    float t0 = clamp(cut.z - px.w, px.x, px.z), t1 = min(clamp(cut.y + px.w, px.x, px.z), t0); // top: x
    float l0 = clamp(px.x - cut.y, px.y, px.w), l1 = min(clamp(cut.x - px.x, px.y, px.w), l0); // left: y
    vec2 v;
    // strip order 0 1 7 2 6 3 5 4 of the polygon b0 b1 r0 r1 t0 t1 l0 l1
    if (i == 0) v = vec2(b0, px.y);
    else if (i == 1) v = vec2(b1, px.y);
    else if (i == 2) v = vec2(px.x, l1);
    else if (i == 3) v = vec2(px.z, r0);
    else if (i == 4) v = vec2(px.x, l0);
    else if (i == 5) v = vec2(px.z, r1);
    else if (i == 6) v = vec2(t1, px.w);
    else v = vec2(t0, px.w);
    return v * u_pixel - 1.0;
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
    // Invalid particles (the CPU side skips them already) and spheres wholly behind the near
    // plane collapse to a point outside the view volume: no fragment.
    if (!finite4(a_center_radius) || !finite4(a_detail) || !(r > 0.0) || zc + r <= u_near) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        return;
    }
    vec4 rect = vec4(-1.0, -1.0, 1.0, 1.0);
    vec4 cut = vec4(-1e30, -1e30, 1e30, 1e30);   // no cut: a sphere at the near plane fills the screen
    if (zc - r > u_near) {
        vec2 sx = slope_range(c.x, zc, r);
        vec2 sy = slope_range(c.y, zc, r);
        rect = vec4(sx.x, sy.x, sx.y, sy.y) * u_projection.xyxy - u_projection.zwzw;
        rect = vec4(min(rect.xy, rect.zw), max(rect.xy, rect.zw)); // a mirrored projection's too
        rect += vec4(-u_pixel, u_pixel);
        rect = clamp(rect, -1.0, 1.0);
        if (u_octagon) cut = diagonal_cuts(c, zc, r);
    }
    gl_Position = vec4(octagon_vertex(rect, cut, gl_VertexID), 0.0, 1.0);
}
