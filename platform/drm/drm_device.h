/* DRM/KMS device discovery (kmscube's drm-common): the card, a connected connector, a mode, a
 * CRTC that can drive it and its primary plane; what the CRTC showed before, to put it back.
 *
 * Choices: the card from the caller (board profile or --device) or the first /dev/dri/cardN
 * with a connected display; the connector by name ("HDMI-A-1", "DSI-1", "Virtual-1": type name
 * and index, as the kernel and modetest write them) or the first connected one; the mode by
 * name ("1920x1080", "1920x1080@60") or the connector's preferred mode (else its first).
 * Becoming DRM master is checked: a display server holding the card is a clear error, not a
 * mysterious EACCES at the first modeset.
 *
 * Errors: 0 or a negative errno with a message naming the device and what to do. */
#ifndef SBFX_DRM_DEVICE_H
#define SBFX_DRM_DEVICE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#define DRM_DEVICE_MAX_CARDS 16

/* Property ids an atomic commit needs, looked up once (drm_atomic.c). */
struct drm_atomic_props {
    uint32_t conn_crtc_id;
    uint32_t crtc_mode_id, crtc_active;
    uint32_t plane_fb_id, plane_crtc_id;
    uint32_t plane_src_x, plane_src_y, plane_src_w, plane_src_h;
    uint32_t plane_crtc_x, plane_crtc_y, plane_crtc_w, plane_crtc_h;
    uint32_t mode_blob;     /* the chosen mode as a property blob */
};

struct drm_device {
    int fd;
    char path[64];
    char driver[32];
    char connector_name[32];
    uint32_t connector_id, crtc_id, plane_id;
    int crtc_index;
    drmModeModeInfo mode;
    drmModeCrtc *saved_crtc;    /* the CRTC before us, restored by drm_device_restore */
    bool atomic;                /* DRM_CLIENT_CAP_ATOMIC is on */
    struct drm_atomic_props props;
};

struct drm_device_desc {
    const char *path;
    const char *connector;
    const char *mode;
};

int drm_device_open(struct drm_device *d, const struct drm_device_desc *desc, char *err, size_t n);
/* Puts the CRTC back as drm_device_open found it (its mode and framebuffer, or off). */
int drm_device_restore(struct drm_device *d, char *err, size_t n);
void drm_device_close(struct drm_device *d);
/* The connector's current state, without probing it (what the kernel last saw: a hotplug, or a
 * state forced through sysfs); one ioctl on stack buffers, nothing allocated. 1 connected,
 * 0 not, or a negative errno. */
int drm_device_connector_connected(const struct drm_device *d);
/* Vertical refresh of a mode in Hz. */
double drm_mode_refresh(const drmModeModeInfo *mode);

#endif
