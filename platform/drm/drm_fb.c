/* Framebuffers cached per GBM bo. */
#include "drm/drm_fb.h"

#include <drm_fourcc.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

static void drm_fb_destroy_callback(struct gbm_bo *bo, void *data)
{
    struct drm_fb *fb = data;
    if (fb->fb_id) drmModeRmFB(fb->fd, fb->fb_id);
    free(fb);
}

static int add_fb(int fd, struct gbm_bo *bo, uint32_t *fb_id)
{
    uint32_t width = gbm_bo_get_width(bo), height = gbm_bo_get_height(bo);
    uint32_t format = gbm_bo_get_format(bo);
    uint32_t handles[4] = {0}, strides[4] = {0}, offsets[4] = {0};
    uint64_t modifiers[4] = {0};
    uint64_t modifier = gbm_bo_get_modifier(bo);
    int planes = gbm_bo_get_plane_count(bo);
    for (int i = 0; i < planes && i < 4; i++) {
        handles[i] = gbm_bo_get_handle_for_plane(bo, i).u32;
        strides[i] = gbm_bo_get_stride_for_plane(bo, i);
        offsets[i] = gbm_bo_get_offset(bo, i);
        modifiers[i] = modifier;
    }
    int r = -1;
    if (modifier != DRM_FORMAT_MOD_INVALID)
        r = drmModeAddFB2WithModifiers(fd, width, height, format, handles, strides, offsets,
                                       modifiers, fb_id, DRM_MODE_FB_MODIFIERS);
    if (r) r = drmModeAddFB2(fd, width, height, format, handles, strides, offsets, fb_id, 0);
    if (r && planes == 1) /* very old drivers: depth 24, 32 bpp */
        r = drmModeAddFB(fd, width, height, 24, 32, strides[0], handles[0], fb_id);
    return r ? -errno : 0;
}

struct drm_fb *drm_fb_get_from_bo(int fd, struct gbm_bo *bo, char *err, size_t n)
{
    struct drm_fb *fb = gbm_bo_get_user_data(bo);
    if (fb) return fb;
    fb = calloc(1, sizeof(*fb));
    if (!fb) {
        snprintf(err, n, "out of memory for a framebuffer");
        return NULL;
    }
    fb->bo = bo;
    fb->fd = fd;
    int rc = add_fb(fd, bo, &fb->fb_id);
    if (rc) {
        snprintf(err, n, "drmModeAddFB2 of a %ux%u buffer (format 0x%08x): %s",
                 gbm_bo_get_width(bo), gbm_bo_get_height(bo), gbm_bo_get_format(bo), strerror(-rc));
        free(fb);
        return NULL;
    }
    gbm_bo_set_user_data(bo, fb, drm_fb_destroy_callback);
    return fb;
}
