/* EGL on a Wayland connection: a display on EGL_PLATFORM_WAYLAND_KHR, an opaque RGB888 window
 * config, an OpenGL ES 3 context (with GPU reset notification where EGL offers it: gl_reset.h)
 * and a window surface on a wl_egl_window, made current. Swap interval 0: the display paces
 * itself with wl_surface frame callbacks (display_wayland.c), so eglSwapBuffers never waits
 * for one of Mesa's own.
 * Errors: 0 or a negative errno with a message naming the EGL call and what to do. */
#ifndef SBFX_WAYLAND_EGL_H
#define SBFX_WAYLAND_EGL_H

#include <EGL/egl.h>
#include <stdbool.h>
#include <stddef.h>

struct wl_display;
struct wl_egl_window;

struct wayland_egl {
    EGLDisplay display;
    EGLConfig config;
    EGLContext context;
    EGLSurface surface;
    bool robust;
};

int wayland_egl_open(struct wayland_egl *we, struct wl_display *wl, struct wl_egl_window *window,
                     char *err, size_t n);
/* A new context in place of the current one (after a GPU reset), current on the same surface. */
int wayland_egl_recreate_context(struct wayland_egl *we, char *err, size_t n);
/* Safe on a zeroed or half-opened struct. */
void wayland_egl_close(struct wayland_egl *we);

#endif
