/* What the module computes on the CPU, in double precision, at load: the black-body and phase
 * tables, the detail volume, the procedural smoke textures, and the deterministic RNG of the
 * simulation. Pure libc, no GL, no file read (the CIE tables are compiled in).
 *
 * The table lookups (sbfx_*_table_lookup) read a table the way the GPU does; they live beside
 * the builders so that each table's grid is defined in one file. Only the tests and the CPU
 * reference (ref/, which is not part of the runtime library) call them. */
#ifndef SBFX_TABLES_H
#define SBFX_TABLES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "sbfx.h"
#include "base/rng.h"

/* ---- black body (docs/design.md §2.3) -------------------------------------------------------- */

/* Colour-matching functions sampled at `bands` wavelengths start_nm + i * step_nm;
 * xyz[0], xyz[1], xyz[2] are x̄, ȳ, z̄ (bands values each). */
typedef struct sbfx_cmf {
    int bands;
    double start_nm, step_nm;
    const double *xyz[3];
} sbfx_cmf;

/* The CIE 1931 2° observer, 360..830 nm in 5 nm bands: generated at build time from
 * colord-data's CIE1931-2deg-XYZ.cmf through lcms2 by tools/gen_cmf.c ($(BUILD)/gen/cie1931_2deg.c),
 * so the library needs no data file and no lcms2 at run time. */
extern const sbfx_cmf sbfx_cie1931_2deg;
/* Planck's spectral radiance [W sr^-1 m^-3] at wavelength lambda_m and temperature kelvin,
 * with expm1; 0 for kelvin <= 0, never inf/nan for kelvin in (0, 1e6]. */
double sbfx_planck(double lambda_m, double kelvin);
/* XYZ of the black body at kelvin (integral of Planck x CMFs over the table's bands). */
void sbfx_blackbody_xyz(const sbfx_cmf *cmf, double kelvin, double xyz[3]);
void sbfx_xyz_to_linear_srgb(const double xyz[3], double rgb[3]);
/* Normalised linear sRGB: XYZ * norm -> sRGB, negative components clipped to 0. */
void sbfx_blackbody_rgb(const sbfx_cmf *cmf, double kelvin, double norm, double rgb[3]);
/* Photometry (docs/look-fire.md): the luminance in cd/m^2 of an optically thick black body
 * (emissivity 1) at kelvin, K_m * integral of Planck x ybar, K_m = 683.002 lm/W the maximum
 * luminous efficacy for the CIE 1931 ybar. 1500 K: 7.8e3, 2000 K: 4.7e5, 2500 K: 5.7e6. */
#define SBFX_LUMINOUS_EFFICACY 683.002
double sbfx_blackbody_luminance(const sbfx_cmf *cmf, double kelvin);
/* The multiplier of the normalised table (norm = sbfx_blackbody_norm) that makes a fire of
 * that emissivity emit emissivity * L_blackbody(T) / white_luminance: linear light in units of
 * white_luminance cd/m^2 (0 if norm is 0: no light in the table). */
double sbfx_emission_scale_photometric(double norm, double emissivity, double white_luminance);
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

/* ---- phase function (docs/design.md §2.3) ---------------------------------------------------- */

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

/* ---- tone curve of the particles' light (sbfx_tone_map; src/tables/tonemap.c) ----------------- */

#define SBFX_TONE_KNEE 0.6   /* light below this reaches the display unchanged */
/* ...and this much reaches 1 (hue-preserving, per-channel): the particles' radiance ceiling
 * (particle.frag's RADIANCE_CEILING), so no light the particles make reaches 1 before it */
#define SBFX_TONE_WHITE 16384.0
/* filmic (docs/look-fire.md): each channel takes this share of the three channels' mean before
 * the curve and gives it back after it, so light too bright for its hue crosses over to the
 * other channels (red -> orange -> yellow -> white) while light below the knee is untouched */
#define SBFX_TONE_INSET 0.06
/* filmic's curve arrives at 1 here with slope 0 (no crease where it turns white) */
#define SBFX_TONE_FILMIC_WHITE 1024.0
typedef struct sbfx_tone_curve {
    double knee, white, steepness, inverse_log_white;
    bool smooth_white; /* filmic: k + (1 - k)(2u - u^2) of the log shoulder u, flat at white */
} sbfx_tone_curve;
sbfx_tone_curve sbfx_tone_curve_default(void);
/* The curve the composite uses for op: white at SBFX_TONE_FILMIC_WHITE for filmic, else the
 * default. */
sbfx_tone_curve sbfx_tone_curve_for(sbfx_tone_map op);
/* filmic on q = light / room (each channel relative to what the display can still add there;
 * docs/look-fire.md): the identity below the knee; up to peak = max q = 1 the colour scaled by
 * curve(peak) / peak (hue kept); above, blended over two stops into the crossover
 * outset(curve(inset(q))), inset(q)_k = (1 - s) q_k + s mean(q), outset its inverse, clamped
 * to [0, 1]: orange -> yellow -> white. */
void sbfx_tone_filmic(const sbfx_tone_curve *c, const double q[3], double x[3]);
/* v for v <= knee, then the logarithmic shoulder (filmic: its smooth-white form), 1 at and above
 * white; 0 for v <= 0, NaN. */
double sbfx_tone_curve_apply(const sbfx_tone_curve *c, double v);

/* ---- detail volume (docs/design.md §2.4) ----------------------------------------------------- */

/* Tileable (in x, y and t) animated turbulence, size x size x frames floats in [0,1], x fastest:
 * domain-warped fBm, octave gain 2^(-1/2) (src/tables/detail_gen.c, docs/look.md). Deterministic
 * from seed. */
void sbfx_detail_generate(int size, int frames, uint32_t seed, float *out);
/* The same lattice without the warp, octave gain 1/2: the smooth fBm the procedural smoke
 * textures of lit media are made of (src/tables/smoke_texture.c). */
void sbfx_detail_generate_smooth(int size, int frames, uint32_t seed, float *out);
/* The smooth fBm with octave gain `gain` and at most `octaves` octaves (>= 1; the smooth one
 * is gain 1/2, 5 octaves). */
void sbfx_detail_generate_fbm(int size, int frames, uint32_t seed, double gain, int octaves, float *out);

/* The detail volume's half floats, their bits (_Float16 rounds to nearest even): with the x86
 * F16C instruction where the CPU has it (libgcc converts one value at a time in software
 * otherwise, a tenth of a load's CPU); the same values either way. ARM converts in hardware as
 * written. (uint16_t: a compiler that has no _Float16 for x86, clang 14, reads this header too.) */
void sbfx_floats_to_halves(const float *in, uint16_t *out, size_t n);

/* ---- procedural smoke textures of lit media (the lit-smoke seed's appendix) ------------ */

/* Each variant is two RGBA8 layers of size x size texels, row 0 at t = 0:
 *   layer 2v:     rgb = unit normal * 0.5 + 0.5 (tangent space), a = height
 *   layer 2v + 1: r = brightness, g = translucency, b = 0, a = 1
 * with a full mip chain (size a power of two, down to 1 x 1): each level is the rounded 2x2
 * box average of the one above, made here so that the GPU and the reference (ref/lit_ref.h)
 * sample the same texels (glGenerateMipmap's filter is the implementation's choice). Texels are
 * stored level by level, each level layer by layer. */
#define SBFX_SMOKE_LAYERS_PER_VARIANT 2
#define SBFX_SMOKE_MIN_SIZE 16
#define SBFX_SMOKE_MAX_SIZE 512
#define SBFX_SMOKE_MAX_VARIANTS 16

/* Mip levels of a size x size texture (log2(size) + 1), bytes of all texels of `variants`
 * variants, and the float scratch the generator needs. */
int sbfx_smoke_texture_levels(int size);
size_t sbfx_smoke_texture_bytes(int size, int variants);
size_t sbfx_smoke_scratch_floats(int size);
/* Writes the texels into out (sbfx_smoke_texture_bytes) using scratch (sbfx_smoke_scratch_floats
 * floats); allocates nothing. Deterministic from seed. Returns 0, or -1 for a size that is not a
 * power of two in [SBFX_SMOKE_MIN_SIZE, SBFX_SMOKE_MAX_SIZE] or variants outside
 * [1, SBFX_SMOKE_MAX_VARIANTS]. */
int sbfx_smoke_texture_generate(int size, int variants, uint32_t seed, uint8_t *out, float *scratch);
/* The seed the module generates a medium's texture with (desc seed, medium index). */
uint32_t sbfx_smoke_texture_seed(uint32_t seed, int medium);
/* Offset in bytes of a level's first texel. */
size_t sbfx_smoke_level_offset(int size, int layers, int level);

/* The normal map's strength: normals of the height field scaled by this (src/tables/smoke_texture.c). */
#define SBFX_SMOKE_NORMAL_STRENGTH 0.35

/* Limits of particle.frag's lit variant, which the scene parser enforces. */
#define SBFX_LIT_MAX_LIGHTS 4 /* the seed's four; lit media use the frame's first four lights */
#define SBFX_LIT_MAX_STEPS 64 /* MAX_STEPS in particle.frag */

#endif
