/* Fire as a light source (issue 27): the radiant intensity of fire particles from their black
 * body, and the live fire gathered into a few point lights. Pure C in double, no GL: the module
 * (fire_lights.c) and the CPU reference (ref/) run the same code. */
#ifndef SBFX_FIRE_LIGHT_H
#define SBFX_FIRE_LIGHT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* What a fire particle's light depends on: particle.frag's fire (MEDIUM_EMITS), averaged over
 * the detail's values (one per pixel drives both the density and the temperature there; the
 * black body is steep in T, so the light at the mean detail would be far too little for cooling
 * fire). The black body is the module's normalised one (table or analytic). */
#define SBFX_FIRE_DETAIL_LEVELS 32
typedef struct sbfx_fire_model {
    double tau, t0, t1, cooling, detail_strength;
    double soot;            /* the cool share's soot per unit of the column's depth (sbfx_fire_cool_soot) */
    double detail[SBFX_FIRE_DETAIL_LEVELS]; /* the detail volume's quantiles (j + 1/2) / LEVELS */
    double emission_scale;  /* radiance per unit of the normalised black body, times (1 - albedo) */
    double ceiling;         /* the radiance ceiling / exposure (particle.frag); 0: none */
    void (*blackbody)(const void *ctx, double kelvin, double rgb[3]);
    const void *blackbody_ctx;
} sbfx_fire_model;

/* Fire's temperature coordinate (T = T0 + T1 x this) at one pixel: particle.frag's
 * detail_fire_temperature (the CPU reference calls this one). */
#define SBFX_FIRE_CORE 0.6
#define SBFX_FIRE_DETAIL 0.5
#define SBFX_FIRE_DETAIL_AGE 1.0
double sbfx_fire_coordinate(double detail, double rho, double intensity, double strength);

/* Fire's soot (particle.frag's fire_soot): optical depth that absorbs and does not glow, where the
 * fire is old and cool: the particle's peak extinction (tau x density scale) x chord^2 / 2r x this,
 * FIRE_SOOT ((1 - coordinate x cooled) (1 - intensity)^2)^2, coordinate the temperature's (T = T0 +
 * T1 coordinate) and cooled = 1 - cooling (1 - intensity). */
#define SBFX_FIRE_SOOT 16.0
double sbfx_fire_soot(double coordinate, double cooled, double intensity);

/* The share of a fire column's opacity that glows (particle.frag's fire_glow_share): its soot
 * whose temperature coordinate is above FIRE_GLOW_THRESHOLD + FIRE_GLOW_AGE (1 - intensity), rising
 * over FIRE_GLOW_WIDTH of the coordinate; the rest is too cool to glow and only absorbs (Kirchhoff).
 * mix(1, that, strength). The emission is this times the opacity; the coverage is the opacity. */
#define SBFX_FIRE_GLOW_THRESHOLD 0.45
#define SBFX_FIRE_GLOW_AGE 0.4
#define SBFX_FIRE_GLOW_WIDTH 0.2
double sbfx_fire_glow_share(double coordinate, double intensity, double strength);

/* Soot that wraps the glowing soot (particle.frag, media.fire.soot; docs/look-fire.md "Pink
 * edges"): the share of a column too cool to glow (1 - glow share) carries `soot` times the
 * column's optical depth on top of it, so the coverage's depth is depth (1 + soot (1 - glow)); it
 * absorbs the background and emits nothing. A luminous flame's soot forms and lingers where the
 * fire is too cool to glow, on the fringe of the luminous zone: that is what darkens the sky
 * behind a fireball's thin, glowing rim instead of letting red light add to it. 0: none. */
#define SBFX_FIRE_SOOT_DEFAULT 2.0
double sbfx_fire_cool_soot(double depth, double glow, double soot);

/* The quantiles of the values a pixel samples from the detail volume (size x size x frames, x
 * fastest): trilinear between texels, as the GPU filters a magnified window (which narrows the
 * texels' spread), at 65536 fixed pseudo-random points; a 1024-bin histogram, no memory. */
void sbfx_fire_detail_levels(const float *volume, int size, int frames, double out[SBFX_FIRE_DETAIL_LEVELS]);

/* The same for a volume whose slices a host pushes (a V4L2 camera, a video clip: the time ring
 * of sbfx_detail_push_slice): one histogram per slice, of SBFX_FIRE_SLICE_SAMPLES values at fixed
 * pseudo-random points of the slice (half-float texels, size x size, REPEAT), bilinear as the GPU
 * filters a magnified window within a slice (adjacent slices of a camera are alike: the filter
 * between them narrows little), in SBFX_FIRE_DETAIL_BINS bins; then the quantiles of the slices'
 * histograms together. A pushed slice replaces its slot's histogram: the statistics follow what
 * the volume holds. No memory. */
#define SBFX_FIRE_DETAIL_BINS 1024
#define SBFX_FIRE_SLICE_SAMPLES 2048
void sbfx_fire_slice_histogram(const uint16_t *half_texels, int size, uint16_t histogram[SBFX_FIRE_DETAIL_BINS]);
void sbfx_fire_detail_levels_of_slices(const uint16_t *histograms, int slices, double out[SBFX_FIRE_DETAIL_LEVELS]);

/* Radiant intensity rgb (linear radiance units x m^2: light per steradian, the same in every
 * direction) of one fire particle of the given radius and intensity, and its emitting area
 * (m^2, the integral over its disc of its opacity with its soot, what it covers):
 *     I = E_detail ∫ L_e(T(rho, detail)) alpha(rho, detail) dA   over the disc, rho = distance from the centre / radius,
 * alpha the exact model's opacity of the chord at rho (docs/design.md §2.1), L_e what the shader
 * emits there. Zero for a particle that is not finite or has no radius or intensity. */
void sbfx_fire_particle_intensity(const sbfx_fire_model *m, double radius, double intensity, double rgb[3],
                                  double *area);

/* One live fire particle, in any one frame (world or view space). */
typedef struct sbfx_fire_particle {
    double position[3];
    double radius, intensity;
} sbfx_fire_particle;

/* Per-particle work memory of sbfx_fire_gather (one per particle, made at load). */
typedef struct sbfx_fire_work {
    double rgb[3], area, luminance;
    int cluster;
} sbfx_fire_work;

/* A gathered light: the fire within SBFX_FIRE_CLUSTER_M of its brightest particle. */
typedef struct sbfx_fire_gathered {
    double position[3];     /* luminance-weighted centre of its particles */
    double intensity[3];    /* radiant intensity that leaves the cluster (linear units x m^2) */
    double extent;          /* rms distance of its light from the centre + mean particle radius */
} sbfx_fire_gathered;

#define SBFX_RADIANCE_CEILING 16384.0 /* particle.frag's, pre-exposed */
#define SBFX_FIRE_CLUSTER_M 2.0    /* particles this close to a cluster's seed join it */
#define SBFX_FIRE_GATHER_MAX 16    /* = SBFX_MAX_POINT_LIGHTS */

/* Gathers `count` fire particles into at most `max` (<= SBFX_FIRE_GATHER_MAX) lights, brightest
 * first; returns how many. Greedy and deterministic: the brightest particle not yet taken seeds a
 * light and takes every particle within SBFX_FIRE_CLUSTER_M of it; once `max` lights are seeded
 * the rest join the nearest seed. Each particle adds its intensity times the share that leaves
 * the fire: the other fire particles in front of it, averaged over directions, pass
 * prod_j (1 - f_j a_j) of it (f_j: the fraction of directions j's sphere covers seen from it,
 * a_j: j's mean opacity over its disc, with its soot). */
int sbfx_fire_gather(const sbfx_fire_model *m, const sbfx_fire_particle *particles, int count,
                     sbfx_fire_work *work, sbfx_fire_gathered *out, int max);

/* The host's falloff of a point light (include/sbfx.h, sbfx_emitted_lights): at distance d from a
 * light of influence radius R, window(d / R) / max(d^2, SBFX_LIGHT_MIN_D2) with
 * window(x) = clamp(1 - x^4, 0, 1)^2. */
#define SBFX_LIGHT_MIN_D2 0.25
double sbfx_light_falloff(double d2, double radius);

/* A gathered light's radius of influence: where colour x exposure / d^2 falls below
 * SBFX_LIGHT_NEGLIGIBLE (about an eighth of an 8-bit step on a white surface), at least its
 * extent + 0.5 m. colour_max: the largest channel of the light's host colour (I / pi). */
#define SBFX_LIGHT_NEGLIGIBLE (1.0 / 2048.0)
double sbfx_fire_light_radius(double colour_max, double exposure, double extent);

/* A gathered light's radius of influence at a given exposure (sbfx_fire_light_radius of its
 * host colour I / pi). */
double sbfx_fire_gathered_radius(const sbfx_fire_gathered *g, double exposure);

/* Fire light in-scattered by a dust or smoke particle (issue 27): the gathered lights, in the
 * frame's view space (eye at the origin), through the medium's phase function (asymmetry g,
 * sbfx_phase) at the particle's centre c, with the host's falloff (sbfx_light_falloff at each
 * light's radius):  rgb = sum_l I_l falloff_l(|c - x_l|) phase(cos theta_l)
 * (radiance per unit albedo: a light of intensity I at d gives I / d^2 of irradiance, which a
 * scatterer sends toward the eye times the phase function), the same model as the scene's point
 * lights (evaluated at the centre, as they are). `position`: the lights' luminance-weighted
 * position seen from c, d2 = max(|c - position|^2, SBFX_LIGHT_MIN_D2). */
typedef struct sbfx_fire_scatter {
    double rgb[3], d2, position[3];
} sbfx_fire_scatter;
void sbfx_fire_scatter_at(const sbfx_fire_gathered *lights, int count, double exposure, const double c[3], double g,
                          sbfx_fire_scatter *out);
/* What particle.frag's fire_scattered gets per particle: rgb, 0, then the gradient gx, gy, 0, 0.
 * Across the particle the light changes as 1/d^2 from `position` does to first order: a pixel
 * whose ray meets the centre's depth plane at c + (u, v, 0) gets
 *     rgb (1 + gx u + gy v),   (gx, gy) = 2 (position - c)_xy / d2,
 * the gradient shortened to at most 1 / radius so that it stays >= 0 on the disc. So smoke
 * above a fireball glows from below. (The exact 1/d^2 per pixel cost 0.03 Mali-G610 cycles more
 * than the budget left: docs/gpus.md.) */
void sbfx_fire_scatter_instance(const sbfx_fire_scatter *s, const double c[3], double radius, double out[8]);

#endif
