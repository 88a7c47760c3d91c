#version 300 es
// Depth of field, step 3: the sharp full-resolution image, the blurred far field mixed in by
// this pixel's far CoC, and the blurred near field laid over everything by its coverage.
precision highp float;
precision highp sampler2D;

uniform sampler2D u_color;
uniform sampler2D u_far_field;     // blurred
uniform sampler2D u_near_field;    // blurred
uniform sampler2D u_scene_depth;
uniform vec4 u_depth_model;       // window depth -> distance (view_distance)
uniform vec2 u_far;
uniform float u_scale;
uniform ivec2 u_low_size;

out vec4 o_color;

// Window depth -> view distance (src/projection.c): the matrix's own depth row, solved around
// the far end so nothing cancels; the clear value means no surface.
float view_distance(float d)
{
    if (d == u_depth_model.y) return 1e30;
    return u_depth_model.w / (u_depth_model.x * (d - u_depth_model.y) + u_depth_model.z);
}

vec4 bilinear(sampler2D t, vec2 low)
{
    vec2 x = low - 0.5;
    ivec2 b = ivec2(floor(x));
    vec2 f = x - vec2(b);
    ivec2 hi = u_low_size - 1;
    vec4 a = texelFetch(t, clamp(b, ivec2(0), hi), 0), c = texelFetch(t, clamp(b + ivec2(1, 0), ivec2(0), hi), 0);
    vec4 d = texelFetch(t, clamp(b + ivec2(0, 1), ivec2(0), hi), 0), e = texelFetch(t, clamp(b + ivec2(1, 1), ivec2(0), hi), 0);
    return mix(mix(a, c, f.x), mix(d, e, f.x), f.y);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 sharp = texelFetch(u_color, p, 0).rgb;
    float z = view_distance(texelFetch(u_scene_depth, p, 0).r);
    float far_coc = clamp((z - u_far.x) / max(u_far.y - u_far.x, 1e-4), 0.0, 1.0);
    vec2 low = gl_FragCoord.xy / u_scale;
    vec4 far_blur = bilinear(u_far_field, low);
    vec4 near_blur = bilinear(u_near_field, low);
    vec3 color = mix(sharp, far_blur.rgb, far_coc);
    float coverage = clamp(near_blur.a * 2.0, 0.0, 1.0);   // a blurred edge at half coverage is opaque
    vec3 near_color = near_blur.a > 1e-4 ? near_blur.rgb / near_blur.a : color;
    o_color = vec4(mix(color, near_color, coverage), 1.0);
}
