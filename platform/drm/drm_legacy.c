/* Legacy KMS: drmModeSetCrtc for the mode, drmModePageFlip with an event for every frame. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "drm/drm_kms.h"

static int legacy_modeset(struct drm_device *d, uint32_t fb_id, char *err, size_t n)
{
    if (drmModeSetCrtc(d->fd, d->crtc_id, fb_id, 0, 0, &d->connector_id, 1, &d->mode) == 0) return 0;
    int rc = -errno;
    snprintf(err, n, "DRM %s: drmModeSetCrtc(crtc %u, %s, %s): %s", d->path, d->crtc_id,
             d->connector_name, d->mode.name, strerror(errno));
    return rc;
}

static int legacy_flip(struct drm_device *d, uint32_t fb_id, void *user, char *err, size_t n)
{
    if (drmModePageFlip(d->fd, d->crtc_id, fb_id, DRM_MODE_PAGE_FLIP_EVENT, user) == 0) return 0;
    int rc = -errno;
    snprintf(err, n, "DRM %s: drmModePageFlip(crtc %u): %s", d->path, d->crtc_id, strerror(errno));
    return rc;
}

const struct drm_kms drm_kms_legacy = {
    .name = "legacy",
    .modeset = legacy_modeset,
    .flip = legacy_flip,
};
