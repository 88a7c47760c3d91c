/* The picture's fine structure (issue 17 "Method for β", docs/design.md §8, docs/look.md): one
 * implementation, used by the unit test (tests/unit/test_look_metrics.c), the GL test
 * (tests/gl/test_gl_look.c) and the bench (tests/look/bench_look.c -> build/bench/look.csv).
 *
 *   Y        luminance of the sRGB output, linearised, Rec. 709 weights
 *   mask     pixels the effect changes by more than 4 levels (any channel) where the background
 *            alone is smooth (its 3x3 neighbourhood spans at most 2 levels in every channel)
 *   E(s)     for s = 2, 4, 8, 16, 32 px: mean over the mask eroded by 2s px (Chebyshev) of
 *            (G_{s/2} * Y - G_s * Y)^2, G a Gaussian of that standard deviation
 *   beta     2 + least-squares slope of log E(s) against log s over 4..32 px
 *   beta_coarse   the same over 8..32 px (the reduced-resolution check)
 * A power-law image P(k) ~ k^-beta gives back beta within 0.15; smooth blobs give about 6.
 * No GL; allocates its work memory per call (tests and benches only). */
#ifndef SBFX_LOOK_METRICS_H
#define SBFX_LOOK_METRICS_H

#include <stddef.h>
#include <stdint.h>

#define LOOK_SCALES 5 /* s = 2, 4, 8, 16, 32 px */
#define LOOK_CHANGE_LEVELS 4 /* the effect changes a pixel by more than this */
#define LOOK_SMOOTH_LEVELS 2 /* the background's 3x3 span at most this: smooth */

typedef struct look_spectrum {
    double energy[LOOK_SCALES]; /* E(s), NAN where the eroded mask is empty */
    size_t pixels[LOOK_SCALES]; /* mask pixels left after erosion by 2s */
    double beta;                /* over 4..32 px; NAN if an E(s) is missing or zero */
    double beta_coarse;         /* over 8..32 px */
    size_t mask_pixels;         /* before erosion */
} look_spectrum;

/* s of index i: 2 << i. */
int look_scale(int i);

/* Linear luminance of n RGBA8 sRGB pixels into y. */
void look_luminance(const uint8_t *rgba, size_t n, double *y);

/* The effect's mask (1/0 per pixel) from the output and the background alone (RGBA8, same
 * size); returns the number of pixels set. */
size_t look_effect_mask(const uint8_t *out_rgba, const uint8_t *background_rgba, int width, int height,
                        uint8_t *mask);

/* E(s) and beta of y (width x height) over mask. Returns 0, or -1 when out of memory. */
int look_measure(const double *y, const uint8_t *mask, int width, int height, look_spectrum *out);

/* Both steps from RGBA8 images. Returns 0 or -1 (out of memory). */
int look_measure_rgba(const uint8_t *out_rgba, const uint8_t *background_rgba, int width, int height,
                      look_spectrum *out);

/* 2 + slope of log E against log s over indices first..last (NAN if any is missing or <= 0). */
double look_beta_fit(const double energy[LOOK_SCALES], int first, int last);

/* Band energies the issue names: 2-8 px = E(4) + E(8), 8-32 px = E(16) + E(32) (the DoG
 * bands [2,4], [4,8] and [8,16], [16,32] px). */
double look_band_fine(const look_spectrum *s);
double look_band_coarse(const look_spectrum *s);

#endif
