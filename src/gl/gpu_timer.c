/* GPU time per frame from a ring of GL_EXT_disjoint_timer_query queries: gpu_timer.h. */
#include "gl/gpu_timer.h"

#include <stdio.h>
#include <string.h>

#ifndef GL_TIME_ELAPSED_EXT
#define GL_TIME_ELAPSED_EXT 0x88BF
#endif
#ifndef GL_GPU_DISJOINT_EXT
#define GL_GPU_DISJOINT_EXT 0x8FBB
#endif

static bool has_extension(const char *name)
{
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; i++) {
        const char *ext = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (ext && strcmp(ext, name) == 0)
            return true;
    }
    return false;
}

/* Desktop OpenGL's version string starts with its number, ES's with "OpenGL ES". */
static bool desktop_context(int *version)
{
    const char *v = (const char *)glGetString(GL_VERSION);
    int major = 0, minor = 0;
    if (!v || strncmp(v, "OpenGL ES", 9) == 0 || sscanf(v, "%d.%d", &major, &minor) != 2)
        return false;
    *version = major * 10 + minor;
    return true;
}

bool gpu_timer_supported(void)
{
    int version = 0;
    if (desktop_context(&version))
        return version >= 33 || has_extension("GL_ARB_timer_query");
    return has_extension("GL_EXT_disjoint_timer_query");
}

/* Records the first failure and disables the timer; true when the last calls succeeded. */
static bool gpu_timer_check(gpu_timer *t, const char *what)
{
    GLenum first = glGetError(), e = first;
    while (e != GL_NO_ERROR)
        e = glGetError();
    if (first == GL_NO_ERROR)
        return true;
    if (!t->failed) {
        t->failed = what;
        t->error = first;
    }
    t->ok = false;
    return false;
}

bool gpu_timer_init(gpu_timer *t)
{
    *t = (gpu_timer){0};
    if (!gpu_timer_supported())
        return false;
    int version = 0;
    t->ok = true;
    t->desktop = desktop_context(&version);
    glGenQueries(GPU_TIMER_RING, t->query);
    if (!gpu_timer_check(t, "glGenQueries"))
        return false;
    if (t->desktop)
        return true;
    GLint disjoint = 0;
    glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint); /* clears a flag left from before */
    return gpu_timer_check(t, "glGetIntegerv(GL_GPU_DISJOINT_EXT)");
}

/* Reads (and so clears) the disjoint flag; marks every query in flight invalid if it was set. */
static void gpu_timer_disjoint(gpu_timer *t)
{
    if (t->desktop)
        return;
    GLint disjoint = 0;
    glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
    if (!gpu_timer_check(t, "glGetIntegerv(GL_GPU_DISJOINT_EXT)") || !disjoint)
        return;
    t->disjoint++;
    for (int i = 0; i < GPU_TIMER_RING; i++)
        t->invalid[i] = true;
}

void gpu_timer_begin(gpu_timer *t, int level)
{
    if (!t->ok || t->active)
        return;
    GLint host = 0;
    glGetQueryiv(GL_TIME_ELAPSED_EXT, GL_CURRENT_QUERY, &host);
    if (!gpu_timer_check(t, "glGetQueryiv(GL_TIME_ELAPSED_EXT)"))
        return;
    if (host != 0) {
        t->host_busy++;
        return;
    }
    if (t->count == GPU_TIMER_RING) {
        t->dropped++;
        return;
    }
    gpu_timer_disjoint(t);
    int slot = t->head;
    glBeginQuery(GL_TIME_ELAPSED_EXT, t->query[slot]);
    if (!gpu_timer_check(t, "glBeginQuery(GL_TIME_ELAPSED_EXT)"))
        return;
    t->level[slot] = level;
    t->invalid[slot] = false;
    t->active = true;
}

void gpu_timer_end(gpu_timer *t)
{
    if (!t->active)
        return;
    t->active = false;
    glEndQuery(GL_TIME_ELAPSED_EXT);
    if (!gpu_timer_check(t, "glEndQuery(GL_TIME_ELAPSED_EXT)"))
        return;
    t->head = (t->head + 1) % GPU_TIMER_RING;
    t->count++;
}

bool gpu_timer_poll(gpu_timer *t, double *ms, int *level, bool *valid)
{
    if (!t->ok || t->count == 0)
        return false;
    int slot = (t->head - t->count + GPU_TIMER_RING) % GPU_TIMER_RING;
    GLuint available = GL_FALSE, ns = 0;
    glGetQueryObjectuiv(t->query[slot], GL_QUERY_RESULT_AVAILABLE, &available);
    if (!gpu_timer_check(t, "glGetQueryObjectuiv(GL_QUERY_RESULT_AVAILABLE)") || !available)
        return false;
    glGetQueryObjectuiv(t->query[slot], GL_QUERY_RESULT, &ns);
    if (!gpu_timer_check(t, "glGetQueryObjectuiv(GL_QUERY_RESULT)"))
        return false;
    gpu_timer_disjoint(t); /* after the result: a disjoint event during it makes it invalid */
    t->count--;
    *ms = ns * 1e-6;
    *level = t->level[slot];
    /* a saturated 32-bit result is no time (llvmpipe's first query of a context reads so) */
    *valid = t->ok && !t->invalid[slot] && ns != 0xFFFFFFFFu;
    return true;
}

void gpu_timer_destroy(gpu_timer *t)
{
    if (t->active) {
        glEndQuery(GL_TIME_ELAPSED_EXT);
        t->active = false;
    }
    if (t->query[0] || t->query[GPU_TIMER_RING - 1])
        glDeleteQueries(GPU_TIMER_RING, t->query);
    memset(t->query, 0, sizeof(t->query));
    t->count = 0;
    t->ok = false;
}
