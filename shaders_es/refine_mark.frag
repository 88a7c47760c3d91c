#version 300 es
// Mixed resolution (src/render/refine.c; docs/quality-and-budgets.md, "Mixed resolution"): marks
// the full-resolution pixels where the coarse particle target does not hold the picture, where
// the particles are then shaded again at full resolution. A pixel is marked when the coarse
// texels its upsampling reads hold particles and either
//   - an opaque edge runs through them: the four low-res depths disagree with this pixel's
//     depth (the composite's nearest-depth test, composite.frag), or
//   - the coarse image changes sharply across them: transmittance, or the light as the display
//     roughly sees it (v / (1 + v)), differs by more than u_contrast between the four texels
//     (the silhouettes of dense, bright fire; soft smoke stays coarse).
// A marked pixel writes depth 1 (the refinement's GL_LESS passes there only: the particles'
// window depth is 0.5 or 0, refine.c) and the refinement's start (no light, transmittance 1);
// the others are discarded (the target's clear, depth 0 and alpha -1, tells the composite to
// upsample there).
precision highp float;
precision highp sampler2D;

uniform mediump sampler2D u_particles;   // low-res: premultiplied light, transmittance
uniform sampler2D u_scene_depth;         // full-res host depth, window depth
uniform float u_inv_divisor;             // 1 / the target's divisor
uniform vec2 u_low_texel;                // 1 / the low-res target's size
uniform vec3 u_near_model;               // window depth -> near / distance (composite.frag)
uniform float u_depth_threshold;         // relative depth difference that counts as an edge
uniform float u_near_over_far;           // near / the view distance beyond which no particle reaches
uniform float u_contrast;                // the coarse image's change that counts as an edge
#ifdef LOW_CORNERS
uniform sampler2D u_low_corners;         // the four low-res depths around a texel (low_corners.frag)
uniform vec2 u_corners_texel;            // 1 / its size
#else
uniform sampler2D u_low_depth;
#endif

out vec4 o_color;

// near / distance (composite.frag's): no surface lands on the particles' reach when clamped there
float near_over_distance(float d)
{
    return u_near_model.x * (d - u_near_model.y) + u_near_model.z;
}

// One texel as (display-ish light, transmittance); NaN and Inf as the composite sanitizes them.
mediump vec2 texel(vec2 uv)
{
    mediump vec4 p = textureLod(u_particles, uv, 0.0);
    mediump float light = max(max(p.r, p.g), p.b);
    mediump vec2 v = vec2(light / (1.0 + light), p.a);
    return isnan(v.x + v.y) ? vec2(0.0, 1.0) : clamp(v, 0.0, 1.0);
}

// The composite's test (composite.frag, nearest_depth_weights), in near / distance
bool depth_edge(vec2 base, vec2 uv, vec2 t)
{
    float E = max(near_over_distance(texelFetch(u_scene_depth, ivec2(gl_FragCoord.xy), 0).r), u_near_over_far);
#ifdef LOW_CORNERS
    vec4 e = textureLod(u_low_corners, (base + 1.5) * u_corners_texel, 0.0);
#else
    vec4 e = vec4(textureLod(u_low_depth, uv, 0.0).r, textureLod(u_low_depth, uv + vec2(t.x, 0.0), 0.0).r,
                  textureLod(u_low_depth, uv + vec2(0.0, t.y), 0.0).r, textureLod(u_low_depth, uv + t, 0.0).r);
#endif
    e = max(e, vec4(u_near_over_far));
    vec4 over = abs(E - e) - u_depth_threshold * e;
    return max(max(over.x, over.y), max(over.z, over.w)) > 0.0;
}

void main()
{
    vec2 low = gl_FragCoord.xy * u_inv_divisor - 0.5;
    vec2 base = floor(low);
    vec2 t = u_low_texel;
    vec2 uv = (base + 0.5) * t;
    mediump vec2 a = texel(uv), b = texel(uv + vec2(t.x, 0.0)), c = texel(uv + vec2(0.0, t.y)), d = texel(uv + t);
    mediump vec2 hi = max(max(a, b), max(c, d)), lo = min(min(a, b), min(c, d));
    // no particle in any of the four texels: nothing to refine, whatever the depths
    if (!(hi.x > 0.0 || lo.y < 1.0)) discard;
    mediump vec2 change = hi - lo;
    if (!(max(change.x, change.y) > u_contrast) && !depth_edge(base, uv, t)) discard;
    gl_FragDepth = 1.0;
    o_color = vec4(0.0, 0.0, 0.0, 1.0);
}
