/* The CPU reference of one frame of a module (ref/reference_frame.h) as the benches use it: the
 * `exact` model per full-resolution pixel in double precision, of the particles the module draws
 * (sbfx_frame_particles), with its media, lights, detail volume and black-body unit, composited
 * over the host scene's RGBA8 colour through the default tone map. Shared by the accuracy bench
 * (bench_accuracy.c) and the budget bench (budget/bench_budget.c). */
#ifndef SBFX_BENCH_REFERENCE_H
#define SBFX_BENCH_REFERENCE_H

#include <stdint.h>
#include "internal.h"
#include "reference_frame.h"

typedef struct bench_reference {
    const float *detail;         /* the module's detail volume (sbfx_detail_generate, seed 1) */
    int detail_size, detail_frames;
    const sbfx_cmf *cmf;
} bench_reference;

/* Renders the reference of fx's particles seen through `frame` (width x height): opaque view
 * distances per pixel (INFINITY: none), the scene's RGBA8 colour; writes out_rgb (w x h x 3,
 * 0..255, unrounded) and, if not NULL, footprint (pixels some particle covers). Returns the
 * particle count, or -1 when out of memory. */
int bench_reference_render(const bench_reference *r, sbfx *fx, const sbfx_frame *frame, const double *distance,
                           const uint8_t *scene_rgba, double *out_rgb, uint8_t *footprint);

#endif
