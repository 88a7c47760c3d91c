/* Procedural detail volume (docs/design.md §2.4, docs/look.md): tileable, looping, animated turbulence.
 *
 * A domain-warped fBm of 3D gradient noise: D(p) = fbm(p + WARP * q(p)), q = two coarse fBm
 * fields (the warp, Inigo Quilez's "domain warping"), which stretches the fine octaves into
 * filaments and wisps instead of round blobs. The octaves' amplitudes fall by 2^(-5/6) per
 * octave: band energy 2^(-5/3) per octave, the spectrum k^-(11/3) of a Kolmogorov scalar seen in
 * a slice (issue 17, "turbulent spectra from octaves"), from 4 cells across the volume down to
 * 2 texels per cell.
 *
 * Axes x, y (size texels) and t (frames) are all periodic: octave k has a lattice of
 * cells[axis] cells per axis, texel x maps to lattice coordinate x * cells / size, and lattice
 * indices are taken modulo cells, so texel size is the same lattice point as texel 0. The warp
 * is periodic too, so the warped field still tiles in x and y and loops in time (the GPU's
 * REPEAT wrap then interpolates across the seams).
 *
 * The sum is standardised over the whole volume and mapped through a tanh curve to (0, 1):
 * mean 0.5, standard deviation about 0.19, no hard clipping (a clamp would leave flat plateaus
 * in the perturbation). Deterministic from the seed; no allocation but the output. */
#include <math.h>
#include <stdbool.h>
#include "tables/tables.h"

#define MAX_OCTAVES 7
#define BASE_CELLS_XY 4 /* coarsest octave: 4 features across the image */
#define BASE_CELLS_T 2  /* ...and 2 across the animation loop: slow evolution */
#define OCTAVE_GAIN 0.6674199270850172 /* 2^(-7/12): band energy 2^(-7/6) per octave */
#define WARP_OCTAVES 2  /* the warp field: the two coarsest octaves */
#define WARP_TEXELS_PER_SIZE 0.08 /* warp amplitude, in volume widths per unit of q */
#define SMOOTH_OCTAVES 5 /* the smooth fBm: the first generator's octaves */
#define OUTPUT_GAIN 0.45 /* tanh gain on the standardised sum: output std ≈ 0.19 */

/* The 12 cube-edge gradient directions of improved Perlin noise, gradient h % 12 of a lattice
 * point: its dot product with the offset d = (dx, dy, dt) from the point is
 * sign[0] * d[axis[0]] + sign[1] * d[axis[1]] (h 0: dx + dy, 1: -dx + dy, ... 11: -dy - dt).
 * Multiplying by +-1 is exact, so this is bit for bit the sum written out per case, without the
 * 12-way branch the CPU could not predict. */
typedef struct gradient {
    double sign[2];
    int axis[2];
} gradient;

static const gradient gradients[12] = {
    {{1, 1}, {0, 1}}, {{-1, 1}, {0, 1}}, {{1, -1}, {0, 1}}, {{-1, -1}, {0, 1}},
    {{1, 1}, {0, 2}}, {{-1, 1}, {0, 2}}, {{1, -1}, {0, 2}}, {{-1, -1}, {0, 2}},
    {{1, 1}, {1, 2}}, {{-1, 1}, {1, 2}}, {{1, -1}, {1, 2}}, {{-1, -1}, {1, 2}},
};

typedef struct octave {
    int cells[3];      /* lattice period per axis (x, y, t) */
    double offset[3];  /* random lattice shift, so lattice points do not sit on texels */
    uint32_t salt;     /* decorrelates the octaves' gradients */
    bool nested_hash;  /* the first generator's hash (the smooth fBm keeps its textures) */
    double amplitude;
    /* The last cell this octave was evaluated in and its corners' gradients: consecutive texels
     * mostly fall in the same cell (2 or more texels per cell), so most evaluations skip the
     * wrapping, the 8 hashes and their gradients' lookup (same values: the output is bit for
     * bit the same). */
    double step[3];    /* cells / size (frames): lattice units per texel, where that is exact */
    bool exact_step;   /* size and frames are powers of two: x * step is x * cells / size */
    bool cached;
    int cell[3];
    const gradient *corner[2][2][2]; /* the gradients of its corners (their hashes % 12) */
} octave;

/* "lowbias32" integer mixer (C. Wellons): good avalanche, cheap, portable. */
static uint32_t mix32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

static int wrap(int i, int period)
{
    int m = i % period;
    return m < 0 ? m + period : m;
}

/* The lattice point's hash from its wrapped indices: one mix of a linear combination (odd
 * multipliers), a quarter of the hashing of the first generator's nested mixes, which dominated
 * the volume's load time; the smooth fBm keeps the nested one. */
static uint32_t lattice_hash(const octave *o, uint32_t wx, uint32_t wy, uint32_t wt)
{
    if (o->nested_hash) return mix32(o->salt ^ mix32(wx ^ mix32(wy ^ mix32(wt))));
    return mix32(o->salt + wx * 0x9E3779B1u + wy * 0x85EBCA77u + wt * 0xC2B2AE3Du);
}

/* Quintic fade: C2-continuous across cells, so the fBm has no visible lattice creases. */
static double fade(double t)
{
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

static double lerp(double a, double b, double t)
{
    return a + (b - a) * t;
}

/* The gradients of the 8 corners of cell i (from their wrapped lattice indices' hashes), kept in
 * the octave. */
static void cell_gradients(octave *o, const int i[3])
{
    if (o->cached && o->cell[0] == i[0] && o->cell[1] == i[1] && o->cell[2] == i[2]) return;
    uint32_t w[3][2]; /* wrapped lattice indices of the cell's two corners per axis */
    for (int k = 0; k < 3; k++) {
        w[k][0] = (uint32_t)wrap(i[k], o->cells[k]);
        w[k][1] = (uint32_t)wrap(i[k] + 1, o->cells[k]);
        o->cell[k] = i[k];
    }
    for (int dz = 0; dz < 2; dz++)
        for (int dy = 0; dy < 2; dy++)
            for (int dx = 0; dx < 2; dx++)
                o->corner[dz][dy][dx] = &gradients[lattice_hash(o, w[0][dx], w[1][dy], w[2][dz]) % 12];
    o->cached = true;
}

/* floor(x) for the lattice's coordinates (|x| well below 2^53): a conversion and a compare,
 * where x86-64's baseline has no rounding instruction and floor() is a call. */
static double lattice_floor(double x)
{
    double t = (double)(long long)x;
    return t > x ? t - 1.0 : t;
}

/* Periodic gradient noise at lattice coordinates p (roughly in [-1, 1]). */
static double gradient_noise(octave *o, const double p[3])
{
    int i[3];
    double f[3], s[3];
    for (int k = 0; k < 3; k++) {
        double fl = lattice_floor(p[k]);
        i[k] = (int)fl;
        f[k] = p[k] - fl;
        s[k] = fade(f[k]);
    }
    cell_gradients(o, i);
    double c[2][2][2];
    for (int dz = 0; dz < 2; dz++)
        for (int dy = 0; dy < 2; dy++)
            for (int dx = 0; dx < 2; dx++) {
                const double d[3] = {f[0] - dx, f[1] - dy, f[2] - dz};
                const gradient *g = o->corner[dz][dy][dx];
                c[dz][dy][dx] = g->sign[0] * d[g->axis[0]] + g->sign[1] * d[g->axis[1]];
            }
    double y0 = lerp(lerp(c[0][0][0], c[0][0][1], s[0]), lerp(c[0][1][0], c[0][1][1], s[0]), s[1]);
    double y1 = lerp(lerp(c[1][0][0], c[1][0][1], s[0]), lerp(c[1][1][0], c[1][1][1], s[0]), s[1]);
    return lerp(y0, y1, s[2]);
}

static bool power_of_two(int v)
{
    return v > 0 && (v & (v - 1)) == 0;
}

static int min_int(int a, int b)
{
    return a < b ? a : b;
}

/* Octave k doubles the previous octave's lattice, up to a cap per axis: no finer than 2 texels
 * per cell in x/y (finer would alias) and 4 frames per cell in t (finer would flicker). Stops
 * early when x/y cannot get finer any more. Returns the number of octaves. */
static int plan_octaves(int size, int frames, uint32_t seed, double gain, octave *o)
{
    int cap_xy = size / 2 > 1 ? size / 2 : 1;
    int cap_t = frames / 4 > 1 ? frames / 4 : 1;
    sbfx_rng rng;
    sbfx_rng_seed(&rng, ((uint64_t)seed << 32) ^ UINT64_C(0x5bf03635d7e1a2c9));
    int n = 0;
    double amplitude = 1.0;
    for (int k = 0; k < MAX_OCTAVES; k++) {
        int cells_xy = min_int(BASE_CELLS_XY << k, cap_xy);
        if (k > 0 && cells_xy == o[n - 1].cells[0]) break;
        o[n].cells[0] = o[n].cells[1] = cells_xy;
        o[n].cells[2] = min_int(BASE_CELLS_T << k, cap_t);
        for (int a = 0; a < 3; a++) o[n].offset[a] = sbfx_rng_uniform(&rng);
        o[n].salt = sbfx_rng_u32(&rng);
        o[n].nested_hash = false;
        o[n].amplitude = amplitude;
        o[n].cached = false;
        o[n].exact_step = power_of_two(size) && power_of_two(frames);
        for (int a = 0; a < 3; a++) o[n].step[a] = (double)o[n].cells[a] / (a < 2 ? size : frames);
        amplitude *= gain;
        n++;
    }
    return n;
}

/* x * cells / size: with a power of two for size, x * (cells / size), the same number (a power of
 * two's reciprocal is exact) without a division. */
static double lattice_coordinate(const octave *o, int axis, double x, int size)
{
    return o->exact_step ? x * o->step[axis] : x * o->cells[axis] / size;
}

static double fbm(octave *o, int n, double x, double y, double t, int size, int frames)
{
    double sum = 0.0;
    for (int k = 0; k < n; k++) {
        double p[3] = {lattice_coordinate(&o[k], 0, x, size) + o[k].offset[0],
                       lattice_coordinate(&o[k], 1, y, size) + o[k].offset[1],
                       lattice_coordinate(&o[k], 2, t, frames) + o[k].offset[2]};
        sum += o[k].amplitude * gradient_noise(&o[k], p);
    }
    return sum;
}

/* The warped field at texel (x, y, t): the two warp fields q (their own octaves, with other
 * salts and offsets) displace x and y before the main fBm. */
static double warped(octave *o, int n, octave *wx, octave *wy, int nw, double x, double y,
                     double t, int size, int frames)
{
    double shift = WARP_TEXELS_PER_SIZE * size;
    double qx = fbm(wx, nw, x, y, t, size, frames), qy = fbm(wy, nw, x, y, t, size, frames);
    return fbm(o, n, x + shift * qx, y + shift * qy, t, size, frames);
}

/* The volume with octave gain `gain`, at most `octaves` octaves and (turbulent) the domain warp. */
static void generate(int size, int frames, uint32_t seed, double gain, int octaves, bool turbulent, float *out)
{
    if (!out || size < 1 || frames < 1) return;
    octave o[MAX_OCTAVES], wx[MAX_OCTAVES], wy[MAX_OCTAVES];
    int n = plan_octaves(size, frames, seed, gain, o);
    int nw = plan_octaves(size, frames, seed ^ 0x77a12f3du, gain, wx);
    plan_octaves(size, frames, seed ^ 0x1b873593u, gain, wy);
    nw = !turbulent ? 0 : nw < WARP_OCTAVES ? nw : WARP_OCTAVES;
    if (n > octaves) n = octaves;
    for (int k = 0; k < n; k++) o[k].nested_hash = !turbulent;
    size_t count = (size_t)size * (size_t)size * (size_t)frames, idx = 0;
    double sum = 0.0, sum2 = 0.0;
    for (int t = 0; t < frames; t++)
        for (int y = 0; y < size; y++)
            for (int x = 0; x < size; x++) {
                double v = warped(o, n, wx, wy, nw, x, y, t, size, frames);
                out[idx++] = (float)v;
                sum += v;
                sum2 += v * v;
            }
    double mean = sum / (double)count;
    double var = sum2 / (double)count - mean * mean;
    double inv_std = var > 1e-24 ? 1.0 / sqrt(var) : 0.0; /* constant volume: all 0.5 */
    for (size_t i = 0; i < count; i++)
        out[i] = (float)(0.5 + 0.5 * tanh(OUTPUT_GAIN * (out[i] - mean) * inv_std));
}

void sbfx_detail_generate(int size, int frames, uint32_t seed, float *out)
{
    generate(size, frames, seed, OCTAVE_GAIN, MAX_OCTAVES, true, out);
}

void sbfx_detail_generate_smooth(int size, int frames, uint32_t seed, float *out)
{
    generate(size, frames, seed, 0.5, SMOOTH_OCTAVES, false, out);
}

void sbfx_detail_generate_fbm(int size, int frames, uint32_t seed, double gain, int octaves, float *out)
{
    generate(size, frames, seed, gain, octaves < 1 ? 1 : octaves, false, out);
}
