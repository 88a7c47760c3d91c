/* Whether the display is there: a connector unplugged (or switched off: the kernel's forced
 * connector state, /sys/class/drm/card0-NAME/status) pauses scan-out, and plugging it back in
 * resumes it with a new modeset. The DRM display asks the connector's current state (no probe:
 * drm_device_connector_connected) at most once per check interval; this file is the decision,
 * pure logic, so tests/platform/test_display_link.c drives it with made-up states.
 *
 *   link_check_due   true when the interval since the last check has passed
 *   link_update      the state seen now -> what to do: nothing, pause (log once), resume (log
 *                    once, set the mode again) */
#ifndef SBFX_DISPLAY_LINK_H
#define SBFX_DISPLAY_LINK_H

#include <stdbool.h>
#include <stdint.h>

#define LINK_CHECK_INTERVAL_NS INT64_C(1000000000)
#define LINK_PAUSED_FRAME_NS INT64_C(100000000) /* the loop's pace while paused (10 Hz) */

enum link_action { LINK_NONE, LINK_PAUSE, LINK_RESUME };

struct display_link {
    bool disconnected;
    int64_t next_check_ns;
    uint64_t unplugs, replugs, checks;
};

bool link_check_due(struct display_link *l, int64_t now_ns);
enum link_action link_update(struct display_link *l, bool connected);

#endif
