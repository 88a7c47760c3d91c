/* GBM + EGL on a DRM device. */
#include "drm/gbm_egl.h"
#include "egl/gl_reset.h"

#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "egl/egl_headless.h" /* egl_headless_error_string */

#define MAX_CONFIGS 64

static const char *egl_error(void)
{
    return egl_headless_error_string(eglGetError());
}

static int create_surface(struct gbm_egl *ge, int width, int height, char *err, size_t n)
{
    static const uint32_t formats[] = {GBM_FORMAT_XRGB8888, GBM_FORMAT_ARGB8888};
    for (size_t i = 0; i < sizeof(formats) / sizeof(formats[0]); i++) {
        ge->surface = gbm_surface_create(ge->gbm, (uint32_t)width, (uint32_t)height, formats[i],
                                         GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
        if (ge->surface) {
            ge->format = formats[i];
            return 0;
        }
    }
    int rc = errno ? -errno : -ENOMEM;
    snprintf(err, n, "gbm_surface_create(%dx%d XRGB8888/ARGB8888, scan-out): %s", width, height,
             strerror(-rc));
    return rc;
}

static int get_display(struct gbm_egl *ge, char *err, size_t n)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (get_platform_display)
        ge->display = get_platform_display(EGL_PLATFORM_GBM_KHR, ge->gbm, NULL);
    else
        ge->display = eglGetDisplay((EGLNativeDisplayType)ge->gbm);
    EGLint major = 0, minor = 0;
    if (ge->display == EGL_NO_DISPLAY || !eglInitialize(ge->display, &major, &minor)) {
        snprintf(err, n, "EGL on GBM: no display (%s); is Mesa's libegl-mesa0 installed?", egl_error());
        ge->display = EGL_NO_DISPLAY;
        return -ENODEV;
    }
    if (!eglBindAPI(EGL_OPENGL_ES_API)) {
        snprintf(err, n, "eglBindAPI(OpenGL ES): %s", egl_error());
        return -ENOTSUP;
    }
    return 0;
}

/* A window config whose native visual is the GBM surface's format. */
static int choose_config(struct gbm_egl *ge, char *err, size_t n)
{
    static const EGLint attribs[] = {
        EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT,
        EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 0, EGL_NONE,
    };
    EGLConfig configs[MAX_CONFIGS];
    EGLint count = 0;
    if (!eglChooseConfig(ge->display, attribs, configs, MAX_CONFIGS, &count) || count < 1) {
        snprintf(err, n, "eglChooseConfig(window, OpenGL ES 3, RGB888): no config (%s)", egl_error());
        return -ENOTSUP;
    }
    for (EGLint i = 0; i < count; i++) {
        EGLint visual = 0;
        if (eglGetConfigAttrib(ge->display, configs[i], EGL_NATIVE_VISUAL_ID, &visual) &&
            (uint32_t)visual == ge->format) {
            ge->config = configs[i];
            return 0;
        }
    }
    snprintf(err, n, "EGL on GBM: none of %d configs matches the surface format 0x%08x", count, ge->format);
    return -ENOTSUP;
}

static int new_context(struct gbm_egl *ge, char *err, size_t n)
{
    ge->context = gl_reset_create_context(ge->display, ge->config, &ge->robust, err, n);
    return ge->context == EGL_NO_CONTEXT ? -ENOTSUP : 0;
}

static int make_current(struct gbm_egl *ge, char *err, size_t n)
{
    if (!eglMakeCurrent(ge->display, ge->egl_surface, ge->egl_surface, ge->context)) {
        snprintf(err, n, "eglMakeCurrent: %s", egl_error());
        return -EIO;
    }
    return gl_reset_check_gles3(err, n);
}

static int create_context(struct gbm_egl *ge, char *err, size_t n)
{
    int rc = new_context(ge, err, n);
    if (rc) return rc;
    ge->egl_surface = eglCreateWindowSurface(ge->display, ge->config,
                                             (EGLNativeWindowType)ge->surface, NULL);
    if (ge->egl_surface == EGL_NO_SURFACE) {
        snprintf(err, n, "eglCreateWindowSurface on the GBM surface: %s", egl_error());
        return -EIO;
    }
    return make_current(ge, err, n);
}

int gbm_egl_recreate_context(struct gbm_egl *ge, char *err, size_t n)
{
    eglMakeCurrent(ge->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (ge->context != EGL_NO_CONTEXT) eglDestroyContext(ge->display, ge->context);
    ge->context = EGL_NO_CONTEXT;
    int rc = new_context(ge, err, n);
    return rc ? rc : make_current(ge, err, n);
}

int gbm_egl_open(struct gbm_egl *ge, int drm_fd, int width, int height, char *err, size_t n)
{
    memset(ge, 0, sizeof(*ge));
    ge->gbm = gbm_create_device(drm_fd);
    if (!ge->gbm) {
        int rc = errno ? -errno : -ENODEV;
        snprintf(err, n, "gbm_create_device: %s (no GBM backend for this driver?)", strerror(-rc));
        return rc;
    }
    int rc = create_surface(ge, width, height, err, n);
    if (rc == 0) rc = get_display(ge, err, n);
    if (rc == 0) rc = choose_config(ge, err, n);
    if (rc == 0) rc = create_context(ge, err, n);
    if (rc) gbm_egl_close(ge);
    return rc;
}

void gbm_egl_close(struct gbm_egl *ge)
{
    if (ge->display != EGL_NO_DISPLAY) {
        eglMakeCurrent(ge->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (ge->egl_surface != EGL_NO_SURFACE) eglDestroySurface(ge->display, ge->egl_surface);
        if (ge->context != EGL_NO_CONTEXT) eglDestroyContext(ge->display, ge->context);
        eglTerminate(ge->display);
        eglReleaseThread();
    }
    if (ge->surface) gbm_surface_destroy(ge->surface);
    if (ge->gbm) gbm_device_destroy(ge->gbm);
    memset(ge, 0, sizeof(*ge));
}
