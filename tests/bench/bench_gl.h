/* GL side of the accuracy benchmark: timers, the isolated particle pass, read-backs.
 *
 * Timing: GL_EXT_disjoint_timer_query (GL_TIME_ELAPSED_EXT) where the context has it, else
 * glFinish-bracketed wall time; both are always measured when the extension is there, so the
 * two can be compared.
 *
 * The particle pass alone: the module's passes are private, so the bench is linked with
 * `-Wl,--wrap=glBindFramebuffer -Wl,--wrap=glDrawArraysInstanced -Wl,--wrap=glDrawArrays`
 * (Makefile, bench section; the draws are also where bench_fragments.h counts fragments). While
 * a particle-pass measurement is armed, every bind of a draw framebuffer ends one timed segment
 * and starts the next (glFinish at each boundary, a timer query per segment); the particle pass
 * is the one segment that issues instanced draws of particles (a program with particle.vert's
 * a_center_radius: the depth and composite passes draw instanced tile rectangles, the post passes
 * full-screen triangles). If not exactly one segment does, the measurement says so (returns
 * false) instead of timing something else. */
#ifndef SBFX_BENCH_GL_H
#define SBFX_BENCH_GL_H

#include <GLES3/gl3.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct bench_timer {
    bool has_query;   /* GL_EXT_disjoint_timer_query is usable */
    GLuint query;
} bench_timer;

/* One measurement: GPU time (timer query, NAN if none or disjoint) and wall time, in ms. */
typedef struct bench_sample {
    double gpu_ms, wall_ms;
} bench_sample;

void bench_timer_init(bench_timer *t);
void bench_timer_destroy(bench_timer *t);

/* Brackets fn(user) with glFinish and, where available, a TIME_ELAPSED query. */
bench_sample bench_time_call(bench_timer *t, void (*fn)(void *), void *user);

/* Runs fn(user) (which must render one sbfx frame) and times only its particle pass. Returns
 * false if the pass was not seen exactly once (see above). */
bool bench_time_particle_pass(bench_timer *t, void (*fn)(void *), void *user, bench_sample *out);

/* An RGBA8 colour framebuffer of w x h for sbfx to composite into. */
typedef struct bench_target {
    GLuint fbo, renderbuffer;
    int width, height;
} bench_target;

int bench_target_create(bench_target *t, int width, int height);
void bench_target_destroy(bench_target *t);
/* Copies the colour of framebuffer `from` into the target (the scene under the particles). */
void bench_target_fill_from(const bench_target *t, GLuint from);
/* glReadPixels RGBA8 of the target's (or any) framebuffer, bottom row first. */
void bench_read_rgba8(GLuint fbo, int width, int height, uint8_t *out);

/* The window-space depth of a depth texture, texel by texel, as floats (bottom row first),
 * through a tiny pass into an RGBA32F target: ES 3.0 cannot glReadPixels depth. Returns 0 or
 * -1 (GL_EXT_color_buffer_float missing, shader or framebuffer failure) with a message. */
int bench_read_depth(GLuint depth_texture, int width, int height, float *out, char *err, size_t n);

/* GL_RENDERER / GL_VERSION strings (never NULL). */
const char *bench_gl_renderer(void);
const char *bench_gl_version(void);

#endif
