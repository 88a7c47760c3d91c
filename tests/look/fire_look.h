/* Renders an effect over the test scene (platform/test_scene.h) the way fire_metric.h measures
 * it: the output, the background alone, and the pixels the fire's own emission changes; used
 * by tests/gl/test_gl_fire_look.c and the bench (tests/look/bench_look_fire.c). Needs a current
 * GLES 3.0 context. */
#ifndef SBFX_FIRE_LOOK_H
#define SBFX_FIRE_LOOK_H

#include <GLES3/gl3.h>
#include <stddef.h>
#include <stdint.h>
#include "fire_metric.h"
#include "sbfx.h"
#include "host/test_scene.h"

typedef struct fire_look {
    int width, height;
    struct test_scene scene;
    GLuint fbo, renderbuffer;                 /* RGBA8: what a display shows */
    uint8_t *out, *background, *no_fire, *fire_mask; /* bottom row first */
} fire_look;

int fire_look_open(fire_look *l, int width, int height, char *err, size_t n);
void fire_look_close(fire_look *l);

/* One view of `scene` (its camera) at t seconds after its timeline starts, particle target
 * 1/scale: fills l->out, l->background, l->no_fire (the fire's emission off) and l->fire_mask
 * (1 where the emission changes the picture by more than FIRE_METRIC_LEVELS), and the ratios:
 * over the mask when use_fire_mask, else over every pixel the effect changes. 0 or -1 (err). */
int fire_look_measure(fire_look *l, const sbfx_scene *scene, sbfx_tone_map op, double t, int scale,
                      int use_fire_mask, fire_ratios *r, char *err, size_t n);

#endif
