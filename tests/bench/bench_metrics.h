/* Image comparison and statistics of the accuracy benchmark. No GL.
 *
 * Errors are in 8-bit levels (0..255) of the RGB channels of the RGBA8 output: the GPU's
 * stored byte against the CPU reference's unrounded value x 255. PSNR uses peak 255. */
#ifndef SBFX_BENCH_METRICS_H
#define SBFX_BENCH_METRICS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

typedef struct bench_error {
    double sum_abs, sum_sq, max_abs;
    size_t count;                           /* channel values compared */
    double edge_sum_abs, edge_sum_sq, edge_max_abs;
    size_t edge_count;
} bench_error;

/* Adds one image: gpu RGBA8 (n pixels), reference RGB (n x 3, 0..255), edge mask (n, may be
 * NULL: no edge statistics). */
void bench_error_add(bench_error *e, const uint8_t *gpu_rgba, const double *ref_rgb, const uint8_t *edge,
                     size_t n);
double bench_error_mean(const bench_error *e);
double bench_error_edge_mean(const bench_error *e);
double bench_psnr(double sum_sq, size_t count); /* +inf for identical images */

/* Pixels within `dilate` pixels (Chebyshev) of an opaque silhouette: a depth discontinuity,
 * found as a jump in the second difference of 1/distance (planes are affine in 1/z on screen,
 * so slanted floors and box faces do not count) above `relative` of 1/distance. */
void bench_edge_mask(const double *distance, int width, int height, double relative, int dilate,
                     uint8_t *mask);

/* Median, minimum and maximum of n values (the array is sorted in place). */
void bench_stats(double *values, int n, double *median, double *min, double *max);

/* pareto[i] = true when no other included point is at least as fast and at least as accurate,
 * and strictly better in one of the two. */
void bench_pareto(const double *ms, const double *err, const bool *include, int n, bool *pareto);

/* DIR/NAME opened for writing; a bench that cannot write its results stops with the reason. */
FILE *bench_open_out(const char *dir, const char *name);

#endif
