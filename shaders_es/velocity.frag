#version 300 es
// Per-pixel motion for the velocity blur (RTR 12.5, McGuire et al.): the opaque scene moves
// with the camera (its depth reprojected into the previous frame); particles carry their own
// screen motion, written premultiplied by the particle pass, and cover the scene's motion by
// their transmittance. Stored as the blur's half-extent in pixels (half the displacement
// during the open shutter), clamped to the tile size, and the pixel's view distance (at most 6e4,
// inside half float) beside it for the gather's depth tests; encoded for an RGBA8 target when
// float targets are not renderable (then without the distance: the gather reads the depth).
precision highp float;
precision highp sampler2D;

uniform sampler2D u_scene_depth;       // full-res window depth
uniform mat4 u_reproject;              // current NDC -> previous clip
uniform vec2 u_ndc_depth;              // window depth -> ndc z: x d + y (the clip depth mode)
uniform vec2 u_size;                   // full-resolution size
uniform float u_shutter;               // fraction of the frame the shutter is open
uniform float u_max_radius;            // = tile size in pixels
uniform vec4 u_depth_model;            // window depth -> distance (view_distance)
#ifdef HAS_PARTICLE_VELOCITY
uniform sampler2D u_particle_velocity; // low-res: premultiplied velocity [px], transmittance
uniform bool u_particles_drawn;        // false on frames without particles
uniform float u_divisor;
uniform ivec2 u_low_size;
#endif
#ifdef ENCODE_UNORM
const bool encode = true;
#else
const bool encode = false;
#endif

out vec4 o_velocity;

// Window depth -> view distance (src/render/projection.c): the matrix's own depth row, solved around
// the far end so nothing cancels; the clear value means no surface.
float view_distance(float d)
{
    if (d == u_depth_model.y) return 1e30;
    return u_depth_model.w / (u_depth_model.x * (d - u_depth_model.y) + u_depth_model.z);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(u_scene_depth, p, 0).r;
    vec2 ndc = gl_FragCoord.xy / u_size * 2.0 - 1.0;
    vec4 previous = u_reproject * vec4(ndc, depth * u_ndc_depth.x + u_ndc_depth.y, 1.0);
    vec2 motion = previous.w > 1e-6 ? (ndc - previous.xy / previous.w) * 0.5 * u_size : vec2(0.0);
#ifdef HAS_PARTICLE_VELOCITY
    if (u_particles_drawn) {
        ivec2 q = clamp(ivec2(gl_FragCoord.xy / u_divisor), ivec2(0), u_low_size - 1);
        vec4 particles = texelFetch(u_particle_velocity, q, 0);
        motion = particles.xy + motion * particles.a;
    }
#endif
    vec2 v = motion * 0.5 * u_shutter;
    float len = length(v);
    if (!(len < 1e30)) v = vec2(0.0);                    // NaN or Inf: no blur
    else if (len > u_max_radius) v *= u_max_radius / len;
    o_velocity = encode ? vec4(v / (2.0 * u_max_radius) + 0.5, 0.0, 1.0) : vec4(v, min(view_distance(depth), 6.0e4), 1.0);
}
