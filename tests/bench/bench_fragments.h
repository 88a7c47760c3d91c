/* Fragments the particle pass shades, counted on the GPU (make bench's Mali estimate).
 *
 * While armed, every instanced draw (the particle pass's: tests/bench/bench_gl.h) is drawn a
 * second time with the same vertex shader (particle.vert, embedded) and vertex array, and a
 * fragment shader that writes 1, additively (GL_ONE, GL_ONE) into an RGBA16F target of the
 * draw's viewport size; the sum of the read-back is the number of fragments the draw made
 * (exact: a half float counts integers to 2048 per pixel). The particle shaders discard nothing,
 * so this is what they shade. Each draw's count is kept against the program that was current. */
#ifndef SBFX_BENCH_FRAGMENTS_H
#define SBFX_BENCH_FRAGMENTS_H

#include <GLES3/gl3.h>
#include <stdbool.h>

#define BENCH_FRAGMENT_DRAWS 16 /* programs: the draws of one program are summed */

typedef struct bench_fragment_tally {
    int draws; /* programs seen */
    GLuint program[BENCH_FRAGMENT_DRAWS];
    double fragments[BENCH_FRAGMENT_DRAWS];
    bool failed; /* a count could not be made (message on stderr) */
} bench_fragment_tally;

/* Arms counting into `tally` (cleared); bench_fragments_end disarms. */
void bench_fragments_begin(bench_fragment_tally *tally);
void bench_fragments_end(void);
/* Called by the glDrawArraysInstanced wrapper after the real draw. */
void bench_fragments_draw(GLenum mode, GLint first, GLsizei count, GLsizei instances);
/* Deletes the counting program and target. */
void bench_fragments_destroy(void);

#endif
