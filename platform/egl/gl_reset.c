/* Reset notification: context attributes, the window contexts made with them, the status query,
 * the injected reset. */
#include "egl/gl_reset.h"

#include <EGL/eglext.h>
#include <errno.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "egl/egl_headless.h" /* egl_headless_error_string */

static bool has_word(const char *list, const char *word)
{
    size_t len = strlen(word);
    for (const char *p = list; p && (p = strstr(p, word)) != NULL; p += len)
        if ((p == list || p[-1] == ' ') && (p[len] == ' ' || p[len] == '\0')) return true;
    return false;
}

bool gl_reset_context_attribs(EGLDisplay display, bool robust, EGLint *attribs)
{
    int i = 0;
    attribs[i++] = EGL_CONTEXT_MAJOR_VERSION;
    attribs[i++] = 3;
    bool add = robust && has_word(eglQueryString(display, EGL_EXTENSIONS),
                                  "EGL_EXT_create_context_robustness");
    if (add) {
        attribs[i++] = EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY_EXT;
        attribs[i++] = EGL_LOSE_CONTEXT_ON_RESET_EXT;
    }
    attribs[i] = EGL_NONE;
    return add;
}

EGLContext gl_reset_create_context(EGLDisplay display, EGLConfig config, bool *robust, char *err, size_t n)
{
    EGLint attribs[GL_RESET_ATTRIBS_MAX];
    *robust = gl_reset_context_attribs(display, true, attribs);
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs);
    if (context == EGL_NO_CONTEXT && *robust) { /* refused with the strategy: a plain one */
        *robust = false;
        gl_reset_context_attribs(display, false, attribs);
        context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs);
    }
    if (context == EGL_NO_CONTEXT)
        snprintf(err, n, "eglCreateContext(OpenGL ES 3): %s", egl_headless_error_string(eglGetError()));
    return context;
}

int gl_reset_check_gles3(char *err, size_t n)
{
    const char *version = (const char *)glGetString(GL_VERSION);
    int major = 0;
    if (!version || sscanf(version, "OpenGL ES %d", &major) != 1 || major < 3) {
        snprintf(err, n, "the context is '%s', not OpenGL ES 3.0 or later", version ? version : "?");
        return -ENOTSUP;
    }
    return 0;
}

void gl_reset_init(struct gl_reset *r, bool robust_context)
{
    int inject = r->inject_frame;
    memset(r, 0, sizeof(*r));
    r->inject_frame = inject;
    if (!robust_context) return;
    const char *ext = (const char *)glGetString(GL_EXTENSIONS);
    if (has_word(ext, "GL_KHR_robustness")) {
        r->status = (gl_reset_status_fn)eglGetProcAddress("glGetGraphicsResetStatusKHR");
        r->extension = "GL_KHR_robustness";
    }
    if (!r->status && has_word(ext, "GL_EXT_robustness")) {
        r->status = (gl_reset_status_fn)eglGetProcAddress("glGetGraphicsResetStatusEXT");
        r->extension = "GL_EXT_robustness";
    }
    if (!r->status) r->extension = NULL;
}

void gl_reset_inject(struct gl_reset *r, int frame)
{
    r->inject_frame = frame;
}

GLenum gl_reset_status(struct gl_reset *r, int frame)
{
    if (r->inject_frame >= 0 && frame == r->inject_frame) {
        r->inject_frame = -1;
        return GL_GUILTY_CONTEXT_RESET;
    }
    return r->status ? r->status() : GL_NO_ERROR;
}

const char *gl_reset_name(GLenum status)
{
    switch (status) {
    case GL_NO_ERROR: return "none";
    case GL_GUILTY_CONTEXT_RESET: return "guilty: this context caused it";
    case GL_INNOCENT_CONTEXT_RESET: return "innocent: another context caused it";
    case GL_UNKNOWN_CONTEXT_RESET: return "cause unknown";
    default: return "unknown status";
    }
}
