#version 300 es
// particle.frag, part 1 of 7: what the particle is, its switches, precision, fetches
// The volumetric particle of the spherical-billboards seed, equation (1):
//   out = in * (1 - alpha) + alpha * albedo * C_in + alpha * (1 - albedo) * L_e
// written premultiplied into the particle target (rgb = added light, a = alpha; the blend
// multiplies the target's alpha, which holds transmittance). Specialised at load by defines:
//   MEDIUM_SCATTERS  dust/smoke: in-scattering through the phase-function table
//   MEDIUM_EMITS     fire: black-body emission at T = (T0 + T1 * detail), cooled as the
//                    particle's intensity (its density scale) falls
//   HAS_DETAIL       perturbation by the animated detail volume
//   OPACITY_PLANAR | OPACITY_SOFT | OPACITY_SPHERICAL | OPACITY_EXACT
//   OPACITY_FLOOR    benchmark only: the same quads, a trivial shader (the fill-rate floor)
//   BLACKBODY_ANALYTIC, PHASE_ANALYTIC   evaluate per fragment instead of fetching the tables
//   LIGHT_PER_PARTICLE  (phase model) in-scattering computed once per particle on the CPU
//   FIRE_LIGHT       (with MEDIUM_SCATTERS) the frame's fire light, in-scattered at the
//                    particle's centre on the CPU, falling off across it from the fire; lit
//                    media take it shaded by their brightness map, as a light without direction
//   LIGHTING_LIT     (with MEDIUM_SCATTERS) the lit-smoke seed instead of the phase function:
//                    per-pixel normals, wrap-around Lambert, back-lighting, up to 4 lights
//   LIT_SHADOW       (with LIGHTING_LIT) ray-marched self-shadowing through the height field,
//                    toward the key light (the first) only
//   TABLE_PROBE      diagnostics: main() writes blackbody(T) and phase(cos) for the probe and
//                    the tests (src/render/diagnostics.c) instead of shading a particle
// Light and colour are mediump (what a Mali-class GPU runs at half precision); geometry,
// depth and opacity stay highp.
precision highp float;
precision highp sampler2D;
precision highp sampler3D;
#ifndef FILTER_BITS   // SBFX_FILTER_BITS (shaders_es/filtered.frag): else the texture unit filters
#define filtered_3d_repeat(s, p) texture(s, p)
#define filtered_array_lod(s, p, lod) textureLod(s, p, lod)
#endif
#if defined(FILTER_BITS) && defined(DETAIL_NEAREST)
#define detail_fetch(s, p) texture(s, p)   // an R32F volume is sampled NEAREST: nothing to filter
#else
#define detail_fetch(s, p) filtered_3d_repeat(s, p)
#endif

