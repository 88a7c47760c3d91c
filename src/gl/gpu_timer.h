/* sbfx's own GPU time per frame without stalling the pipeline (docs/design.md §6, issue 11 item 2):
 * GL_EXT_disjoint_timer_query through the ES 3.0 core query entry points (glBeginQuery etc.
 * accept GL_TIME_ELAPSED_EXT where the extension is listed; no EGL, no GetProcAddress), as a
 * ring of GPU_TIMER_RING query objects read a few frames late.
 *
 *   gpu_timer_init        makes the queries; false where the extension is missing or the
 *                         queries fail: the module then has no GPU time of its own and uses
 *                         the fallback (the host passes its measured frame time; see the
 *                         caller) — a tested path, MESA_EXTENSION_OVERRIDE=-GL_EXT_disjoint_timer_query
 *   gpu_timer_begin/end   bracket one frame's passes, tagged with the ladder level rendered
 *   gpu_timer_poll        the oldest finished frame, if its result is available: never waits
 *                         (GL_QUERY_RESULT_AVAILABLE first); call until it returns false
 *
 * Never stalls: when all GPU_TIMER_RING queries are still in flight, the frame is not timed
 * (counted in `dropped`) rather than waited for. The disjoint flag (GL_GPU_DISJOINT_EXT, read
 * with glGetIntegerv, which also clears it) is read at every begin and every poll; when set,
 * every query in flight is marked invalid (a power-state change, a reset: their times mean
 * nothing), and poll returns them with *valid = false.
 *
 * The host's queries: only one GL_TIME_ELAPSED_EXT query may be active at a time. A host that
 * times its whole frame around sbfx_render has one active; sbfx then skips timing that frame
 * (glGetQueryiv(GL_TIME_ELAPSED_EXT, GL_CURRENT_QUERY) at begin; counted in `host_busy`) and
 * leaves the host's query untouched. Query objects and the active query are not part of the
 * GL state sbfx saves and restores: begin/end change nothing the host can observe but the
 * query objects sbfx owns.
 *
 * GL failures: every call is checked (glGetError); a failure records the call's name and the
 * error in `failed` / `error`, disables the timer (`ok` = false: fallback from then on) and is
 * for the caller to report. 32-bit results: times up to 4.29 s; a saturated one (0xFFFFFFFF ns:
 * llvmpipe answers so for the first query of a context) is returned invalid.
 * Results become available once the host flushes (its swap); until then poll returns false. */
#ifndef SBFX_GPU_TIMER_H
#define SBFX_GPU_TIMER_H

#include <GLES3/gl3.h>
#include <stdbool.h>

#define GPU_TIMER_RING 4

typedef struct gpu_timer {
    GLuint query[GPU_TIMER_RING];
    int level[GPU_TIMER_RING];      /* the ladder level each query's frame was rendered at */
    bool invalid[GPU_TIMER_RING];   /* a disjoint event happened while it was in flight */
    int head;                       /* next slot to begin */
    int count;                      /* queries ended and not yet read */
    bool ok;                        /* the extension is there and no GL call has failed */
    bool desktop;                   /* desktop OpenGL (3.3 / GL_ARB_timer_query): no disjoint flag */
    bool active;                    /* begun, not yet ended */
    int dropped;                    /* frames not timed: ring full */
    int host_busy;                  /* frames not timed: the host's time query was active */
    int disjoint;                   /* disjoint events seen */
    const char *failed;             /* the GL call that failed, NULL if none */
    GLenum error;                   /* its error */
} gpu_timer;

/* GL_EXT_disjoint_timer_query on ES; on desktop OpenGL 3.3+ or GL_ARB_timer_query, which have
 * no disjoint flag (the desktop driver does not report disjoint events: none are counted). */
bool gpu_timer_supported(void);
bool gpu_timer_init(gpu_timer *t);
void gpu_timer_begin(gpu_timer *t, int level);
void gpu_timer_end(gpu_timer *t);
bool gpu_timer_poll(gpu_timer *t, double *ms, int *level, bool *valid);
void gpu_timer_destroy(gpu_timer *t);

#endif
