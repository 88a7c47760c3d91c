/* The DRM/KMS display: drm_device (discovery) + gbm_egl (surface, context) + drm_kms (atomic or
 * legacy) + drm_fb (framebuffers cached per bo). One page flip is in flight at a time: present()
 * swaps, locks the new front bo and queues its flip; the flip event (dispatch) releases the bo
 * that left the screen. The first frame sets the mode. Once a second the connector's state is
 * read (display_link.h): while it is unplugged, frames are rendered but not shown (the loop is
 * paced at 10 Hz then), and when it is back the mode is set again. */
#include "display/display.h"

#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "drm/drm_device.h"
#include "drm/drm_fb.h"
#include "drm/drm_kms.h"
#include "drm/drm_mode_spec.h"
#include "drm/drm_writeback.h"
#include "display/display_link.h"
#include "egl/egl_headless.h"
#include "drm/gbm_egl.h"

#define FLIP_TIMEOUT_MS 1000

struct display_drm {
    struct display base;
    struct display_drm_desc desc;
    struct drm_device drm;
    struct gbm_egl ge;
    const struct drm_kms *kms;
    struct gbm_bo *shown;     /* on screen */
    struct gbm_bo *pending;   /* flip queued, not on screen yet */
    bool mode_set;
    unsigned last_sequence;   /* vblank counter of the last flip */
    drmEventContext events;
    struct display_link link;
};

static struct display_drm *to_drm(struct display *d)
{
    return (struct display_drm *)d; /* base is the first member */
}

static void on_flip(int fd, unsigned sequence, unsigned sec, unsigned usec, void *user)
{
    struct display_drm *k = user;
    if (k->shown) gbm_surface_release_buffer(k->ge.surface, k->shown);
    k->shown = k->pending;
    k->pending = NULL;
    k->base.busy = false;
    k->base.counts.flips++;
    if (k->last_sequence && sequence > k->last_sequence + 1)
        k->base.counts.missed += sequence - k->last_sequence - 1;
    k->last_sequence = sequence;
}

static int drm_dispatch(struct display *d, char *err, size_t n)
{
    struct display_drm *k = to_drm(d);
    if (drmHandleEvent(k->drm.fd, &k->events) == 0) return 0;
    int rc = -errno;
    snprintf(err, n, "DRM %s: reading page-flip events: %s", k->drm.path, strerror(errno));
    return rc ? rc : -EIO;
}

/* Blocks (bounded) until the flip in flight completed. */
static int wait_flip(struct display_drm *k, char *err, size_t n)
{
    while (k->pending) {
        struct pollfd p = {.fd = k->drm.fd, .events = POLLIN};
        int r = poll(&p, 1, FLIP_TIMEOUT_MS);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) {
            snprintf(err, n, "DRM %s: page flip on CRTC %u did not complete within %d ms",
                     k->drm.path, k->drm.crtc_id, FLIP_TIMEOUT_MS);
            return -ETIMEDOUT;
        }
        int rc = drm_dispatch(&k->base, err, n);
        if (rc) return rc;
    }
    return 0;
}

static int show(struct display_drm *k, struct gbm_bo *bo, uint32_t fb_id, char *err, size_t n)
{
    if (!k->mode_set) {
        int rc = k->kms->modeset(&k->drm, fb_id, err, n);
        if (rc) return rc;
        k->mode_set = true;
        if (k->shown) gbm_surface_release_buffer(k->ge.surface, k->shown); /* after a replug */
        k->shown = bo; /* on screen now: no event */
        return 0;
    }
    int rc = k->kms->flip(&k->drm, fb_id, k, err, n);
    if (rc) return rc;
    k->pending = bo;
    k->base.busy = true;
    return 0;
}

static int64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

/* Once a second: is the connector still there. Unplugged: scan-out pauses (logged once); back:
 * the next frame sets the mode again (logged once). */
static void check_link(struct display_drm *k)
{
    if (!link_check_due(&k->link, now_ns())) return;
    int connected = drm_device_connector_connected(&k->drm);
    if (connected < 0) return; /* the ioctl failed: the flips will say why */
    switch (link_update(&k->link, connected)) {
    case LINK_PAUSE:
        k->base.counts.unplugs++;
        fprintf(stderr, "sbfx-play: DRM %s: %s disconnected; scan-out paused, rendering goes on\n",
                k->drm.path, k->drm.connector_name);
        break;
    case LINK_RESUME:
        k->base.counts.replugs++;
        k->mode_set = false;
        k->last_sequence = 0;
        fprintf(stderr, "sbfx-play: DRM %s: %s connected again; setting the mode, scan-out resumes\n",
                k->drm.path, k->drm.connector_name);
        break;
    case LINK_NONE: break;
    }
}

/* A frame while the connector is away: not shown; the loop slows to 10 Hz. */
static int skip_frame(struct display *d)
{
    struct timespec pace = {0, LINK_PAUSED_FRAME_NS};
    nanosleep(&pace, NULL);
    d->counts.paused++;
    return 0;
}

static int drm_present(struct display *d, int index, char *err, size_t n)
{
    struct display_drm *k = to_drm(d);
    int rc = wait_flip(k, err, n); /* the loop normally waited already */
    if (rc) return rc;
    check_link(k);
    if (k->link.disconnected) return skip_frame(d);
    if (!eglSwapBuffers(k->ge.display, k->ge.egl_surface)) {
        snprintf(err, n, "eglSwapBuffers: %s", egl_headless_error_string(eglGetError()));
        return -EIO;
    }
    struct gbm_bo *bo = gbm_surface_lock_front_buffer(k->ge.surface);
    if (!bo) {
        snprintf(err, n, "gbm_surface_lock_front_buffer: no buffer (%s)", strerror(errno));
        return -EIO;
    }
    struct drm_fb *fb = drm_fb_get_from_bo(k->drm.fd, bo, err, n);
    rc = fb ? show(k, bo, fb->fb_id, err, n) : -EIO;
    if (rc) {
        gbm_surface_release_buffer(k->ge.surface, bo);
        return rc;
    }
    d->counts.presented++;
    return 0;
}

static int drm_finish(struct display *d, char *err, size_t n)
{
    struct display_drm *k = to_drm(d);
    int rc = wait_flip(k, err, n);
    if (rc == 0 && k->desc.screenshot && k->mode_set)
        rc = drm_writeback_capture(&k->drm, k->desc.screenshot, err, n);
    return rc;
}

static void drm_destroy(struct display *d)
{
    if (!d) return;
    struct display_drm *k = to_drm(d);
    char why[256];
    if (k->pending && wait_flip(k, why, sizeof(why)) != 0)
        fprintf(stderr, "sbfx-play: %s\n", why);
    if (k->mode_set && drm_device_restore(&k->drm, why, sizeof(why)) != 0)
        fprintf(stderr, "sbfx-play: %s\n", why);
    if (k->ge.surface && k->shown) gbm_surface_release_buffer(k->ge.surface, k->shown);
    if (k->ge.surface && k->pending) gbm_surface_release_buffer(k->ge.surface, k->pending);
    gbm_egl_close(&k->ge); /* destroys the bos: their framebuffers go with them */
    drm_device_close(&k->drm);
    free(k);
}

/* The GBM surface, its buffers on screen and the KMS state stay: only the context is new. */
static int drm_reset_context(struct display *d, char *err, size_t n)
{
    struct display_drm *k = to_drm(d);
    int rc = gbm_egl_recreate_context(&k->ge, err, n);
    d->robust_context = k->ge.robust;
    return rc;
}

static const struct display_ops drm_ops = {
    .present = drm_present,
    .dispatch = drm_dispatch,
    .finish = drm_finish,
    .reset_context = drm_reset_context,
    .destroy = drm_destroy,
};

static int choose_kms(struct display_drm *k, char *err, size_t n)
{
    char why[256];
    if (k->desc.modeset == MODESET_LEGACY && k->desc.screenshot) {
        snprintf(err, n, "--screenshot reads back through an atomic writeback connector: it "
                 "cannot work with --modeset legacy");
        return -EINVAL;
    }
    if (k->desc.modeset == MODESET_LEGACY) {
        k->kms = &drm_kms_legacy;
        return 0;
    }
    int rc = drm_atomic_init(&k->drm, why, sizeof(why));
    if (rc == 0) {
        k->kms = &drm_kms_atomic;
        return 0;
    }
    if (k->desc.modeset == MODESET_AUTO && !k->desc.screenshot && rc == -ENOTSUP) {
        k->kms = &drm_kms_legacy; /* the fallback */
        return 0;
    }
    snprintf(err, n, "%s%s", why, k->desc.screenshot ? " (--screenshot needs atomic writeback)" : "");
    return rc;
}

static int drm_setup(struct display_drm *k, char *err, size_t n)
{
    const struct drm_device_desc dd = {
        .path = k->desc.device, .connector = k->desc.connector, .mode = k->desc.mode,
    };
    int rc = drm_device_open(&k->drm, &dd, err, n);
    if (rc == 0) rc = choose_kms(k, err, n);
    if (rc) return rc;
    const drmModeModeInfo *m = &k->drm.mode;
    rc = gbm_egl_open(&k->ge, k->drm.fd, m->hdisplay, m->vdisplay, err, n);
    if (rc) return rc;
    struct display *d = &k->base;
    d->width = m->hdisplay;
    d->height = m->vdisplay;
    d->fd = k->drm.fd;
    d->refresh_hz = drm_mode_refresh(m);
    d->robust_context = k->ge.robust;
    snprintf(d->description, sizeof(d->description), "DRM %s (%s) %s %dx%d@%.2f %s", k->drm.path,
             k->drm.driver, k->drm.connector_name, d->width, d->height, d->refresh_hz, k->kms->name);
    return 0;
}

int display_drm_create(const struct display_drm_desc *desc, struct display **out, char *err,
                       size_t n)
{
    *out = NULL;
    struct display_drm *k = calloc(1, sizeof(*k));
    if (!k) {
        snprintf(err, n, "out of memory");
        return -ENOMEM;
    }
    k->desc = *desc;
    k->drm.fd = -1;
    k->base = (struct display){.ops = &drm_ops, .name = "drm", .fd = -1, .framebuffer = 0};
    k->events = (drmEventContext){.version = 2, .page_flip_handler = on_flip};
    int rc = drm_setup(k, err, n);
    if (rc) {
        drm_destroy(&k->base);
        return rc;
    }
    *out = &k->base;
    return 0;
}
