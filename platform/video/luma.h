/* Camera luma -> one slice of sbfx's detail volume (DESIGN §2.4).
 *
 * A frame's 8-bit luma (plane 0 of GREY, NV12, NV21, YUV420, YVU420, NV16, NV61; every other
 * byte of YUYV, YVYU, UYVY, VYUY) is centre-cropped to a square, box-filtered down to
 * size x size, normalised (automatic gain and contrast: the slice's mean and spread, smoothed
 * over frames so a flickering light does not pump) and mapped through the same tanh curve as
 * the procedural volume, mean 0.5 and spread about 0.19, so camera and procedural detail
 * perturb particles alike. The result is IEEE half-float bit patterns (_Float16, round to
 * nearest even) for sbfx_detail_push_slice.
 *
 * No allocation after luma_resampler_init: the box tables are sized once for the slice size and
 * the camera's format; every call writes into the caller's buffers. */
#ifndef SBFX_LUMA_H
#define SBFX_LUMA_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define LUMA_MAX_SIZE 512      /* largest detail slice, texels per side */
#define LUMA_MAX_SAMPLES 4     /* per box and axis: a 4K frame still costs 64 reads a texel */

/* Where a frame's luma bytes are: pixel (x, y) is data[y * stride + x * step + offset]. */
struct luma_view {
    const uint8_t *data;
    size_t bytes;    /* readable from data: a short buffer is rejected, not overrun */
    int width, height;
    int stride;      /* bytes per row */
    int step;        /* bytes from one pixel's luma to the next: 1 or 2 */
    int offset;      /* of the first pixel's luma: 1 for UYVY and VYUY */
};

/* Luma layout of a V4L2 pixel format (fourcc): false when its plane 0 is not 8-bit luma. */
bool luma_layout(uint32_t fourcc, int *step, int *offset);

struct luma_resampler {
    int size;                          /* slice side */
    int width, height;                 /* the frame size the tables are for */
    int x0[LUMA_MAX_SIZE + 1];         /* box edges in frame pixels, per texel column */
    int y0[LUMA_MAX_SIZE + 1];         /* ... per texel row */
    float mean, spread;                /* smoothed statistics (spread: standard deviation) */
    bool have_stats;
    float *values;                     /* size * size box means, caller-owned (see below) */
};

/* Plans the boxes of a width x height frame into size x size texels. `values` must hold
 * size * size floats and outlive the resampler. 0, or -EINVAL with a message. */
int luma_resampler_init(struct luma_resampler *r, int size, int width, int height, float *values,
                        char *err, size_t n);

/* One frame -> size * size half-float bit patterns in out (row 0 = the frame's top row).
 * 0, or -EINVAL when the view does not match the planned frame or is too short. */
int luma_to_slice(struct luma_resampler *r, const struct luma_view *view, uint16_t *out);

/* The float -> IEEE half bits conversion used for every texel (round to nearest even). */
uint16_t luma_half_bits(float v);

#endif
