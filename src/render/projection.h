/* What a frame's projection says (render/render.h says what the room is for; projection.c;
 * docs/design.md §5), and the host's camera helpers (sbfx_perspective, sbfx_frustum,
 * sbfx_reverse_z, sbfx_look_at in sbfx.h). */
#ifndef SBFX_RENDER_PROJECTION_H
#define SBFX_RENDER_PROJECTION_H

#include <stdbool.h>
#include "sbfx.h"

/* View distance from window depth d: p14 / (scale (d - window_far) + offset); d = window_far
 * (the clear value) is no surface. */
typedef struct sbfx_depth_model {
    float projection[4];     /* p0, p5, p8, p9 */
    double near, far;        /* view distances of the planes; far = INFINITY without one */
    double scale, window_far, offset, p14;
    float ndc[2];            /* ndc_z = ndc[0] * d + ndc[1] (velocity reprojection) */
    bool reversed;           /* near -> larger depth */
} sbfx_depth_model;
bool sbfx_depth_model_from(sbfx *fx, const sbfx_frame *f, sbfx_depth_model *out);
/* The shaders' vec4 u_depth_model: scale, window_far, offset, p14. */
void sbfx_depth_model_uniform(const sbfx_depth_model *m, float out[4]);
/* The shaders' vec3 u_near_model: near / distance = A (d - window_far) + B, A = near scale / p14,
 * B = near offset / p14 (the depth model's reciprocal, folded in double: no division per fragment). */
void sbfx_near_model_uniform(const sbfx_depth_model *m, float out[3]);
/* The window depth a host's depth buffer holds for a view distance under the frame's projection
 * and clip depth mode (the clear value for INFINITY or beyond a finite far plane), and the view
 * distance sbfx reads from a window depth (INFINITY for the clear value): what the shaders
 * compute, in double. A malformed projection gives the clear value / INFINITY. */
float sbfx_window_depth(const sbfx_frame *frame, double distance);
double sbfx_window_distance(const sbfx_frame *frame, float window);

#endif
