/* What the module computes on the CPU, in double precision, at load: the black-body and phase
 * tables, the detail volume, the procedural smoke textures, and the deterministic RNG of the
 * simulation. Pure libc (+ lcms2 to read the CIE tables), no GL.
 *
 * The table lookups (sbfx_*_table_lookup) read a table the way the GPU does; they live beside
 * the builders so that each table's grid is defined in one file. Only the tests and the CPU
 * reference (ref/, which is not part of the runtime library) call them. */
#ifndef SBFX_TABLES_H
#define SBFX_TABLES_H

#include <stddef.h>
#include <stdint.h>
#include "sbfx.h"

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
/* The normalisation used by the table: 1 / Y(max_kelvin), so luminance is <= 1 in the table. */
double sbfx_blackbody_norm(const sbfx_cmf *cmf, double max_kelvin);
/* Table of `size` entries, entry i at T_i = max_kelvin * i / (size - 1), RGB (3 doubles each). */
void sbfx_blackbody_table(const sbfx_cmf *cmf, double max_kelvin, int size, double *rgb_out);
/* Linear interpolation in such a table, T clamped to [0, max_kelvin] (what the GPU does). */
void sbfx_blackbody_table_lookup(const double *table, int size, double max_kelvin, double kelvin,
                                 double rgb[3]);

/* ---- phase function (DESIGN §2.3) ----------------------------------------------------- */

/* Cornette–Shanks shaped phase function, normalised to 1 over the sphere (1/sr).
 * cos_theta is the cosine of the scattering angle between the light's direction of travel and
 * the direction the scattered light leaves in (1 = light goes straight on), so positive g
 * peaks forward: P = 3(1-g^2)(1+c^2) / (8π (2+g^2) (1+g^2-2gc)^{3/2}). */
double sbfx_phase(double cos_theta, double g);
#define SBFX_PHASE_G_MAX 0.99
/* Table n_cos x n_g, row-major by g: entry (i, j) at cos = -1 + 2i/(n_cos-1),
 * g = -G_MAX + 2 G_MAX j/(n_g-1). */
void sbfx_phase_table(int n_cos, int n_g, double *out);
/* Bilinear lookup in that table (what the GPU does), arguments clamped to the table's range. */
double sbfx_phase_table_lookup(const double *table, int n_cos, int n_g, double cos_theta, double g);

/* ---- detail volume (DESIGN §2.4) ------------------------------------------------------ */

/* Tileable (in x, y and t) animated fBm, size x size x frames floats in [0,1], x fastest.
 * Deterministic from seed. */
void sbfx_detail_generate(int size, int frames, uint32_t seed, float *out);

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

/* Limits of particle.frag's lit variant, which the scene parser enforces. */
#define SBFX_LIT_MAX_LIGHTS 4 /* the seed's four; lit media use the frame's first four lights */
#define SBFX_LIT_MAX_STEPS 64 /* MAX_STEPS in particle.frag */

/* ---- small deterministic RNG shared by simulation, tests and tools -------------------- */
typedef struct sbfx_rng { uint64_t state; } sbfx_rng;
void sbfx_rng_seed(sbfx_rng *rng, uint64_t seed);
uint32_t sbfx_rng_u32(sbfx_rng *rng);
double sbfx_rng_uniform(sbfx_rng *rng); /* [0,1) */
double sbfx_rng_range(sbfx_rng *rng, double lo, double hi);

#endif
