/* tests/vm helper: turns the first connected output of a DRM device on and off COUNT times,
 * with a page flip (and its vblank event) in between, as fast as the driver allows:
 *   vblank_stress DEVICE COUNT
 * Each cycle: a dumb buffer scanned out (drmModeSetCrtc: the CRTC's vblank goes on), one page
 * flip waited for (a vblank reference, the vblank interrupt enabled), the CRTC switched off
 * (drm_crtc_vblank_off: the driver's disable_vblank while the vblank timer may be firing).
 *
 * Debian 6.1's vkms deadlocks on the last step when its vblank hrtimer fires at that moment:
 * vkms_disable_vblank() calls hrtimer_cancel() under dev->vblank_time_lock, which the timer's
 * callback (vkms_vblank_simulate -> drm_handle_vblank) spins on. tests/vm/patches/
 * vkms-vblank-cancel-deadlock.patch fixes it; tests/vm/guest.sh runs this as drm-vblank-off-stress.
 * Prints "cycles N, flips N" and exits 0, or 1 with what failed. */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

struct output {
    uint32_t connector, crtc, fb;
    drmModeModeInfo mode;
};

static int find_output(int fd, struct output *o)
{
    drmModeRes *res = drmModeGetResources(fd);
    if (!res) return -1;
    int found = -1;
    for (int i = 0; i < res->count_connectors && found < 0; i++) {
        drmModeConnector *c = drmModeGetConnector(fd, res->connectors[i]);
        if (!c) continue;
        if (c->connection == DRM_MODE_CONNECTED && c->count_modes > 0 && c->encoder_id) {
            drmModeEncoder *e = drmModeGetEncoder(fd, c->encoder_id);
            if (e && e->crtc_id) {
                o->connector = c->connector_id;
                o->crtc = e->crtc_id;
                o->mode = c->modes[0];
                found = 0;
            }
            drmModeFreeEncoder(e);
        } else if (c->connection == DRM_MODE_CONNECTED && c->count_modes > 0 && res->count_crtcs) {
            o->connector = c->connector_id;
            o->crtc = res->crtcs[0];
            o->mode = c->modes[0];
            found = 0;
        }
        drmModeFreeConnector(c);
    }
    drmModeFreeResources(res);
    return found;
}

static int make_fb(int fd, struct output *o)
{
    struct drm_mode_create_dumb create = {.width = o->mode.hdisplay, .height = o->mode.vdisplay, .bpp = 32};
    if (drmIoctl(fd, DRM_IOCTL_MODE_CREATE_DUMB, &create) != 0) return -1;
    return drmModeAddFB(fd, create.width, create.height, 24, 32, create.pitch, create.handle, &o->fb);
}

static void on_flip(int fd, unsigned seq, unsigned s, unsigned us, void *done)
{
    (void)fd, (void)seq, (void)s, (void)us;
    *(int *)done = 1;
}

static int flip_and_wait(int fd, const struct output *o)
{
    int done = 0;
    if (drmModePageFlip(fd, o->crtc, o->fb, DRM_MODE_PAGE_FLIP_EVENT, &done) != 0) return -1;
    drmEventContext ev = {.version = 2, .page_flip_handler = on_flip};
    while (!done) {
        struct pollfd p = {.fd = fd, .events = POLLIN};
        int r = poll(&p, 1, 2000);
        if (r == 0) {
            errno = ETIMEDOUT;
            return -1;
        }
        if (r < 0 && errno != EINTR) return -1;
        if (r > 0 && drmHandleEvent(fd, &ev) != 0) return -1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: vblank_stress DEVICE COUNT\n");
        return 1;
    }
    int count = atoi(argv[2]);
    int fd = open(argv[1], O_RDWR | O_CLOEXEC);
    struct output o;
    memset(&o, 0, sizeof(o));
    if (fd < 0 || find_output(fd, &o) != 0 || make_fb(fd, &o) != 0) {
        fprintf(stderr, "vblank_stress: %s: no output to drive: %s\n", argv[1], strerror(errno));
        return 1;
    }
    int flips = 0, cycle;
    for (cycle = 0; cycle < count; cycle++) {
        if (drmModeSetCrtc(fd, o.crtc, o.fb, 0, 0, &o.connector, 1, &o.mode) != 0) break;
        if (flip_and_wait(fd, &o) != 0) break;
        flips++;
        if (drmModeSetCrtc(fd, o.crtc, 0, 0, 0, NULL, 0, NULL) != 0) break;
    }
    int failed = cycle < count;
    if (failed) fprintf(stderr, "vblank_stress: cycle %d: %s\n", cycle, strerror(errno));
    printf("cycles %d, flips %d\n", cycle, flips);
    close(fd);
    return failed;
}
