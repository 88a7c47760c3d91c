/* The names of the module's programs, for the bench's per-program counts (bench_fragments.h):
 * with SBFX_SHADER_LOG=1 set before sbfx_create, sbfx logs "shader build begin: VERT FRAG |
 * DEFINES" and "shader build end: program N" around each program it builds; a bench's log
 * callback hands those lines here, and a program's id then gives back "VERT FRAG | DEFINES"
 * (the last BENCH_PROGRAM_NAMES programs built: a module's are among them). */
#ifndef SBFX_BENCH_PROGRAMS_H
#define SBFX_BENCH_PROGRAMS_H

#include <GLES3/gl3.h>
#include <stddef.h>

#define BENCH_PROGRAM_NAMES 64

/* Takes one INFO line of sbfx's log (others are ignored). */
void bench_programs_note(const char *message);
/* "VERT FRAG | DEFINES" of a program sbfx built, "" for one it did not. */
const char *bench_program_name(GLuint id);
/* Its fragment shader's file name and its defines ("-": none), as tools/shader-stats.sh names them. */
void bench_program_shader(GLuint id, char *shader, size_t shader_size, char *variant, size_t variant_size);

#endif
