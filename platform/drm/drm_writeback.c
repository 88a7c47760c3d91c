/* Writeback capture: a dumb XRGB8888 buffer, one ALLOW_MODESET commit, wait on the out-fence,
 * map, PNG, detach. Runs once, after the last frame, so it may allocate. */
#include "drm/drm_writeback.h"

#include <drm_fourcc.h>
#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "drm/drm_kms.h"
#include "image/png_io.h"

#define FENCE_TIMEOUT_MS 3000

struct writeback {
    uint32_t connector_id, prop_crtc, prop_fb, prop_fence;
    uint32_t handle, pitch, fb_id;
    uint64_t size;
    void *map;
};

static bool drives_crtc(int fd, const drmModeConnector *c, int crtc_index)
{
    for (int i = 0; i < c->count_encoders; i++) {
        drmModeEncoder *e = drmModeGetEncoder(fd, c->encoders[i]);
        bool ok = e && (e->possible_crtcs & (1u << crtc_index));
        drmModeFreeEncoder(e);
        if (ok) return true;
    }
    return false;
}

static int find_connector(struct drm_device *d, struct writeback *wb, char *err, size_t n)
{
    if (drmSetClientCap(d->fd, DRM_CLIENT_CAP_WRITEBACK_CONNECTORS, 1) != 0) {
        snprintf(err, n, "DRM %s (%s): no writeback connectors (%s)", d->path, d->driver, strerror(errno));
        return -ENOTSUP;
    }
    drmModeRes *res = drmModeGetResources(d->fd);
    for (int i = 0; res && i < res->count_connectors && !wb->connector_id; i++) {
        drmModeConnector *c = drmModeGetConnector(d->fd, res->connectors[i]);
        if (c && c->connector_type == DRM_MODE_CONNECTOR_WRITEBACK && drives_crtc(d->fd, c, d->crtc_index))
            wb->connector_id = c->connector_id;
        drmModeFreeConnector(c);
    }
    drmModeFreeResources(res);
    if (!wb->connector_id) {
        snprintf(err, n, "DRM %s (%s): no writeback connector for CRTC %u", d->path, d->driver, d->crtc_id);
        return -ENOTSUP;
    }
    const uint32_t C = DRM_MODE_OBJECT_CONNECTOR;
    wb->prop_crtc = drm_property_id(d->fd, wb->connector_id, C, "CRTC_ID");
    wb->prop_fb = drm_property_id(d->fd, wb->connector_id, C, "WRITEBACK_FB_ID");
    wb->prop_fence = drm_property_id(d->fd, wb->connector_id, C, "WRITEBACK_OUT_FENCE_PTR");
    if (wb->prop_crtc && wb->prop_fb && wb->prop_fence) return 0;
    snprintf(err, n, "DRM %s: writeback connector %u lacks its properties", d->path, wb->connector_id);
    return -ENOTSUP;
}

static int create_buffer(struct drm_device *d, struct writeback *wb, char *err, size_t n)
{
    uint32_t w = d->mode.hdisplay, h = d->mode.vdisplay;
    struct drm_mode_create_dumb create = {.width = w, .height = h, .bpp = 32};
    if (drmIoctl(d->fd, DRM_IOCTL_MODE_CREATE_DUMB, &create) != 0) {
        int rc = -errno;
        snprintf(err, n, "DRM %s: DRM_IOCTL_MODE_CREATE_DUMB %ux%u: %s", d->path, w, h, strerror(errno));
        return rc;
    }
    wb->handle = create.handle;
    wb->pitch = create.pitch;
    wb->size = create.size;
    uint32_t handles[4] = {wb->handle}, pitches[4] = {wb->pitch}, offsets[4] = {0};
    if (drmModeAddFB2(d->fd, w, h, DRM_FORMAT_XRGB8888, handles, pitches, offsets, &wb->fb_id, 0)) {
        int rc = -errno;
        snprintf(err, n, "DRM %s: drmModeAddFB2 of the writeback buffer: %s", d->path, strerror(errno));
        return rc;
    }
    struct drm_mode_map_dumb map = {.handle = wb->handle};
    if (drmIoctl(d->fd, DRM_IOCTL_MODE_MAP_DUMB, &map) != 0) {
        int rc = -errno;
        snprintf(err, n, "DRM %s: DRM_IOCTL_MODE_MAP_DUMB: %s", d->path, strerror(errno));
        return rc;
    }
    wb->map = mmap(NULL, wb->size, PROT_READ, MAP_SHARED, d->fd, (off_t)map.offset);
    if (wb->map == MAP_FAILED) {
        wb->map = NULL;
        int rc = -errno;
        snprintf(err, n, "DRM %s: mmap of the writeback buffer: %s", d->path, strerror(errno));
        return rc;
    }
    return 0;
}

/* Routes the CRTC into the buffer (fb != 0) or detaches the connector (fb == 0). */
static int commit(struct drm_device *d, struct writeback *wb, uint32_t fb, int *fence)
{
    drmModeAtomicReq *req = drmModeAtomicAlloc();
    if (!req) return -ENOMEM;
    int r = drmModeAtomicAddProperty(req, wb->connector_id, wb->prop_crtc, fb ? d->crtc_id : 0);
    if (fb && r >= 0) r = drmModeAtomicAddProperty(req, wb->connector_id, wb->prop_fb, fb);
    if (fb && r >= 0)
        r = drmModeAtomicAddProperty(req, wb->connector_id, wb->prop_fence, (uint64_t)(uintptr_t)fence);
    int rc = r < 0 ? -ENOMEM : 0;
    if (rc == 0 && drmModeAtomicCommit(d->fd, req, DRM_MODE_ATOMIC_ALLOW_MODESET, NULL) != 0) rc = -errno;
    drmModeAtomicFree(req);
    return rc;
}

static int wait_fence(int fence, char *err, size_t n)
{
    struct pollfd p = {.fd = fence, .events = POLLIN};
    int r;
    do r = poll(&p, 1, FENCE_TIMEOUT_MS);
    while (r < 0 && errno == EINTR);
    if (r == 1) return 0;
    snprintf(err, n, "writeback: the out-fence did not signal within %d ms%s", FENCE_TIMEOUT_MS,
             r < 0 ? " (poll failed)" : "");
    return -ETIMEDOUT;
}

static int save_png(const struct drm_device *d, const struct writeback *wb, const char *path,
                    char *err, size_t n)
{
    int w = d->mode.hdisplay, h = d->mode.vdisplay;
    uint8_t *rgba = malloc((size_t)w * h * 4);
    if (!rgba) {
        snprintf(err, n, "writeback: out of memory for a %dx%d picture", w, h);
        return -ENOMEM;
    }
    for (int y = 0; y < h; y++) {
        const uint32_t *row = (const uint32_t *)((const uint8_t *)wb->map + (size_t)y * wb->pitch);
        uint8_t *out = rgba + (size_t)y * w * 4;
        for (int x = 0; x < w; x++) {
            uint32_t px = row[x]; /* XRGB8888: little-endian 32-bit words */
            out[4 * x + 0] = (uint8_t)(px >> 16);
            out[4 * x + 1] = (uint8_t)(px >> 8);
            out[4 * x + 2] = (uint8_t)px;
            out[4 * x + 3] = 255;
        }
    }
    int rc = png_write_rgba(path, rgba, w, h, false, err, n);
    free(rgba);
    return rc;
}

static void release(struct drm_device *d, struct writeback *wb)
{
    if (wb->map) munmap(wb->map, wb->size);
    if (wb->fb_id) drmModeRmFB(d->fd, wb->fb_id);
    if (wb->handle) {
        struct drm_mode_destroy_dumb destroy = {.handle = wb->handle};
        drmIoctl(d->fd, DRM_IOCTL_MODE_DESTROY_DUMB, &destroy);
    }
}

int drm_writeback_capture(struct drm_device *d, const char *png_path, char *err, size_t n)
{
    if (!d->atomic) {
        snprintf(err, n, "writeback needs atomic modesetting (not --modeset legacy)");
        return -ENOTSUP;
    }
    struct writeback wb = {0};
    int fence = -1;
    int rc = find_connector(d, &wb, err, n);
    if (rc == 0) rc = create_buffer(d, &wb, err, n);
    if (rc == 0 && (rc = commit(d, &wb, wb.fb_id, &fence)) != 0)
        snprintf(err, n, "DRM %s: writeback commit (connector %u -> CRTC %u): %s", d->path,
                 wb.connector_id, d->crtc_id, strerror(-rc));
    if (rc == 0 && fence < 0) {
        snprintf(err, n, "DRM %s: the writeback commit returned no out-fence", d->path);
        rc = -EIO;
    }
    if (rc == 0) rc = wait_fence(fence, err, n);
    if (rc == 0) rc = save_png(d, &wb, png_path, err, n);
    if (fence >= 0) close(fence);
    if (wb.connector_id && wb.fb_id) commit(d, &wb, 0, NULL);
    release(d, &wb);
    return rc;
}
