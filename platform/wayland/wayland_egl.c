/* EGL on a Wayland connection (wl_egl_window). */
#include "wayland/wayland_egl.h"

#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <wayland-client.h>
#include <wayland-egl.h>

#include "egl/egl_headless.h" /* egl_headless_error_string */
#include "egl/gl_reset.h"

#define MAX_CONFIGS 64

static const char *egl_error(void)
{
    return egl_headless_error_string(eglGetError());
}

static int get_display(struct wayland_egl *we, struct wl_display *wl, char *err, size_t n)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    we->display = get_platform_display ? get_platform_display(EGL_PLATFORM_WAYLAND_KHR, wl, NULL)
                                       : eglGetDisplay((EGLNativeDisplayType)wl);
    EGLint major = 0, minor = 0;
    if (we->display == EGL_NO_DISPLAY || !eglInitialize(we->display, &major, &minor)) {
        snprintf(err, n, "EGL on Wayland: no display (%s); is Mesa's libegl-mesa0 installed "
                 "(it brings the Wayland platform)?", egl_error());
        we->display = EGL_NO_DISPLAY;
        return -ENODEV;
    }
    if (!eglBindAPI(EGL_OPENGL_ES_API)) {
        snprintf(err, n, "eglBindAPI(OpenGL ES): %s", egl_error());
        return -ENOTSUP;
    }
    return 0;
}

static bool has_size(EGLDisplay display, EGLConfig config, EGLint attrib, EGLint bits)
{
    EGLint value = -1;
    return eglGetConfigAttrib(display, config, attrib, &value) && value == bits;
}

/* Exactly 8 bits per channel and no alpha: XRGB8888, which every compositor and display plane
 * takes, opaque as a display scans it out. eglChooseConfig sorts deeper configs first (Mesa
 * offers XRGB2101010 where the compositor does): the sizes are checked here. */
static int choose_config(struct wayland_egl *we, char *err, size_t n)
{
    static const EGLint attribs[] = {
        EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT,
        EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 0, EGL_NONE,
    };
    EGLConfig configs[MAX_CONFIGS];
    EGLint count = 0, bits = 8;
    if (!eglChooseConfig(we->display, attribs, configs, MAX_CONFIGS, &count) || count < 1) {
        snprintf(err, n, "eglChooseConfig(window, OpenGL ES 3, RGB888): no config (%s)", egl_error());
        return -ENOTSUP;
    }
    for (EGLint i = 0; i < count; i++) {
        if (has_size(we->display, configs[i], EGL_RED_SIZE, bits) && has_size(we->display, configs[i], EGL_GREEN_SIZE, bits) &&
            has_size(we->display, configs[i], EGL_BLUE_SIZE, bits) && has_size(we->display, configs[i], EGL_ALPHA_SIZE, 0)) {
            we->config = configs[i];
            return 0;
        }
    }
    snprintf(err, n, "EGL on Wayland: none of %d window configs has 8 bits per colour channel and no "
             "alpha", count);
    return -ENOTSUP;
}

static int new_context(struct wayland_egl *we, char *err, size_t n)
{
    we->context = gl_reset_create_context(we->display, we->config, &we->robust, err, n);
    return we->context == EGL_NO_CONTEXT ? -ENOTSUP : 0;
}

static int make_current(struct wayland_egl *we, char *err, size_t n)
{
    if (!eglMakeCurrent(we->display, we->surface, we->surface, we->context)) {
        snprintf(err, n, "eglMakeCurrent: %s", egl_error());
        return -EIO;
    }
    int rc = gl_reset_check_gles3(err, n);
    if (rc) return rc;
    if (!eglSwapInterval(we->display, 0)) {
        snprintf(err, n, "eglSwapInterval(0): %s", egl_error());
        return -EIO;
    }
    return 0;
}

int wayland_egl_open(struct wayland_egl *we, struct wl_display *wl, struct wl_egl_window *window,
                     char *err, size_t n)
{
    memset(we, 0, sizeof(*we));
    int rc = get_display(we, wl, err, n);
    if (rc == 0) rc = choose_config(we, err, n);
    if (rc == 0) rc = new_context(we, err, n);
    if (rc == 0) {
        we->surface = eglCreateWindowSurface(we->display, we->config, (EGLNativeWindowType)window, NULL);
        if (we->surface == EGL_NO_SURFACE) {
            snprintf(err, n, "eglCreateWindowSurface on the wl_egl_window: %s", egl_error());
            rc = -EIO;
        }
    }
    if (rc == 0) rc = make_current(we, err, n);
    if (rc) wayland_egl_close(we);
    return rc;
}

int wayland_egl_recreate_context(struct wayland_egl *we, char *err, size_t n)
{
    eglMakeCurrent(we->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (we->context != EGL_NO_CONTEXT) eglDestroyContext(we->display, we->context);
    we->context = EGL_NO_CONTEXT;
    int rc = new_context(we, err, n);
    return rc ? rc : make_current(we, err, n);
}

void wayland_egl_close(struct wayland_egl *we)
{
    if (we->display != EGL_NO_DISPLAY) {
        eglMakeCurrent(we->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (we->surface != EGL_NO_SURFACE) eglDestroySurface(we->display, we->surface);
        if (we->context != EGL_NO_CONTEXT) eglDestroyContext(we->display, we->context);
        eglTerminate(we->display);
        eglReleaseThread();
    }
    memset(we, 0, sizeof(*we));
}
