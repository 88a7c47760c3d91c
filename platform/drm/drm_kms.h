/* How a framebuffer reaches the screen: one implementation per KMS API (kmscube's drm-atomic.c
 * and drm-legacy.c), chosen once; the display code calls through the struct.
 *
 *   modeset  blocking: sets the mode and shows fb (the first frame)
 *   flip     non-blocking: shows fb at the next vblank; a page-flip event with `user` arrives
 *            on the device fd (drmHandleEvent) when it is on screen
 *
 * Atomic needs DRM_CLIENT_CAP_ATOMIC and the property ids (drm_atomic_init); the per-frame
 * atomic flip is one DRM_IOCTL_MODE_ATOMIC on fixed arrays, so it allocates nothing (libdrm's
 * drmModeAtomicAlloc/Commit would, every frame). Both return 0 or -errno with a message. */
#ifndef SBFX_DRM_KMS_H
#define SBFX_DRM_KMS_H

#include <stddef.h>
#include <stdint.h>

#include "drm/drm_device.h"

struct drm_kms {
    const char *name; /* "atomic" or "legacy" */
    int (*modeset)(struct drm_device *d, uint32_t fb_id, char *err, size_t n);
    int (*flip)(struct drm_device *d, uint32_t fb_id, void *user, char *err, size_t n);
};

extern const struct drm_kms drm_kms_atomic;
extern const struct drm_kms drm_kms_legacy;

/* Turns on atomic modesetting and looks up the properties; -ENOTSUP when the driver has no
 * atomic support (then use legacy). */
int drm_atomic_init(struct drm_device *d, char *err, size_t n);

/* Looks up a property id by name on a KMS object; 0 when it has none. */
uint32_t drm_property_id(int fd, uint32_t object_id, uint32_t object_type, const char *name);

#endif
