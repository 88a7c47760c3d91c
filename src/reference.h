/* CPU reference of every per-fragment computation, in double precision, usable without GL.
 * Tests and the benchmark compare the GPU against these functions; the GL code builds its
 * lookup tables from them. Pure libc (+ lcms2 to read the CIE tables). */
#ifndef SBFX_REFERENCE_H
#define SBFX_REFERENCE_H

#include <stddef.h>
#include <stdint.h>
#include "sbfx.h"

/* ---- opacity (DESIGN §2.1) ------------------------------------------------------------ */

/* One spherical particle in view space (camera at origin, looking down -z, so center[2] < 0
 * for a particle in front of the camera). tau is the extinction at the centre. */
typedef struct sbfx_ref_particle {
    double center[3];
    double radius;
    double tau;
} sbfx_ref_particle;

/* The pixel's situation: ray = direction through the pixel scaled so that ray[2] == -1
 * (i.e. x/(-z), y/(-z), -1); opaque_depth = distance along -z of the opaque surface (Zs);
 * near = near-plane distance; soft_scale = depth range of the soft-particle fade (soft mode). */
typedef struct sbfx_ref_pixel {
    double ray[3];
    double opaque_depth;
    double near;
    double soft_scale;
} sbfx_ref_pixel;

/* Opacity alpha in [0,1] of one particle for one pixel, in the given mode (DEFAULT = EXACT, the
 * module's default).
 * Always finite; a particle with a NaN/Inf input or radius <= 0 gives 0. */
double sbfx_ref_opacity(sbfx_opacity_mode mode, const sbfx_ref_particle *p, const sbfx_ref_pixel *px);
/* Optical depth (the exponent) instead of alpha; +inf never returned (clamped to 1e30). */
double sbfx_ref_optical_depth(sbfx_opacity_mode mode, const sbfx_ref_particle *p,
                              const sbfx_ref_pixel *px);
/* ∫_a^b sqrt(h + u^2) du, stable as h -> 0 (h >= 0). */
double sbfx_ref_chord_integral(double h, double a, double b);
/* RTR soft-particle contrast curve: 0.5*(2x)^p for x<0.5 else 1-0.5*(2(1-x))^p, x clamped. */
double sbfx_ref_soft_fade(double x, double power);

/* ---- black body (DESIGN §2.3) --------------------------------------------------------- */

#define SBFX_CMF_MAX_BANDS 512
#define SBFX_CMF_DEFAULT_PATH "/usr/share/colord/cmf/CIE1931-2deg-XYZ.cmf"

typedef struct sbfx_cmf {
    int bands;
    double start_nm, step_nm;
    double xyz[3][SBFX_CMF_MAX_BANDS];
} sbfx_cmf;

/* Reads colord's CGATS file (lcms2's IT8 reader). On failure returns SBFX_ERR_MISSING_DATA
 * and writes a message naming the file and the Debian package (colord-data) into err. */
sbfx_result sbfx_cmf_load(const char *path, sbfx_cmf *out, char *err, size_t err_size);
/* Planck's spectral radiance [W sr^-1 m^-3] at wavelength lambda_m and temperature kelvin,
 * with expm1; 0 for kelvin <= 0, never inf/nan for kelvin in (0, 1e6]. */
double sbfx_planck(double lambda_m, double kelvin);
/* XYZ of the black body at kelvin (integral of Planck x CMFs over the table's bands). */
void sbfx_blackbody_xyz(const sbfx_cmf *cmf, double kelvin, double xyz[3]);
void sbfx_xyz_to_linear_srgb(const double xyz[3], double rgb[3]);
/* Normalised linear sRGB: XYZ * norm -> sRGB, negative components clipped to 0. */
void sbfx_blackbody_rgb(const sbfx_cmf *cmf, double kelvin, double norm, double rgb[3]);
/* The normalisation: 1 / Y(kelvin), so the black body at `kelvin` has luminance 1. The module
 * uses desc.blackbody_max_kelvin (6000 K): the unit the media's `emission` multiplies. */
double sbfx_blackbody_norm(const sbfx_cmf *cmf, double kelvin);

/* The black-body table (what the GPU samples): `size` entries over [lo, hi] kelvin, uniform in
 * 1/T (entry i at 1/T = 1/hi + i/(size-1) * (1/lo - 1/hi)), 4 floats each: the colour's linear
 * sRGB divided by its luminance, before clipping (r/Y, g/Y, b/Y), and ln(Y * norm / T).
 * Why these: in 1/T Planck's law is nearly exponential at the cool end (Wien) and Y/T nearly
 * constant at the hot end (Rayleigh–Jeans), and the chromaticity is smooth in 1/T throughout,
 * so linear interpolation of these four stays within 1e-4 of the function where a table linear
 * in T and in Y misses by orders of magnitude at the cool end. Clipping to the gamut comes after
 * interpolation. */
void sbfx_blackbody_table(const sbfx_cmf *cmf, double norm, double lo, double hi, int size, float *out);
/* Linear interpolation in that table as the GPU does it (entries are float), extrapolated along
 * the end cells outside [lo, hi] (for ln(Y/T) below lo that is Wien's law), times T, negative
 * components clipped. 0 for T <= 0 or NaN. */
void sbfx_blackbody_table_lookup(const float *table, int size, double lo, double hi, double kelvin,
                                 double rgb[3]);
/* Largest error of the lookup against sbfx_blackbody_rgb over [lo, hi] (8 points per cell):
 * max over channels |table - function| / the function's largest channel. */
double sbfx_blackbody_table_error(const sbfx_cmf *cmf, double norm, const float *table, int size,
                                  double lo, double hi);

/* ---- phase function (DESIGN §2.3) ----------------------------------------------------- */

/* Cornette–Shanks shaped phase function, normalised to 1 over the sphere (1/sr).
 * cos_theta is the cosine of the scattering angle between the light's direction of travel and
 * the direction the scattered light leaves in (1 = light goes straight on), so positive g
 * peaks forward: P = 3(1-g^2)(1+c^2) / (8π (2+g^2) (1+g^2-2gc)^{3/2}). */
double sbfx_phase(double cos_theta, double g);
#define SBFX_PHASE_G_MAX 0.99
/* The phase table of one medium (its g is fixed at load): `size` entries over a coordinate
 * t in [0, 1], t = 0 at the back (s = -1), t = 1 at the peak (s = 1), s = sign(g) cos θ (the
 * function of (s, |g|) is that of (cos θ, g)). For |g| >= SBFX_PHASE_WARP_MIN_G
 *     t = ln(b(s) / (1+|g|)^2) / ln((1-|g|)^2 / (1+|g|)^2),  b(s) = (1-|g|)^2 + 2|g| (1 - s),
 * b being 1 + g^2 - 2 g cos θ written without cancellation at the peak. The function is
 * ~ b^{-3/2}, so in t it is nearly exp(-1.5 ln b), an exponential whose relative curvature is
 * the same everywhere: linear interpolation is as good at the peak as at the back, where a
 * table linear in cos θ fails at the peak by orders of magnitude. Below that g, t = (s + 1) / 2
 * (the function is nearly flat). Entry i at t = i / (size - 1). */
#define SBFX_PHASE_WARP_MIN_G 0.02
double sbfx_phase_coordinate(double cos_theta, double g);
void sbfx_phase_table(double g, int size, float *out);
/* Linear interpolation in that table at cos_theta, as the GPU does it. */
double sbfx_phase_table_lookup(const float *table, int size, double g, double cos_theta);
/* Largest relative error of the lookup against sbfx_phase over all angles (a cos θ grid 16
 * times finer than the table, plus the peak and the back). */
double sbfx_phase_table_error(const float *table, int size, double g);

/* ---- tone curve of the particles' light (sbfx_tone_map; src/tonemap.c) ----------------- */

#define SBFX_TONE_KNEE 0.6   /* light below this reaches the display unchanged */
#define SBFX_TONE_WHITE 64.0 /* ...and this much (the radiance ceiling) reaches 1 */
typedef struct sbfx_tone_curve {
    double knee, white, steepness, inverse_log_white;
} sbfx_tone_curve;
sbfx_tone_curve sbfx_tone_curve_default(void);
/* v for v <= knee, then the logarithmic shoulder, 1 at and above white; 0 for v <= 0, NaN. */
double sbfx_tone_curve_apply(const sbfx_tone_curve *c, double v);

/* ---- detail volume (DESIGN §2.4) ------------------------------------------------------ */

/* Tileable (in x, y and t) animated fBm, size x size x frames floats in [0,1], x fastest.
 * Deterministic from seed. */
void sbfx_detail_generate(int size, int frames, uint32_t seed, float *out);

/* ---- small deterministic RNG shared by simulation, tests and tools -------------------- */
typedef struct sbfx_rng { uint64_t state; } sbfx_rng;
void sbfx_rng_seed(sbfx_rng *rng, uint64_t seed);
uint32_t sbfx_rng_u32(sbfx_rng *rng);
double sbfx_rng_uniform(sbfx_rng *rng); /* [0,1) */
double sbfx_rng_range(sbfx_rng *rng, double lo, double hi);

#endif
