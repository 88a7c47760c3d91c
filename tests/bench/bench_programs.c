/* The names of the module's programs: see bench_programs.h. */
#include "bench_programs.h"

#include <stdio.h>
#include <string.h>

static struct {
    char pending[256];
    GLuint id[BENCH_PROGRAM_NAMES];
    char name[BENCH_PROGRAM_NAMES][256];
    int next;
} programs;

void bench_programs_note(const char *message)
{
    const char *begin = strstr(message, "shader build begin: ");
    unsigned id = 0;
    if (begin) snprintf(programs.pending, sizeof(programs.pending), "%s", begin + strlen("shader build begin: "));
    else if (sscanf(message, "shader build end: program %u", &id) == 1 && id > 0) {
        int slot = programs.next++ % BENCH_PROGRAM_NAMES;
        programs.id[slot] = id;
        memcpy(programs.name[slot], programs.pending, sizeof(programs.pending));
    }
}

const char *bench_program_name(GLuint id)
{
    for (int i = 0; i < BENCH_PROGRAM_NAMES; i++)
        if (programs.id[i] == id && id != 0) return programs.name[i];
    return "";
}

void bench_program_shader(GLuint id, char *shader, size_t shader_size, char *variant, size_t variant_size)
{
    const char *name = bench_program_name(id), *bar = strstr(name, " | ");
    char frag[128] = "?";
    sscanf(name, "%*s %127s", frag);
    snprintf(shader, shader_size, "%s", frag);
    snprintf(variant, variant_size, "%s", bar && bar[3] ? bar + 3 : "-");
}
