/* A DRM framebuffer per GBM buffer object, made the first time the bo is shown and cached on it
 * (gbm_bo_set_user_data), removed when GBM destroys the bo. A GBM surface cycles through a few
 * bos, so after the first frames no framebuffer is created and nothing is allocated. */
#ifndef SBFX_DRM_FB_H
#define SBFX_DRM_FB_H

#include <gbm.h>
#include <stddef.h>
#include <stdint.h>

struct drm_fb {
    struct gbm_bo *bo;
    int fd;
    uint32_t fb_id;
};

/* NULL with a message in err when the framebuffer cannot be made. Uses the bo's modifier with
 * drmModeAddFB2WithModifiers when it has a valid one, else plain drmModeAddFB2 (vkms, and
 * drivers without modifiers, report DRM_FORMAT_MOD_INVALID), else the legacy drmModeAddFB. */
struct drm_fb *drm_fb_get_from_bo(int fd, struct gbm_bo *bo, char *err, size_t n);

#endif
