/* Fragments each of the module's programs shades, counted on the GPU (make bench's Mali
 * estimates: tests/bench/run.sh, tools/mali-accuracy.awk, tools/boards-table.sh).
 *
 * While armed, every draw (glDrawArrays and glDrawArraysInstanced, through the linker's --wrap:
 * tests/bench/bench_gl.h) is drawn a second time with the same vertex shader — the source of the
 * one attached to the current program, defines and all —, vertex array and vertex uniforms, and
 * a fragment shader that writes 1, additively (GL_ONE, GL_ONE), into an RGBA16F target of the
 * draw's viewport size kept for that program; the sums of the targets' read-backs are the
 * fragments each program's draws made (exact: a half float counts integers to 2048 per pixel).
 * A draw masked by its target's depth test (mixed resolution's refinement: a depth texture;
 * early termination of the particles: a depth renderbuffer) is counted against the same depth:
 * what passes is what a GPU with early depth tests shades.
 * sbfx's shaders discard nothing (but refine_mark.frag and terminate_mark.frag, counted whole:
 * they run everywhere), so
 * this is what they shade: the particle pass's quads with
 * their overlap, the passes over the screen's tiles (render/tiles.h) and the full-screen ones —
 * counted, not assumed equal to the screen. Targets are read back when a program draws at
 * another size and when counting ends. */
#ifndef SBFX_BENCH_FRAGMENTS_H
#define SBFX_BENCH_FRAGMENTS_H

#include <GLES3/gl3.h>
#include <stdbool.h>

#define BENCH_FRAGMENT_DRAWS 24 /* programs: the draws of one program are summed */

typedef struct bench_fragment_tally {
    int draws; /* programs seen */
    GLuint program[BENCH_FRAGMENT_DRAWS];
    double fragments[BENCH_FRAGMENT_DRAWS];
    double masked[BENCH_FRAGMENT_DRAWS]; /* of those, the draws masked by a depth test (mixed
                                            resolution's refinement, render/refine.c) */
    double masked_fragments; /* their sum: the refined fragments */
    bool failed; /* a count could not be made (message on stderr) */
} bench_fragment_tally;

/* Arms counting into `tally` (cleared); bench_fragments_end reads the last counts and disarms. */
void bench_fragments_begin(bench_fragment_tally *tally);
void bench_fragments_end(void);
/* Called by the draw wrappers after the real draw (instances 0: glDrawArrays). */
void bench_fragments_draw(GLenum mode, GLint first, GLsizei count, GLsizei instances);
/* Deletes the counting programs and targets. */
void bench_fragments_destroy(void);

#endif
