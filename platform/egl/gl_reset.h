/* GPU resets (GL_KHR_robustness / GL_EXT_robustness): the player asks for a context with reset
 * notification where EGL offers EGL_EXT_create_context_robustness (the reset strategy
 * EGL_LOSE_CONTEXT_ON_RESET_EXT), and asks the context once per frame whether a reset happened
 * (glGetGraphicsResetStatusKHR or ...EXT, fetched with eglGetProcAddress). A context that was
 * reset is lost for good: the player then makes a new one and everything that lived in it
 * (platform/player/reset.c).
 *
 * Testing without a GPU that can be made to hang: gl_reset_inject() makes the status query
 * answer GL_GUILTY_CONTEXT_RESET once, at a given frame, without asking the driver (sbfx-play:
 * SBFX_PLAY_INJECT_GPU_RESET=FRAME in the environment; tests/platform/test_gl_reset.c). */
#ifndef SBFX_GL_RESET_H
#define SBFX_GL_RESET_H

#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <stdbool.h>
#include <stddef.h>

#ifndef GL_GUILTY_CONTEXT_RESET
#define GL_GUILTY_CONTEXT_RESET 0x8253
#define GL_INNOCENT_CONTEXT_RESET 0x8254
#define GL_UNKNOWN_CONTEXT_RESET 0x8255
#endif

#define GL_RESET_ATTRIBS_MAX 8

typedef GLenum (*gl_reset_status_fn)(void);

struct gl_reset {
    gl_reset_status_fn status; /* NULL: no robustness, resets cannot be told */
    const char *extension;     /* "GL_KHR_robustness", "GL_EXT_robustness" or NULL */
    int inject_frame;          /* -1: none; otherwise answered once at that frame */
};

/* Context attributes for eglCreateContext: EGL_CONTEXT_MAJOR_VERSION 3, plus the reset
 * notification strategy when the display offers EGL_EXT_create_context_robustness (and robust
 * is true). Returns true when the strategy was added. attribs holds GL_RESET_ATTRIBS_MAX. */
bool gl_reset_context_attribs(EGLDisplay display, bool robust, EGLint *attribs);
/* An OpenGL ES 3 context on `config` (a window's: DRM/GBM, Wayland), robust where the display
 * offers it, else a plain one; *robust says which. EGL_NO_CONTEXT, with err, when neither is made. */
EGLContext gl_reset_create_context(EGLDisplay display, EGLConfig config, bool *robust, char *err, size_t n);
/* With a context current: 0 when it is OpenGL ES 3.0 or later, else -ENOTSUP with err. */
int gl_reset_check_gles3(char *err, size_t n);
/* With the new context current: finds the status query. robust_context: the context was
 * created with the notification strategy (without it the query is not told of resets). */
void gl_reset_init(struct gl_reset *r, bool robust_context);
void gl_reset_inject(struct gl_reset *r, int frame);
/* GL_NO_ERROR, or the reset status (GL_GUILTY/INNOCENT/UNKNOWN_CONTEXT_RESET). */
GLenum gl_reset_status(struct gl_reset *r, int frame);
const char *gl_reset_name(GLenum status);

#endif
