/* One shot of an example scene for the look measurements (docs/look.md): the scene file's
 * module over the opaque test scene (platform/host/test_scene.h), seen from the scene's camera turned
 * by an azimuth offset, at time t, at a target divisor, with the detail on or off; the output
 * and the background alone read back as RGBA8 (bottom row first). Needs a current GLES 3.0
 * context. Shared by tests/gl/test_gl_look.c and tests/look/bench_look.c. */
#ifndef SBFX_LOOK_RENDER_H
#define SBFX_LOOK_RENDER_H

#include <GLES3/gl3.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "sbfx.h"
#include "host/test_scene.h"

typedef struct look_shot {
    const char *scene_path;  /* a scene file (NULL: the built-in explosion) */
    double t;                /* seconds after load (whole 1/120 s steps) */
    float azimuth_offset;    /* degrees added to the scene camera's azimuth */
    int divisor;             /* particle target divisor, 1 2 4 8; 0: the scene's (else 4) */
    bool detail_off;         /* every medium's detail strength set to 0 after load */
    const sbfx_desc *base;   /* optional: other desc fields (scene, divisor, log are set here) */
    bool detail_unloaded;    /* strengths 0 and sbfx_reload: programs without the detail at all */
    int reps;                /* sbfx_render this many times (0: once); particle_ms = the median */
    bool fire_dark;          /* the fire medium's emission set to 0 (its particles still drawn) */
} look_shot;

typedef struct look_renderer {
    int width, height;
    struct test_scene scene;
    GLuint out_fbo, out_renderbuffer;
    uint8_t *out_rgba, *background_rgba; /* width x height x 4 */
    double particle_ms;                  /* wall time of the last shot's sbfx_render (glFinish), median */
} look_renderer;

/* 0, or -1 with a message in err. */
int look_renderer_open(look_renderer *r, int width, int height, char *err, size_t n);
void look_renderer_close(look_renderer *r);

/* Renders the shot into r->out_rgba and r->background_rgba. 0, or -1 with a message. */
int look_render(look_renderer *r, const look_shot *shot, char *err, size_t n);

#endif
