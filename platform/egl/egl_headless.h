/* Headless OpenGL ES 3.0 context through EGL, for machines without a display.
 *
 * Contract: egl_headless_open() leaves a GLES 3.0+ context current on the calling thread with
 * no window surface (render into FBOs). It prefers Mesa's surfaceless platform
 * (EGL_PLATFORM_SURFACELESS_MESA) and falls back to EGL_DEFAULT_DISPLAY, to a config-less
 * context or to a 1x1 pbuffer, whichever the driver offers. Mesa's environment variables
 * (GALLIUM_DRIVER, LIBGL_ALWAYS_SOFTWARE, MESA_EXTENSION_OVERRIDE, EGL_PLATFORM...) act as
 * they always do: nothing here overrides them.
 *
 * Errors: 0 on success, or a negative errno-like code with a message in err that says which
 * EGL call failed and what to do about it:
 *   -ENODEV   no EGL display could be opened or initialised
 *   -ENOTSUP  the display offers no OpenGL ES 3.0 context
 *   -EIO      a context or surface could not be created or made current */
#ifndef SBFX_EGL_HEADLESS_H
#define SBFX_EGL_HEADLESS_H

#include <EGL/egl.h>
#include <stdbool.h>
#include <stddef.h>

/* Which API a context is made for: OpenGL ES 3.0 (what everything else opens), or desktop
 * OpenGL 4.5 with the core or the compatibility profile (EGL_OPENGL_API: desktop hosts, issue 18;
 * docs/hosts/desktop-gl.md). */
enum egl_headless_api { EGL_HEADLESS_GLES3, EGL_HEADLESS_GL_CORE, EGL_HEADLESS_GL_COMPAT };

struct egl_headless {
    EGLDisplay display;
    EGLContext context;
    EGLSurface surface;   /* EGL_NO_SURFACE unless the pbuffer fallback was needed */
    EGLConfig config;     /* EGL_NO_CONFIG_KHR (NULL) with a config-less context */
    const char *platform; /* "surfaceless" or "default": how the display was found */
    int egl_major, egl_minor;
    bool robust;          /* asked for (open_robust), then: the context has reset notification
                             (gl_reset.h) */
    enum egl_headless_api api;
};

int egl_headless_open(struct egl_headless *out, char *err, size_t n);
int egl_headless_open_api(struct egl_headless *out, enum egl_headless_api api, char *err, size_t n);
/* The API tests open: SBFX_TEST_GL_API=core or compat selects desktop OpenGL, unset or "es"
 * OpenGL ES 3.0. */
enum egl_headless_api egl_headless_test_api(void);
/* The same with GPU reset notification asked for where EGL offers it (the player; tests and
 * benches keep the plain context). */
int egl_headless_open_robust(struct egl_headless *out, char *err, size_t n);
/* A new context in place of the current one (after a GPU reset: the old one is lost with
 * everything in it), made current. */
int egl_headless_recreate_context(struct egl_headless *egl, char *err, size_t n);
/* Initializes the display and terminates it again: the driver's libraries are loaded and stay
 * (Mesa keeps its driver and LLVM mapped), no context is made and no driver thread is left. For
 * a process that forks children which each open a context (the test harness, tests/check.h):
 * they inherit the loaded, relocated libraries instead of loading them each. 0, or -ENODEV with
 * the reason in err. */
int egl_headless_load_driver(char *err, size_t n);
/* Releases the context and the display; safe on a zeroed or already-closed struct. */
void egl_headless_close(struct egl_headless *egl);

/* Human-readable name of an EGL error code ("EGL_BAD_ALLOC"...). */
const char *egl_headless_error_string(EGLint code);

#endif
