/* What a board profile or the command line asks of a DRM display: a mode "WxH" or "WxH@HZ" and
 * how to set it. The vocabulary the player's options and the DRM display share, here below both
 * (the options room parses it, drm_device.c and display_drm.c act on it). No libdrm. */
#ifndef SBFX_DRM_MODE_SPEC_H
#define SBFX_DRM_MODE_SPEC_H

enum modeset_kind { MODESET_AUTO, MODESET_ATOMIC, MODESET_LEGACY };

/* "WxH" or "WxH@HZ" (a mode name); refresh 0 when not given. 0 or -EINVAL. */
int mode_spec_parse(const char *text, int *width, int *height, int *refresh);

#endif
