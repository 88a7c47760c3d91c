/* Where sbfx-play's frames go: the contract every display backend fills (kmscube's shape: one
 * small struct of function pointers per backend, so the player's loop never asks which one it
 * is on).
 *
 *   display_headless.c  EGL surfaceless, an RGBA8 framebuffer object, each frame read back and
 *                       written as frame-NNNN.png (and into a contact sheet)
 *   display_drm.c       DRM/KMS: GBM surface + EGL window surface, atomic (or legacy) modeset,
 *                       one page flip in flight, paced by vblank
 *   display_wayland.c   a Wayland client: full-screen xdg toplevel, wl_egl_window, one frame
 *                       in flight, paced by wl_surface frame callbacks, presentation-time
 *                       feedback
 *
 * Creating a backend leaves a GLES 3.0 context current on the calling thread; the player draws
 * each frame into d->framebuffer (sbfx_frame.out_framebuffer) and calls present(). While
 * d->busy, a presented frame is not on screen yet: the loop polls d->fd (POLLIN) and calls
 * dispatch() until busy clears, and only then presents again.
 * Every function returns 0 or a negative errno with a message in err saying what failed. */
#ifndef SBFX_DISPLAY_H
#define SBFX_DISPLAY_H

#include <GLES3/gl3.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct display;

struct display_ops {
    /* The frame in d->framebuffer is finished; index counts presented frames from 0. */
    int (*present)(struct display *d, int index, char *err, size_t n);
    /* Handles what d->fd reported (a completed page flip). */
    int (*dispatch)(struct display *d, char *err, size_t n);
    /* d->busy for longer than the loop waits (1 s): NULL, the loop gives up (a page flip that
     * never completes is an error); otherwise 0 when the backend goes on without it (wayland:
     * a hidden window gets no frame callbacks) and clears busy. */
    int (*stalled)(struct display *d, char *err, size_t n);
    /* After the last frame: waits until it is on screen, writes what is left (contact sheet,
     * screenshot). */
    int (*finish)(struct display *d, char *err, size_t n);
    /* After a GPU reset: a new GL context in place of the lost one, current, with the
     * backend's own GL objects (d->framebuffer) made again in it. */
    int (*reset_context)(struct display *d, char *err, size_t n);
    /* Puts the screen back as it was, releases everything; safe after a failed create. */
    void (*destroy)(struct display *d);
};

struct display_counts {
    uint64_t presented;   /* frames handed to the display */
    uint64_t flips;       /* page flips completed (drm) */
    uint64_t missed;      /* vblanks that passed with no new frame between two flips (drm) */
    uint64_t unplugs;     /* the connector went away: scan-out paused (drm, display_link.h) */
    uint64_t replugs;     /* it came back: mode set again, scan-out resumed */
    uint64_t paused;      /* frames rendered but not shown while it was away */
    /* presentation feedback (wayland, wp_presentation): what the compositor says happened */
    uint64_t feedback_presented; /* frames it reports on screen */
    uint64_t feedback_discarded; /* frames it never showed (replaced by a newer one) */
    int64_t latency_ns_sum;      /* commit -> on screen, summed over feedback_presented */
    int64_t latency_ns_max;
};

struct display {
    const struct display_ops *ops;
    const char *name;           /* "headless", "drm" or "wayland" */
    int width, height;
    GLuint framebuffer;         /* where the frame is composed (0: the window surface) */
    int fd;                     /* poll for POLLIN while busy; -1 when never busy */
    bool busy;
    double refresh_hz;          /* 0 when not paced by a display */
    bool robust_context;        /* the context has GPU reset notification (gl_reset.h) */
    bool presentation;          /* counts.feedback_* and latency are reported (wayland) */
    bool resized;               /* width/height changed: the player makes its size-bound
                                   objects again and clears it (wayland configure) */
    bool closed;                /* the window was asked to close: the run ends (exit 0) */
    bool lost;                  /* the display server went away: the run ends with
                                   PLAYER_EXIT_DISPLAY_LOST (player.h) */
    char description[192];      /* for the banner: "card0 (vkms) Virtual-1 1024x768@60 atomic" */
    struct display_counts counts;
};

struct display_headless_desc {
    int width, height;
    const char *out_dir;        /* existing folder for frame-NNNN.png */
    bool contact_sheet;         /* also DIR/contact-sheet.png, written by finish() */
    int frames;                 /* planned frame count (contact sheet layout) */
};

struct display_drm_desc {
    const char *device;         /* "/dev/dri/card0"; NULL: the first card with a display */
    const char *connector;      /* "HDMI-A-1"; NULL: the first connected one */
    const char *mode;           /* "1920x1080" or "1920x1080@60"; NULL: the preferred mode */
    int modeset;                /* enum modeset_kind (drm/drm_mode_spec.h): auto, atomic, legacy */
    const char *screenshot;     /* PNG of the last frame as scanned out (writeback); NULL */
};

struct display_wayland_desc {
    int width, height;          /* the window's size where the compositor leaves it to the
                                   client: with size_set always, else only where no output's
                                   size is known (a full-screen window is the output's size) */
    bool size_set;              /* --size was given */
};

int display_headless_create(const struct display_headless_desc *desc, struct display **out,
                            char *err, size_t n);
int display_drm_create(const struct display_drm_desc *desc, struct display **out, char *err,
                       size_t n);

/* Connects to the compositor of WAYLAND_DISPLAY (XDG_RUNTIME_DIR). */
int display_wayland_create(const struct display_wayland_desc *desc, struct display **out,
                           char *err, size_t n);

/* The EGL renderer description of the current context, for the banner. */
const char *display_gl_renderer(void);

#endif
