#version 300 es
// Depth of field, step 3: the sharp full-resolution image, the blurred far field mixed in by
// this pixel's far CoC, and the blurred near field laid over everything by its coverage.
// Where particles cover the scene the image is C = T x scene + P (composite.frag: transmittance
// T, the particles' light P). The far CoC is this pixel's, at full resolution: the particles'
// (their distance's) by their coverage, the scene's by T. The far field holds the scene behind
// particles that are in focus (dof_setup.frag: keep = their far CoC), so
//   C' = C + w (F - X),  X = mix(scene, C, keep),  w = T x scene CoC + (1 - T) x particle CoC
// gives, for particles in focus (keep 0), C' = P + T x (blurred scene): the particles stay the
// sharp full-resolution picture and only the sky seen through them is blurred, by how much of
// it is seen; for particles in the far field (keep 1) C' = mix(C, F, w) as for the scene.
//   HAS_SHIMMER  the scene as the composite read it: displaced by the heat's offsets
//   NO_PARTICLES  drawn outside the particles' tiles (src/render/tiles.c), where their target is
//                clear (transmittance 1, no motion) and the image the scene: what the particles'
//                branch of main() gives there, without its fetches
//   WRITE_VELOCITY  the velocity blur follows: this pass also writes its per-pixel motion, as
//                velocity.frag would (the same depth and particle texels, read here once for
//                both; with HAS_PARTICLE_VELOCITY and ENCODE_UNORM as there), and the velocity
//                pass is not drawn
// The blurred fields are read bilinearly by their LINEAR sampler (RGBA16F or RGBA8).
precision highp float;
precision highp sampler2D;
#ifndef FILTER_BITS   // SBFX_FILTER_BITS (shaders_es/filtered.frag): else the texture unit filters
#define filtered_2d(s, uv) textureLod(s, uv, 0.0)
#endif

uniform sampler2D u_color;         // full resolution; alpha: the particles' transmittance
uniform sampler2D u_far_field;     // blurred, LINEAR
uniform sampler2D u_near_field;    // blurred, LINEAR
uniform sampler2D u_scene_depth;
uniform vec4 u_depth_model;       // window depth -> distance (view_distance)
uniform vec2 u_far;                // [sharp, full blur] distances
uniform vec2 u_low_texel;          // 1 / (blur scale x blur-resolution size): pixel -> field uv
uniform bool u_particles_drawn;    // this frame's particles are in u_color and u_particle_motion
uniform sampler2D u_particle_motion; // low-res, NEAREST: premultiplied velocity, distance; transmittance
uniform vec2 u_particle_texel;     // 1 / (divisor x particle target size): pixel -> particle uv
uniform sampler2D u_scene_color;   // the host's colour, LINEAR (the composite's sampler)
uniform vec2 u_full_size;
#ifdef HAS_SHIMMER
uniform sampler2D u_distortion;    // low-res RGBA16F, LINEAR: the composite's scene offsets
#endif

#ifdef WRITE_VELOCITY
uniform mat4 u_reproject;              // current NDC -> previous clip
uniform vec2 u_ndc_depth;              // window depth -> ndc z: x d + y (the clip depth mode)
uniform float u_shutter;               // fraction of the frame the shutter is open
uniform float u_max_radius;            // the velocity blur's tile size in pixels
#ifdef ENCODE_UNORM
const bool encode = true;
#else
const bool encode = false;
#endif
layout(location = 1) out vec4 o_velocity;

// velocity.frag's motion of this pixel from its window depth (its view distance beside it) and,
// where particles cover it, their premultiplied velocity and transmittance (m: the particle
// texel under it).
void write_velocity(float depth, float distance, vec4 m)
{
    vec2 ndc = gl_FragCoord.xy / u_full_size * 2.0 - 1.0;
    vec4 previous = u_reproject * vec4(ndc, depth * u_ndc_depth.x + u_ndc_depth.y, 1.0);
    vec2 motion = previous.w > 1e-6 ? (ndc - previous.xy / previous.w) * 0.5 * u_full_size : vec2(0.0);
#if defined(HAS_PARTICLE_VELOCITY) && !defined(NO_PARTICLES)
    if (u_particles_drawn) motion = m.xy + motion * m.a;
#endif
    vec2 v = motion * 0.5 * u_shutter;
    float len = length(v);
    if (!(len < 1e30)) v = vec2(0.0);                    // NaN or Inf: no blur
    else if (len > u_max_radius) v *= u_max_radius / len;
    o_velocity = encode ? vec4(v / (2.0 * u_max_radius) + 0.5, 0.0, 1.0) : vec4(v, min(distance, 6.0e4), 1.0);
}
#endif
layout(location = 0) out vec4 o_color;

// Window depth -> view distance (src/render/projection.c): the matrix's own depth row, solved around
// the far end so nothing cancels; the clear value means no surface.
float view_distance(float d)
{
    if (d == u_depth_model.y) return 1e30;
    return u_depth_model.w / (u_depth_model.x * (d - u_depth_model.y) + u_depth_model.z);
}

// The scene where composite.frag read it for this pixel.
vec3 scene_behind(vec2 particle_uv)
{
    vec2 scene_uv = gl_FragCoord.xy / u_full_size;
#ifdef HAS_SHIMMER
    vec2 offset = filtered_2d(u_distortion, particle_uv).rg;
    if (!(abs(offset.x) < 1.0 && abs(offset.y) < 1.0)) offset = vec2(0.0);
    scene_uv = clamp(scene_uv + offset, 0.5 / u_full_size, 1.0 - 0.5 / u_full_size);
#endif
    return filtered_2d(u_scene_color, scene_uv).rgb;
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 sharp = texelFetch(u_color, p, 0);
    float ramp = 1.0 / max(u_far.y - u_far.x, 1e-4);
    float depth = texelFetch(u_scene_depth, p, 0).r;
    float distance = view_distance(depth);
    float far_coc = clamp((distance - u_far.x) * ramp, 0.0, 1.0);
    vec3 x = sharp.rgb;   // what the far field holds here
    vec4 m = vec4(0.0, 0.0, 0.0, 1.0);
#ifndef NO_PARTICLES
    if (u_particles_drawn) {
        vec2 particle_uv = gl_FragCoord.xy * u_particle_texel;
        m = textureLod(u_particle_motion, particle_uv, 0.0);
        float coverage = 1.0 - m.a;
        float keep = coverage > 1e-3 ? clamp((m.b / coverage - u_far.x) * ramp, 0.0, 1.0) : 1.0;
        far_coc = mix(keep, far_coc, clamp(sharp.a, 0.0, 1.0));
        x = mix(scene_behind(particle_uv), x, keep);
    }
#endif
    vec2 uv = gl_FragCoord.xy * u_low_texel;
    vec4 far_blur = filtered_2d(u_far_field, uv);
    vec4 near_blur = filtered_2d(u_near_field, uv);
    vec3 color = sharp.rgb + far_coc * (far_blur.rgb - x);
    float coverage = clamp(near_blur.a * 2.0, 0.0, 1.0);   // a blurred edge at half coverage is opaque
    vec3 near_color = near_blur.a > 1e-4 ? near_blur.rgb / near_blur.a : color;
    o_color = vec4(mix(color, near_color, coverage), 1.0);
#ifdef WRITE_VELOCITY
    write_velocity(depth, distance, m);
#endif
}
