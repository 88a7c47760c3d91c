/* Atomic KMS: one blocking ALLOW_MODESET commit for the mode, then non-blocking commits of the
 * primary plane's FB_ID with a page-flip event. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "drm/drm_kms.h"

#define ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))

uint32_t drm_property_id(int fd, uint32_t object_id, uint32_t object_type, const char *name)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, object_id, object_type);
    uint32_t id = 0;
    for (uint32_t i = 0; props && i < props->count_props && !id; i++) {
        drmModePropertyRes *p = drmModeGetProperty(fd, props->props[i]);
        if (p && strcmp(p->name, name) == 0) id = p->prop_id;
        drmModeFreeProperty(p);
    }
    drmModeFreeObjectProperties(props);
    return id;
}

struct prop_ref {
    uint32_t *dst;
    uint32_t object, type;
    const char *name;
};

int drm_atomic_init(struct drm_device *d, char *err, size_t n)
{
    if (!d->plane_id) {
        snprintf(err, n, "DRM %s (%s): no primary plane found for CRTC %u (no universal planes)",
                 d->path, d->driver, d->crtc_id);
        return -ENOTSUP;
    }
    if (drmSetClientCap(d->fd, DRM_CLIENT_CAP_ATOMIC, 1) != 0) {
        int rc = errno == EOPNOTSUPP || errno == EINVAL ? -ENOTSUP : -errno;
        snprintf(err, n, "DRM %s (%s): no atomic modesetting (%s)", d->path, d->driver, strerror(errno));
        return rc;
    }
    struct drm_atomic_props *p = &d->props;
    const uint32_t C = DRM_MODE_OBJECT_CONNECTOR, R = DRM_MODE_OBJECT_CRTC, P = DRM_MODE_OBJECT_PLANE;
    const struct prop_ref refs[] = {
        {&p->conn_crtc_id, d->connector_id, C, "CRTC_ID"}, {&p->crtc_mode_id, d->crtc_id, R, "MODE_ID"},
        {&p->crtc_active, d->crtc_id, R, "ACTIVE"},        {&p->plane_fb_id, d->plane_id, P, "FB_ID"},
        {&p->plane_crtc_id, d->plane_id, P, "CRTC_ID"},    {&p->plane_src_x, d->plane_id, P, "SRC_X"},
        {&p->plane_src_y, d->plane_id, P, "SRC_Y"},        {&p->plane_src_w, d->plane_id, P, "SRC_W"},
        {&p->plane_src_h, d->plane_id, P, "SRC_H"},        {&p->plane_crtc_x, d->plane_id, P, "CRTC_X"},
        {&p->plane_crtc_y, d->plane_id, P, "CRTC_Y"},      {&p->plane_crtc_w, d->plane_id, P, "CRTC_W"},
        {&p->plane_crtc_h, d->plane_id, P, "CRTC_H"},
    };
    for (size_t i = 0; i < ARRAY_SIZE(refs); i++) {
        *refs[i].dst = drm_property_id(d->fd, refs[i].object, refs[i].type, refs[i].name);
        if (*refs[i].dst) continue;
        snprintf(err, n, "DRM %s (%s): object %u has no property %s", d->path, d->driver,
                 refs[i].object, refs[i].name);
        drmSetClientCap(d->fd, DRM_CLIENT_CAP_ATOMIC, 0);
        return -ENOTSUP;
    }
    if (drmModeCreatePropertyBlob(d->fd, &d->mode, sizeof(d->mode), &p->mode_blob) != 0) {
        int rc = -errno;
        snprintf(err, n, "DRM %s: drmModeCreatePropertyBlob(mode): %s", d->path, strerror(errno));
        return rc;
    }
    d->atomic = true;
    return 0;
}

static int add(drmModeAtomicReq *req, uint32_t object, uint32_t prop, uint64_t value)
{
    return drmModeAtomicAddProperty(req, object, prop, value) < 0 ? -ENOMEM : 0;
}

static int fill_modeset(const struct drm_device *d, drmModeAtomicReq *req, uint32_t fb_id)
{
    const struct drm_atomic_props *p = &d->props;
    uint32_t w = d->mode.hdisplay, h = d->mode.vdisplay, plane = d->plane_id;
    int rc = add(req, d->connector_id, p->conn_crtc_id, d->crtc_id);
    rc |= add(req, d->crtc_id, p->crtc_mode_id, p->mode_blob);
    rc |= add(req, d->crtc_id, p->crtc_active, 1);
    rc |= add(req, plane, p->plane_fb_id, fb_id);
    rc |= add(req, plane, p->plane_crtc_id, d->crtc_id);
    rc |= add(req, plane, p->plane_src_x, 0) | add(req, plane, p->plane_src_y, 0);
    rc |= add(req, plane, p->plane_src_w, (uint64_t)w << 16) | add(req, plane, p->plane_src_h, (uint64_t)h << 16);
    rc |= add(req, plane, p->plane_crtc_x, 0) | add(req, plane, p->plane_crtc_y, 0);
    rc |= add(req, plane, p->plane_crtc_w, w) | add(req, plane, p->plane_crtc_h, h);
    return rc ? -ENOMEM : 0;
}

static int atomic_modeset(struct drm_device *d, uint32_t fb_id, char *err, size_t n)
{
    drmModeAtomicReq *req = drmModeAtomicAlloc();
    int rc = req ? fill_modeset(d, req, fb_id) : -ENOMEM;
    if (rc == 0 && drmModeAtomicCommit(d->fd, req, DRM_MODE_ATOMIC_ALLOW_MODESET, NULL) != 0)
        rc = -errno;
    drmModeAtomicFree(req);
    if (rc)
        snprintf(err, n, "DRM %s: atomic modeset (crtc %u, %s, %s): %s", d->path, d->crtc_id,
                 d->connector_name, d->mode.name, strerror(-rc));
    return rc;
}

static int atomic_flip(struct drm_device *d, uint32_t fb_id, void *user, char *err, size_t n)
{
    uint32_t objs[1] = {d->plane_id}, count_props[1] = {1}, props[1] = {d->props.plane_fb_id};
    uint64_t values[1] = {fb_id};
    struct drm_mode_atomic atomic = {
        .flags = DRM_MODE_ATOMIC_NONBLOCK | DRM_MODE_PAGE_FLIP_EVENT,
        .count_objs = 1,
        .objs_ptr = (uint64_t)(uintptr_t)objs,
        .count_props_ptr = (uint64_t)(uintptr_t)count_props,
        .props_ptr = (uint64_t)(uintptr_t)props,
        .prop_values_ptr = (uint64_t)(uintptr_t)values,
        .user_data = (uint64_t)(uintptr_t)user,
    };
    if (drmIoctl(d->fd, DRM_IOCTL_MODE_ATOMIC, &atomic) == 0) return 0;
    int rc = -errno;
    snprintf(err, n, "DRM %s: atomic page flip (plane %u): %s", d->path, d->plane_id, strerror(errno));
    return rc;
}

const struct drm_kms drm_kms_atomic = {
    .name = "atomic",
    .modeset = atomic_modeset,
    .flip = atomic_flip,
};
