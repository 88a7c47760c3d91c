/* detail-from-input: the video itself as sbfx's detail images, as a V4L2 camera is for the
 * player (platform/video/live_detail.h). Each frame's centred square is box-filtered down on
 * the GPU to the detail slice's size and read back one frame late (gl_guest_detail); here its
 * luma is taken with the stream's own matrix (BT.601, BT.709, BT.2020: Y' = Kr R' + (1 - Kr - Kb)
 * G' + Kb B') and goes through the player's normalisation (luma.h: automatic gain and contrast
 * smoothed over frames, the procedural volume's tanh curve, half floats), ready for
 * sbfx_detail_push_slice. Buffers are allocated at start; a frame allocates nothing. */
#ifndef SBFX_GST_INPUT_DETAIL_H
#define SBFX_GST_INPUT_DETAIL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "video/luma.h"

struct input_detail {
    int size;                  /* slice side (sbfx_detail_dimensions) */
    double kr, kb;             /* the stream's luma weights */
    uint8_t *luma;             /* size * size */
    float *values;             /* the resampler's box means */
    uint16_t *slice;           /* size * size half floats, ready to push */
    struct luma_resampler resampler;
    bool ready;                /* slice holds a frame not pushed yet */
    uint64_t slices;           /* frames made into slices */
    uint64_t distinct;         /* ... that differed from the one before */
    uint64_t last_hash;
};

/* 0, or -1 with a message (sizes out of range, out of memory). Weights default to BT.709. */
int input_detail_start(struct input_detail *d, int size, char *err, size_t n);
void input_detail_set_weights(struct input_detail *d, double kr, double kb);
/* gl_guest_detail's `take`: size x size RGBA bytes -> d->slice (user is the input_detail). */
void input_detail_take(const uint8_t *rgba, void *user);
void input_detail_stop(struct input_detail *d);

#endif
