/* GBM surface + EGL window surface + GLES 3 context on a DRM device (kmscube's common.c part).
 *
 * gbm_egl_open() creates a scan-out capable GBM surface of width x height XRGB8888 (ARGB8888
 * when the driver insists), an EGL display on it (EGL_PLATFORM_GBM_KHR), a config whose native
 * visual is that format, an OpenGL ES 3 context (with GPU reset notification where EGL offers
 * it: gl_reset.h) and a window surface, and makes them current.
 * After eglSwapBuffers, gbm_surface_lock_front_buffer() gives the bo to show.
 * Errors: 0 or a negative errno with a message naming the call. */
#ifndef SBFX_GBM_EGL_H
#define SBFX_GBM_EGL_H

#include <EGL/egl.h>
#include <gbm.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct gbm_egl {
    struct gbm_device *gbm;
    struct gbm_surface *surface;
    uint32_t format;
    EGLDisplay display;
    EGLConfig config;
    EGLContext context;
    EGLSurface egl_surface;
    bool robust;                /* the context has reset notification (gl_reset.h) */
};

int gbm_egl_open(struct gbm_egl *ge, int drm_fd, int width, int height, char *err, size_t n);
/* A new context in place of the current one (after a GPU reset), current on the same window
 * surface. */
int gbm_egl_recreate_context(struct gbm_egl *ge, char *err, size_t n);
/* Safe on a zeroed or half-opened struct. */
void gbm_egl_close(struct gbm_egl *ge);

#endif
