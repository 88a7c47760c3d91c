/* The scene file's dis group (docs/triggers.md), read by the player with libconfig; the module
 * accepts the group and leaves it alone (src/ knows nothing of DIS):
 *
 *   dis = {
 *     origin = [48.1372, 11.5756, 520.0];   # latitude, longitude (degrees), height (m, WGS-84):
 *                                           # the scene's (0, 0, 0); x east, y up, z south
 *     range = 20000.0;                      # metres from the origin; farther is ignored (20 km)
 *     exercise = 1;                         # only this exercise ID (1..255; default: any)
 *     effects = (                           # the first rule that matches wins
 *       { munition = "2.9.*.2.*.*.*"; result = 5; effect = "explosion"; },
 *       { munition = "*"; effect = "smoke"; }
 *     );
 *     default = "explosion";                # when no rule matches (none: ignored)
 *   };
 *
 * Errors name the file, the line and the key. */
#ifndef SBFX_DIS_CONFIG_H
#define SBFX_DIS_CONFIG_H

#include <stdbool.h>
#include <stddef.h>

#include "net/dis/dis_receiver.h"

/* Fills s's origin, range, exercise and effects from the scene file's dis group, leaving the
 * rest of s alone; *found: whether the file has one. 0, or -EINVAL / -ENOENT with err. */
int dis_config_read(const char *scene_path, struct dis_settings *s, bool *found, char *err, size_t n);

#endif
