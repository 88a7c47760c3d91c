/* The scene file's cigi group (docs/cigi.md), read by the player with libconfig; the module
 * accepts the group and leaves it alone (src/ knows nothing of CIGI):
 *
 *   cigi = {
 *     effects = (                               # the host's entity types that are effects
 *       { entity_type = 1001; effect = "explosion"; },
 *       { entity_type = 1002; effect = "smoke"; }
 *     );
 *   };
 *
 * An Entity Control's latitude, longitude and altitude are placed through the scene's geodetic
 * origin, dis.origin (read here too: dis = { origin = [lat, lon, height]; ... }). An entity type
 * named twice, or an effect the scene does not have (check_effect), is an error that names the
 * file, the line and the key. */
#ifndef SBFX_CIGI_CONFIG_H
#define SBFX_CIGI_CONFIG_H

#include <stdbool.h>
#include <stddef.h>

#include "net/cigi/cigi_receiver.h"

/* Whether the scene has an effect of that name: 0, or nonzero with why ("the scene has no effect
 * of that name (its effects: ...)"). */
typedef int (*cigi_effect_check_fn)(const char *name, char *why, size_t n, void *user);

/* Fills s's effects (and origin, when the scene has dis.origin) from the scene file, leaving the
 * rest of s alone; *found: whether the file has a cigi group. check: NULL to take any name.
 * 0, or -EINVAL / -ENOENT with err. */
int cigi_config_read(const char *scene_path, struct cigi_settings *s, bool *found, cigi_effect_check_fn check,
                     void *user, char *err, size_t n);

#endif
