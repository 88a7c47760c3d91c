/* The Wayland display: sbfx-play as a client of a compositor (cage, weston, labwc...), no root,
 * no DRM master. An xdg toplevel asks to be full screen (a refusal is logged and the window is
 * rendered at whatever size the compositor gives); frames go through EGL on a wl_egl_window
 * (wayland_egl.h) with one in flight: present() asks for a wl_surface frame callback and swaps,
 * the callback (dispatch) clears busy. Each frame also asks for presentation-time feedback
 * (present_feedback.h): on screen or discarded, latency, missed refresh cycles.
 * A configure with a new size resizes the wl_egl_window and sets d->resized. A window the
 * compositor stops drawing (hidden, output off) gets no frame callbacks: after a second
 * (stalled) frames go on at 10 Hz unshown until it asks again. The compositor going away sets
 * d->lost and ends the run (player.h: PLAYER_EXIT_DISPLAY_LOST). */
#include "display/display.h"

#include <errno.h>
#include <limits.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <wayland-client.h>
#include <wayland-egl.h>

#include "egl/egl_headless.h" /* egl_headless_error_string */
#include "presentation-time-client-protocol.h"
#include "wayland/present_feedback.h"
#include "wayland/wayland_egl.h"
#include "xdg-shell-client-protocol.h"

#define CONFIGURE_TIMEOUT_MS 5000
#define FINISH_TIMEOUT_MS 1000
#define HIDDEN_PACE_MS 100 /* the loop's pace while the window is not drawn (10 Hz) */
#define FEEDBACK_SLOTS 8   /* presentation feedbacks in flight (one frame's arrives a frame or two late) */

struct display_wayland;

struct feedback_slot {
    struct display_wayland *k;
    struct wp_presentation_feedback *feedback; /* NULL: free */
    int64_t commit_ns;                         /* when the frame was committed (k->clock) */
};

struct display_wayland {
    struct display base;
    struct display_wayland_desc desc;
    struct wl_display *wl;
    struct wl_registry *registry;
    struct wl_compositor *compositor;
    struct xdg_wm_base *wm_base;
    struct wp_presentation *presentation;
    struct wl_output *output;       /* the first output: its size is a full-screen window's */
    int output_width, output_height; /* its current mode (0: not told) */
    clockid_t clock;                /* the presentation clock (wp_presentation.clock_id) */
    struct wl_surface *surface;
    struct xdg_surface *xdg_surface;
    struct xdg_toplevel *toplevel;
    struct wl_callback *frame;      /* the frame callback in flight */
    struct wl_egl_window *window;
    struct wayland_egl egl;
    struct feedback_slot slots[FEEDBACK_SLOTS];
    struct present_feedback feedback;
    int toplevel_width, toplevel_height; /* the last xdg_toplevel.configure (0: ours to choose) */
    bool toplevel_fullscreen;
    bool configured;                /* the first xdg_surface.configure arrived */
    uint64_t judge_fullscreen_at;   /* frame callbacks after which a refusal is told (0: not yet) */
    int fullscreen_logged;          /* -1 not yet, else the state last logged */
    bool hidden;                    /* no frame callback for a second: frames are not shown */
    char name[64];                  /* WAYLAND_DISPLAY */
};

static struct display_wayland *to_wayland(struct display *d)
{
    return (struct display_wayland *)d; /* base is the first member */
}

static int64_t clock_ns(clockid_t clock)
{
    struct timespec ts;
    clock_gettime(clock, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

/* ---- the connection going away ------------------------------------------------------------ */

/* After a failed libwayland call: the compositor gone (d->lost), or a protocol error (a bug
 * here: named with its interface and code). */
static int connection_error(struct display_wayland *k, const char *what, char *err, size_t n)
{
    int code = wl_display_get_error(k->wl);
    if (code == EPROTO) {
        const struct wl_interface *iface = NULL;
        uint32_t id = 0, error = wl_display_get_protocol_error(k->wl, &iface, &id);
        snprintf(err, n, "Wayland %s: protocol error %u on %s@%u while %s (a bug in sbfx-play: "
                 "please report it with WAYLAND_DEBUG=1 output)", k->name, error,
                 iface ? iface->name : "?", id, what);
        return -EPROTO;
    }
    k->base.lost = true;
    snprintf(err, n, "Wayland %s: the compositor went away (%s while %s); exiting so that the "
             "service manager restarts sbfx-play with it", k->name, strerror(code ? code : EPIPE), what);
    return -EPIPE;
}

/* Reads and dispatches what the compositor sent, waiting up to timeout_ms for it (0: only
 * what is there); flushes our requests first. libwayland's prepare/read protocol, so that
 * Mesa's own event queue on the same connection is never starved or raced. */
static int pump(struct display_wayland *k, int timeout_ms, char *err, size_t n)
{
    while (wl_display_prepare_read(k->wl) != 0)
        if (wl_display_dispatch_pending(k->wl) < 0) return connection_error(k, "dispatching events", err, n);
    if (wl_display_flush(k->wl) < 0 && errno != EAGAIN) {
        wl_display_cancel_read(k->wl);
        return connection_error(k, "sending requests", err, n);
    }
    struct pollfd p = {.fd = wl_display_get_fd(k->wl), .events = POLLIN};
    if (poll(&p, 1, timeout_ms) > 0) {
        if (wl_display_read_events(k->wl) < 0) return connection_error(k, "reading events", err, n);
    } else {
        wl_display_cancel_read(k->wl); /* nothing yet, or a signal: the loop decides */
    }
    if (wl_display_dispatch_pending(k->wl) < 0) return connection_error(k, "dispatching events", err, n);
    return 0;
}

/* ---- protocol listeners ------------------------------------------------------------------ */

static void on_registry_global(void *data, struct wl_registry *registry, uint32_t name,
                               const char *interface, uint32_t version)
{
    struct display_wayland *k = data;
    if (strcmp(interface, wl_compositor_interface.name) == 0 && !k->compositor)
        k->compositor = wl_registry_bind(registry, name, &wl_compositor_interface, version < 4 ? version : 4);
    else if (strcmp(interface, xdg_wm_base_interface.name) == 0 && !k->wm_base)
        k->wm_base = wl_registry_bind(registry, name, &xdg_wm_base_interface, 1);
    else if (strcmp(interface, wp_presentation_interface.name) == 0 && !k->presentation)
        k->presentation = wl_registry_bind(registry, name, &wp_presentation_interface, 1);
    else if (strcmp(interface, wl_output_interface.name) == 0 && !k->output)
        k->output = wl_registry_bind(registry, name, &wl_output_interface, 1);
}

static void on_registry_global_remove(void *data, struct wl_registry *registry, uint32_t name)
{
}

static const struct wl_registry_listener registry_listener = {
    .global = on_registry_global,
    .global_remove = on_registry_global_remove,
};

static void on_wm_base_ping(void *data, struct xdg_wm_base *wm_base, uint32_t serial)
{
    xdg_wm_base_pong(wm_base, serial);
}

static const struct xdg_wm_base_listener wm_base_listener = {.ping = on_wm_base_ping};

static void on_output_geometry(void *data, struct wl_output *output, int32_t x, int32_t y,
                               int32_t mm_width, int32_t mm_height, int32_t subpixel,
                               const char *make, const char *model, int32_t transform)
{
}

static void on_output_mode(void *data, struct wl_output *output, uint32_t flags, int32_t width,
                           int32_t height, int32_t refresh_mhz)
{
    struct display_wayland *k = data;
    if (!(flags & WL_OUTPUT_MODE_CURRENT)) return;
    k->output_width = width;
    k->output_height = height;
    if (refresh_mhz > 0 && !k->base.refresh_hz) k->base.refresh_hz = refresh_mhz / 1000.0;
}

static const struct wl_output_listener output_listener = {
    .geometry = on_output_geometry,
    .mode = on_output_mode,
};

static void on_presentation_clock(void *data, struct wp_presentation *presentation, uint32_t clock)
{
    struct display_wayland *k = data;
    k->clock = (clockid_t)clock;
}

static const struct wp_presentation_listener presentation_listener = {.clock_id = on_presentation_clock};

static void on_toplevel_configure(void *data, struct xdg_toplevel *toplevel, int32_t width,
                                  int32_t height, struct wl_array *states)
{
    struct display_wayland *k = data;
    k->toplevel_width = width;
    k->toplevel_height = height;
    k->toplevel_fullscreen = false;
    const uint32_t *state;
    wl_array_for_each(state, states) if (*state == XDG_TOPLEVEL_STATE_FULLSCREEN) k->toplevel_fullscreen = true;
}

static void on_toplevel_close(void *data, struct xdg_toplevel *toplevel)
{
    struct display_wayland *k = data;
    k->base.closed = true;
    fprintf(stderr, "sbfx-play: Wayland %s: the compositor asked the window to close; the run ends\n", k->name);
}

static const struct xdg_toplevel_listener toplevel_listener = {
    .configure = on_toplevel_configure,
    .close = on_toplevel_close,
};

static void describe(struct display_wayland *k)
{
    struct display *d = &k->base;
    snprintf(d->description, sizeof(d->description), "Wayland %s %dx%d %s, %s", k->name, d->width,
             d->height, k->toplevel_fullscreen ? "full screen" : "window",
             k->presentation ? "presentation-time feedback" : "no presentation-time");
}

/* Full screen refused (or granted again): said once per change, the run goes on either way.
 * Not before the compositor had the chance to grant it to a mapped window (judge_fullscreen_at). */
static void log_fullscreen(struct display_wayland *k)
{
    describe(k);
    bool judged = k->judge_fullscreen_at && k->base.counts.flips >= k->judge_fullscreen_at;
    if (!judged && !k->toplevel_fullscreen) return;
    if (k->fullscreen_logged == (int)k->toplevel_fullscreen) return;
    if (!k->toplevel_fullscreen)
        fprintf(stderr, "sbfx-play: Wayland %s: the compositor did not make the window full screen; "
                "rendering goes on in a %dx%d window\n", k->name, k->base.width, k->base.height);
    else if (k->fullscreen_logged == 0)
        fprintf(stderr, "sbfx-play: Wayland %s: the window is full screen now (%dx%d)\n", k->name,
                k->base.width, k->base.height);
    k->fullscreen_logged = k->toplevel_fullscreen;
}

/* Where the compositor leaves the size to us (0x0): the window's size so far, else the output's
 * (cage configures a full-screen window only once it is mapped: its first buffer is then the
 * right size already), else --size. */
static void own_size(const struct display_wayland *k, int *w, int *h)
{
    const struct display *d = &k->base;
    if (d->width) *w = d->width, *h = d->height;
    else if (!k->desc.size_set && k->output_width > 0) *w = k->output_width, *h = k->output_height;
    else *w = k->desc.width, *h = k->desc.height;
}

/* The size the compositor configured, or ours where it leaves it to us. */
static void apply_size(struct display_wayland *k)
{
    struct display *d = &k->base;
    int w = 0, h = 0;
    own_size(k, &w, &h);
    if (k->toplevel_width > 0) w = k->toplevel_width;
    if (k->toplevel_height > 0) h = k->toplevel_height;
    if (w == d->width && h == d->height) return;
    d->width = w;
    d->height = h;
    if (!k->window) return; /* the first configure: the window is made at this size */
    wl_egl_window_resize(k->window, w, h, 0, 0);
    d->resized = true;
}

static void on_xdg_surface_configure(void *data, struct xdg_surface *xdg_surface, uint32_t serial)
{
    struct display_wayland *k = data;
    xdg_surface_ack_configure(xdg_surface, serial);
    apply_size(k);
    k->configured = true;
    log_fullscreen(k);
}

static const struct xdg_surface_listener xdg_surface_listener = {.configure = on_xdg_surface_configure};

static void on_frame_done(void *data, struct wl_callback *callback, uint32_t time_ms)
{
    struct display_wayland *k = data;
    wl_callback_destroy(callback);
    k->frame = NULL;
    k->base.busy = false;
    k->base.counts.flips++;
    log_fullscreen(k);
    if (!k->hidden) return;
    k->hidden = false;
    fprintf(stderr, "sbfx-play: Wayland %s: the compositor draws the window again; frames are "
            "shown again\n", k->name);
}

static const struct wl_callback_listener frame_listener = {.done = on_frame_done};

static void release_slot(struct feedback_slot *s)
{
    wp_presentation_feedback_destroy(s->feedback);
    s->feedback = NULL;
}

static void on_feedback_sync_output(void *data, struct wp_presentation_feedback *f, struct wl_output *output)
{
}

static void on_feedback_presented(void *data, struct wp_presentation_feedback *f, uint32_t sec_hi,
                                  uint32_t sec_lo, uint32_t nsec, uint32_t refresh_ns,
                                  uint32_t seq_hi, uint32_t seq_lo, uint32_t flags)
{
    struct feedback_slot *s = data;
    struct display_wayland *k = s->k;
    int64_t t = (int64_t)(((uint64_t)sec_hi << 32 | sec_lo) * 1000000000 + nsec);
    present_feedback_presented(&k->feedback, &k->base.counts, t, (uint64_t)seq_hi << 32 | seq_lo,
                               refresh_ns, s->commit_ns);
    if (refresh_ns) k->base.refresh_hz = 1e9 / refresh_ns;
    release_slot(s);
}

static void on_feedback_discarded(void *data, struct wp_presentation_feedback *f)
{
    struct feedback_slot *s = data;
    present_feedback_discarded(&s->k->base.counts);
    release_slot(s);
}

static const struct wp_presentation_feedback_listener feedback_listener = {
    .sync_output = on_feedback_sync_output,
    .presented = on_feedback_presented,
    .discarded = on_feedback_discarded,
};

/* ---- the display's operations --------------------------------------------------------------- */

/* Feedback for the frame about to be committed (none when every slot is in flight: the
 * compositor is that far behind, and the counters say so through missed refreshes). */
static void ask_feedback(struct display_wayland *k)
{
    if (!k->presentation) return;
    for (int i = 0; i < FEEDBACK_SLOTS; i++) {
        struct feedback_slot *s = &k->slots[i];
        if (s->feedback) continue;
        s->feedback = wp_presentation_feedback(k->presentation, k->surface);
        if (!s->feedback) return;
        s->k = k;
        s->commit_ns = clock_ns(k->clock);
        wp_presentation_feedback_add_listener(s->feedback, &feedback_listener, s);
        return;
    }
}

/* Some compositors (cage) ignore set_fullscreen on a window not mapped yet and size it at its
 * first buffer: asked again with that buffer. The configure that answers comes before the
 * frame callback after next, when a refusal is told. */
static void ask_fullscreen_mapped(struct display_wayland *k)
{
    xdg_toplevel_set_fullscreen(k->toplevel, NULL);
    k->judge_fullscreen_at = k->base.counts.flips + 2;
}

/* A frame while the compositor does not draw the window: not shown; its events are read for
 * up to 100 ms (the frame callback that says it is drawn again, a configure, a close). */
static int hidden_frame(struct display_wayland *k, char *err, size_t n)
{
    k->base.counts.paused++;
    return pump(k, HIDDEN_PACE_MS, err, n);
}

static int wayland_present(struct display *d, int index, char *err, size_t n)
{
    struct display_wayland *k = to_wayland(d);
    if (k->hidden) return hidden_frame(k, err, n);
    k->frame = wl_surface_frame(k->surface);
    if (!k->frame) return connection_error(k, "asking for a frame callback", err, n);
    wl_callback_add_listener(k->frame, &frame_listener, k);
    ask_feedback(k);
    if (!eglSwapBuffers(k->egl.display, k->egl.surface)) {
        EGLint egl = eglGetError();
        if (wl_display_get_error(k->wl)) return connection_error(k, "eglSwapBuffers", err, n);
        snprintf(err, n, "eglSwapBuffers: %s", egl_headless_error_string(egl));
        return -EIO;
    }
    d->busy = true;
    d->counts.presented++;
    if (d->counts.presented == 1 && !k->toplevel_fullscreen) ask_fullscreen_mapped(k);
    else if (d->counts.presented == 1) k->judge_fullscreen_at = 1; /* granted at once: a later loss is told */
    return pump(k, 0, err, n); /* Mesa may have read our events while swapping: dispatch them */
}

static int wayland_dispatch(struct display *d, char *err, size_t n)
{
    return pump(to_wayland(d), 0, err, n);
}

static int wayland_stalled(struct display *d, char *err, size_t n)
{
    struct display_wayland *k = to_wayland(d);
    k->hidden = true;
    d->busy = false; /* the callback stays asked for: its arrival ends the pause */
    fprintf(stderr, "sbfx-play: Wayland %s: no frame callback for a second: the compositor does not "
            "draw the window (hidden, or its output is off); frames go on at 10 Hz, not shown, until "
            "it does\n", k->name);
    return 0;
}

/* The last frame's callback, for at most a second (a hidden window's never comes). */
static int wayland_finish(struct display *d, char *err, size_t n)
{
    struct display_wayland *k = to_wayland(d);
    int64_t deadline = clock_ns(CLOCK_MONOTONIC) + (int64_t)FINISH_TIMEOUT_MS * 1000000;
    while (d->busy && !k->hidden) {
        int64_t left_ms = (deadline - clock_ns(CLOCK_MONOTONIC)) / 1000000;
        if (left_ms <= 0) break;
        int rc = pump(k, (int)left_ms, err, n);
        if (rc) return rc;
    }
    return 0;
}

static int wayland_reset_context(struct display *d, char *err, size_t n)
{
    struct display_wayland *k = to_wayland(d);
    int rc = wayland_egl_recreate_context(&k->egl, err, n);
    d->robust_context = k->egl.robust;
    return rc;
}

static void wayland_destroy(struct display *d)
{
    if (!d) return;
    struct display_wayland *k = to_wayland(d);
    wayland_egl_close(&k->egl);
    if (k->window) wl_egl_window_destroy(k->window);
    for (int i = 0; i < FEEDBACK_SLOTS; i++)
        if (k->slots[i].feedback) release_slot(&k->slots[i]);
    if (k->frame) wl_callback_destroy(k->frame);
    if (k->toplevel) xdg_toplevel_destroy(k->toplevel);
    if (k->xdg_surface) xdg_surface_destroy(k->xdg_surface);
    if (k->surface) wl_surface_destroy(k->surface);
    if (k->presentation) wp_presentation_destroy(k->presentation);
    if (k->output) wl_output_destroy(k->output);
    if (k->wm_base) xdg_wm_base_destroy(k->wm_base);
    if (k->compositor) wl_compositor_destroy(k->compositor);
    if (k->registry) wl_registry_destroy(k->registry);
    if (k->wl) {
        wl_display_flush(k->wl); /* the window goes away now, not when the socket closes */
        wl_display_disconnect(k->wl);
    }
    free(k);
}

static const struct display_ops wayland_ops = {
    .present = wayland_present,
    .dispatch = wayland_dispatch,
    .stalled = wayland_stalled,
    .finish = wayland_finish,
    .reset_context = wayland_reset_context,
    .destroy = wayland_destroy,
};

/* ---- setup ------------------------------------------------------------------------------ */

static int connect_compositor(struct display_wayland *k, char *err, size_t n)
{
    const char *name = getenv("WAYLAND_DISPLAY");
    snprintf(k->name, sizeof(k->name), "%s", name && *name ? name : "wayland-0");
    k->wl = wl_display_connect(NULL);
    if (!k->wl) {
        const char *dir = getenv("XDG_RUNTIME_DIR");
        snprintf(err, n, "cannot connect to the Wayland compositor %s/%s: %s (is one running, and are "
                 "WAYLAND_DISPLAY and XDG_RUNTIME_DIR those of its session?)", dir ? dir : "$XDG_RUNTIME_DIR",
                 k->name, strerror(errno));
        return -ENOENT;
    }
    k->registry = wl_display_get_registry(k->wl);
    if (!k->registry) return connection_error(k, "asking for the registry", err, n);
    wl_registry_add_listener(k->registry, &registry_listener, k);
    if (wl_display_roundtrip(k->wl) < 0) return connection_error(k, "reading the registry", err, n);
    if (!k->compositor || !k->wm_base) {
        snprintf(err, n, "Wayland %s offers no %s: sbfx-play needs a compositor with xdg-shell (cage, "
                 "weston, labwc, sway, mutter, kwin)", k->name, k->compositor ? "xdg_wm_base" : "wl_compositor");
        return -ENOTSUP;
    }
    xdg_wm_base_add_listener(k->wm_base, &wm_base_listener, k);
    k->clock = CLOCK_MONOTONIC;
    if (k->presentation) wp_presentation_add_listener(k->presentation, &presentation_listener, k);
    if (k->output) wl_output_add_listener(k->output, &output_listener, k);
    if ((k->presentation || k->output) && wl_display_roundtrip(k->wl) < 0)
        return connection_error(k, "reading the presentation clock and the output's mode", err, n);
    return 0;
}

/* The toplevel asks for full screen before its first commit, then waits (bounded) for the
 * configure that says its size. */
static int create_toplevel(struct display_wayland *k, char *err, size_t n)
{
    k->surface = wl_compositor_create_surface(k->compositor);
    k->xdg_surface = k->surface ? xdg_wm_base_get_xdg_surface(k->wm_base, k->surface) : NULL;
    k->toplevel = k->xdg_surface ? xdg_surface_get_toplevel(k->xdg_surface) : NULL;
    if (!k->toplevel) return connection_error(k, "creating the window", err, n);
    xdg_surface_add_listener(k->xdg_surface, &xdg_surface_listener, k);
    xdg_toplevel_add_listener(k->toplevel, &toplevel_listener, k);
    xdg_toplevel_set_title(k->toplevel, "sbfx-play");
    xdg_toplevel_set_app_id(k->toplevel, "sbfx-play");
    xdg_toplevel_set_fullscreen(k->toplevel, NULL);
    wl_surface_commit(k->surface);
    int64_t deadline = clock_ns(CLOCK_MONOTONIC) + (int64_t)CONFIGURE_TIMEOUT_MS * 1000000;
    while (!k->configured) {
        int64_t left_ms = (deadline - clock_ns(CLOCK_MONOTONIC)) / 1000000;
        if (left_ms <= 0) {
            snprintf(err, n, "Wayland %s: the compositor did not configure the window within %d ms",
                     k->name, CONFIGURE_TIMEOUT_MS);
            return -ETIMEDOUT;
        }
        int rc = pump(k, (int)left_ms, err, n);
        if (rc) return rc;
    }
    return 0;
}

/* The whole window is opaque: the compositor need not draw what is behind it. */
static void set_opaque(struct display_wayland *k)
{
    struct wl_region *region = wl_compositor_create_region(k->compositor);
    if (!region) return;
    wl_region_add(region, 0, 0, INT32_MAX, INT32_MAX);
    wl_surface_set_opaque_region(k->surface, region);
    wl_region_destroy(region);
}

static int wayland_setup(struct display_wayland *k, char *err, size_t n)
{
    int rc = connect_compositor(k, err, n);
    if (rc == 0) rc = create_toplevel(k, err, n);
    if (rc) return rc;
    struct display *d = &k->base;
    k->window = wl_egl_window_create(k->surface, d->width, d->height);
    if (!k->window) {
        snprintf(err, n, "wl_egl_window_create(%dx%d) failed", d->width, d->height);
        return -ENOMEM;
    }
    set_opaque(k);
    rc = wayland_egl_open(&k->egl, k->wl, k->window, err, n);
    if (rc) return rc;
    d->fd = wl_display_get_fd(k->wl);
    d->robust_context = k->egl.robust;
    d->presentation = k->presentation != NULL;
    d->resized = false;
    describe(k);
    return 0;
}

int display_wayland_create(const struct display_wayland_desc *desc, struct display **out,
                           char *err, size_t n)
{
    *out = NULL;
    struct display_wayland *k = calloc(1, sizeof(*k));
    if (!k) {
        snprintf(err, n, "out of memory");
        return -ENOMEM;
    }
    k->desc = *desc;
    k->fullscreen_logged = -1;
    k->base = (struct display){.ops = &wayland_ops, .name = "wayland", .fd = -1, .framebuffer = 0};
    int rc = wayland_setup(k, err, n);
    if (rc) {
        wayland_destroy(&k->base);
        return rc;
    }
    *out = &k->base;
    return 0;
}
