#version 300 es
// particle.frag, part 2 of 7: varyings, uniforms by concern, outputs
#ifndef TABLE_PROBE
flat in vec4 v_center_radius;
flat in vec4 v_detail;
#endif
#ifdef LIGHT_PER_PARTICLE
flat in vec3 v_light;            // in-scattered light evaluated once at the particle's centre
#endif
#ifdef HAS_MOTION_TARGET
flat in vec2 v_velocity;
#endif
#if defined(FIRE_LIGHT) && !defined(LIGHTING_LIT)
flat in mediump vec3 v_fire;          // fire light in-scattered at the centre (phase model)
flat in mediump vec2 v_fire_gradient; // its relative change per metre across the particle
#endif
#ifdef MEDIUM_HEAT
uniform float u_heat_strength;   // largest shimmer offset, UV units
#endif

uniform sampler2D u_depth;       // low-res opaque near / distance (depth texture; 0: no surface)
uniform float u_near;
uniform vec4 u_ray_map;         // this pixel's ray (z = -1): xy = gl_FragCoord.xy * u_ray_map.xy + u_ray_map.zw
uniform float u_tau;
uniform float u_soft_scale;

#ifdef HAS_DETAIL
uniform sampler3D u_detail;
uniform float u_detail_window;
uniform float u_detail_strength;
uniform float u_time;            // in detail-volume loops
#endif
#ifdef MEDIUM_SCATTERS
uniform sampler2D u_phase_lut;   // R32F, row m: medium m's phase function (src/scene/scene_tables.c)
uniform int u_phase_row;
uniform vec4 u_phase_warp;       // sign(g), (1-|g|)^2, 2|g| (0: unwarped), 1/ln((1-|g|)^2/(1+|g|)^2)
uniform vec2 u_phase_shift;      // -ln((1+|g|)^2) * u_phase_warp.w, entries - 1
uniform vec4 u_phase_analytic;   // 3 (1 - g^2) / (8 pi (2 + g^2)), (1-|g|)^2, 2|g|, sign(g) (PHASE_ANALYTIC)
uniform vec3 u_albedo_color;     // albedo * tint
#define MAX_LIGHTS 8
#ifndef LIGHT_SLOTS
#define LIGHT_SLOTS MAX_LIGHTS   // set at load to the scene's lights + one effect's flashes
#endif
uniform int u_light_count;
uniform vec4 u_light_vector[MAX_LIGHTS]; // view space: w = 0 direction of travel, w = 1 position
uniform vec3 u_light_color[MAX_LIGHTS];  // irradiance (point lights: at 1 m) x 4 pi (render/particles.c)
uniform vec3 u_ambient;
#endif
#ifdef LIGHTING_LIT
precision highp sampler2DArray;
uniform sampler2DArray u_smoke;  // per variant v: layer 2v normal*0.5+0.5, height; 2v+1 brightness, translucency
#ifdef FIRE_LIGHT   // with the fire's light at the centre in the free components (particle.vert)
flat in vec4 v_lit;              // layer 2v, level of detail, the fire's light's red and green
flat in vec4 v_view;             // unit, from the centre toward the eye; the fire's light's blue
#else
flat in vec2 v_lit;              // the particle's layer 2v and level of detail (particle.vert)
flat in vec3 v_view;             // unit, from the particle's centre toward the eye
#endif
uniform vec3 u_wrap;             // wrap-around scale 1/(1+w), bias w/(1+w); 1+w
uniform float u_translucency;
uniform float u_direct;          // 1 - dampening: the lights' direct term is scaled by it
uniform vec2 u_steps;            // nMin + 1/2, nMax - nMin of the ray march
#define MAX_LIT_LIGHTS 4
#define LIT_SLOTS (LIGHT_SLOTS < MAX_LIT_LIGHTS ? LIGHT_SLOTS : MAX_LIT_LIGHTS)
#if LIGHT_SLOTS > 1
flat in vec4 v_fill[LIT_SLOTS - 1]; // lights 1.. seen from the particle's centre: direction, falloff
flat in float v_fill_back[LIT_SLOTS - 1]; // ... and falloff x max(0, -V.L)
#endif
#define MAX_STEPS 64             // SBFX_LIT_MAX_STEPS
#endif
#ifdef BLACKBODY_ANALYTIC
#define MAX_BANDS 96
uniform int u_cmf_count;
uniform vec3 u_cmf_rgb[MAX_BANDS]; // sRGB weight of each band (CMF, trapezoid, 2hc², norm)
uniform float u_cmf_band[MAX_BANDS]; // wavelength [µm]
#endif
#ifdef MEDIUM_EMITS
uniform sampler2D u_blackbody;   // RGBA32F, uniform in 1/T: rgb / Y, ln(Y / T) (src/tables/blackbody.c)
uniform vec3 u_blackbody_map;    // 1/T at entry 0, entries per unit of 1/T, entries - 2
uniform vec4 u_temperature;      // T0, T1, cooling, the cool share's soot (media.fire.soot)
uniform float u_emission_scale;   // includes (1 - albedo)
// Per-fragment radiance ceiling, in pre-exposed units: compositing ("under", front to back, as
// "over") never sums layers above their largest one, so the target stays inside half-float's 65504 (docs/look-fire.md).
const float RADIANCE_CEILING = 16384.0;
#endif

// 0: premultiplied light, alpha; 1: shimmer offset (heat adds, others occlude by alpha);
// 2: premultiplied screen velocity and view distance, alpha (motion blur, depth of field)
layout(location = 0) out vec4 o_color;
#ifdef HAS_DISTORTION_TARGET
layout(location = 1) out vec4 o_distortion;
#endif
#ifdef HAS_MOTION_TARGET
layout(location = 2) out vec4 o_velocity;
#endif

