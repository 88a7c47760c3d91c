/* Per-pixel lit smoke (the lit-smoke seed): a CPU reference in double precision of sampling
 * the procedural smoke textures (made at load, src/tables/tables.h), of every lighting term and of
 * the height-field ray march. The particle shader's LIGHTING_LIT variant
 * (shaders_es/particle.frag.parts/5-lighting.glsl) computes the same things in float; tests and
 * the lighting bench compare the two. Part of libsbfx_ref.a, not of the runtime library. Pure
 * libc, no GL.
 *
 * Texture space of a lit particle (centre c, radius r, view space; the view matrix is the
 * tangent basis, so tangent = view x, bitangent = view y, normal = view +z, toward the eye):
 *   st = (p.xy - c.xy) / (2r) + 0.5     zt = (p.z - c.z) / (2r)
 * The height field h(st) in [0,1] describes a slab |zt| <= h/2 — a sphere of radius r where
 * h = sqrt(1 - |2st - 1|^2) — with density max(0, h - 2|zt|): 1 on the centre plane of the
 * thickest part, 0 on its surfaces. A pixel is shaded at the front surface zt = h/2. */
#ifndef SBFX_LIT_REF_H
#define SBFX_LIT_REF_H

#include <stddef.h>
#include <stdint.h>
#include "tables/tables.h"

/* ---- sampling the procedural smoke textures (src/tables/tables.h makes them) ---------------- */

typedef struct sbfx_smoke_texture {
    int size, layers, levels; /* levels <= sbfx_smoke_texture_levels(size) */
    const uint8_t *texels;    /* level by level, each layers x size' x size' RGBA8 */
} sbfx_smoke_texture;

/* Trilinear fetch as the GPU does it (LINEAR_MIPMAP_LINEAR, CLAMP_TO_EDGE, texel centres at
 * (i + 0.5)/size', lod clamped to [0, levels - 1]), channels in [0,1]. */
void sbfx_smoke_sample(const sbfx_smoke_texture *tex, int layer, double s, double t, double lod, double rgba[4]);
/* The level of detail a particle samples at, one per particle: log2 of texels per target pixel
 * at the centre's depth, = log2(size * pixel_slope * depth / (2 radius)), where pixel_slope is
 * one target pixel's width in x/(-z) units (2 / (target width * projection[0])); >= 0. */
double sbfx_lit_lod(int size, double radius, double depth, double pixel_slope);

/* The maps of one variant at st: the normal 2 rgb - 1 as filtered (not renormalised: a little
 * shorter between texels and on coarser levels). */
typedef struct sbfx_lit_maps {
    double normal[3];
    double height, brightness, translucency;
} sbfx_lit_maps;
void sbfx_lit_maps_at(const sbfx_smoke_texture *tex, int variant, double s, double t, double lod,
                      sbfx_lit_maps *out);
/* The variant a particle uses: floor(detail_u * variants), clamped to [0, variants - 1]. */
int sbfx_lit_variant(double detail_u, int variants);

/* ---- lighting terms ------------------------------------------------------------------ */

/* Wrap-around Lambert: max(0, N.L * 1/(1+w) + w/(1+w)). */
double sbfx_lit_wrap(double n_dot_l, double wrap);
/* Back-lighting. The seed prints min(0, E.L) * map, which is negative (it would darken) for a
 * light behind the particle and 0 for one in front. We use its magnitude, max(0, -E.L):
 * E = surface -> eye, L = surface -> light, so a light straight behind gives the full
 * translucency map (the thin rim glows), one in front or to the side gives 0. */
double sbfx_lit_backlight(double v_dot_l, double translucency_map, double translucency);
/* Step count of the march, the seed's n = nMin + (N.V)(nMax - nMin), N.V clamped to [0,1],
 * rounded half up. */
int sbfx_lit_steps(double n_dot_v, int n_min, int n_max);
/* Transmittance from the front surface at (st, height) toward the unit direction to_light
 * (view space), marched through the height field of `variant` in `steps` equal steps (midpoint
 * samples) over one diameter (length 1 in texture units: the longest chord of the particle's
 * sphere, which holds the whole slab; beyond the slab the density is 0):
 *   exp(-tau * 2r * sum_k max(0, h(st_k) - 2|zt_k|) * dt),  dt = 1 / steps.
 * tau = extinction at the densest point (per metre), as for the particle's opacity. steps = 0
 * gives 1 (no self-shadowing). The march stops once the optical depth passes 20. */
double sbfx_lit_shadow(const sbfx_smoke_texture *tex, int variant, double lod, const double st[2],
                       double height, const double to_light[3], double radius, double tau, int steps);

/* ---- one fragment ---------------------------------------------------------------------- */

typedef struct sbfx_lit_medium {
    double albedo_color[3]; /* albedo * tint */
    double tau;             /* extinction at the centre x the fragment's density scale */
    double wrap, translucency, dampening;
    int steps_min, steps_max;
} sbfx_lit_medium;

typedef struct sbfx_lit_light {
    double vector[4]; /* view space: w = 0 direction of travel (unit), w = 1 position */
    double color[3];  /* irradiance; point lights at 1 m, falling off as 1/max(d^2, 0.25) */
} sbfx_lit_light;

/* The light a lit particle sends toward the eye through this pixel's ray (ray.z = -1), before
 * the particle's opacity multiplies it (every fetch at the particle's lod):
 *   albedo * B * (ambient + (1 - dampening) * sum_i E_i falloff_i S_i (wrap_i + back_i))
 * over the first SBFX_LIT_MAX_LIGHTS lights, with N, B, translucency from the maps at the
 * pixel's st, V the unit vector from the centre toward the eye (per particle). Light 0, the key
 * light, is taken at the front surface p (direction and falloff per pixel; a point light at p
 * itself has no direction: only the wrap's bias lights it) and S_0 is the march toward it. The
 * others are taken at the centre (direction and falloff per particle; one at the centre lights
 * it along +z) with S_i = 1. Finite for any finite input. */
void sbfx_lit_radiance(const sbfx_lit_medium *m, const sbfx_smoke_texture *tex, int variant, double lod,
                       const double center[3], double radius, const double ray[3],
                       const sbfx_lit_light *lights, int light_count, const double ambient[3],
                       double rgb[3]);

/* The fire's light on a lit particle through this pixel's ray (particle.frag's FIRE_LIGHT with
 * LIGHTING_LIT), before the opacity multiplies it: albedo * B * (1 - dampening) * fire, fire the
 * fire's light at the particle's centre (src/sim/fire_light.h's in-scattering, isotropic: per
 * particle, like the fill lights) and B the brightness map at the pixel's st. The fire is
 * gathered per particle without a direction: it lights the relief through the brightness map,
 * as a light wrapped all around it would, not through the normals, and unshadowed.
 * sbfx_lit_radiance plus this is the shader's light. */
void sbfx_lit_fire_radiance(const sbfx_lit_medium *m, const sbfx_smoke_texture *tex, int variant, double lod,
                            const double center[3], double radius, const double ray[3], const double fire[3],
                            double rgb[3]);

#endif
