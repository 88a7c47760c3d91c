/* Reading back what the CRTC scans out through a writeback connector (vkms has one; some SoC
 * display controllers too): one atomic commit routes the CRTC's output into a dumb buffer, its
 * out-fence says when the frame is written, the buffer is saved as a PNG. Atomic only.
 * Returns 0 or -errno with a message: -ENOTSUP when the device has no usable writeback
 * connector for the CRTC. */
#ifndef SBFX_DRM_WRITEBACK_H
#define SBFX_DRM_WRITEBACK_H

#include <stddef.h>

#include "drm/drm_device.h"

int drm_writeback_capture(struct drm_device *d, const char *png_path, char *err, size_t n);

#endif
