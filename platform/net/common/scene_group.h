/* What the protocols' scene groups (net/dis/dis_config.c, net/cigi/cigi_config.c) read alike with
 * libconfig: the scene file opened, an error that names the file, the line and the key, the keys a
 * group may have, a finite number, and the scene's geodetic origin, dis.origin, which DIS and CIGI
 * both place through. */
#ifndef SBFX_SCENE_GROUP_H
#define SBFX_SCENE_GROUP_H

#include <libconfig.h>
#include <stdbool.h>
#include <stddef.h>

/* The scene file being read and where its first error goes. */
struct scene_reader {
    const char *path;
    char *err;
    size_t n;
};

/* config_init()s cfg and reads path into it: 0, or -ENOENT (cannot be read) / -EINVAL (bad
 * syntax) with "FILE:LINE: what" in err. The caller config_destroy()s cfg either way. */
int scene_group_load(config_t *cfg, const char *path, char *err, size_t n);

/* "FILE:LINE: what" at setting s (the scene's path and line 0 without one) into r's err;
 * returns -EINVAL. */
int scene_group_fail(struct scene_reader *r, const config_setting_t *s, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* g must be a group whose keys are all in keys (NULL-terminated); where names g in the error
 * ("dis", "a cigi.effects entry"). 0, or -EINVAL with the error. */
int scene_group_check_keys(struct scene_reader *r, const config_setting_t *g, const char *where,
                           const char *const *keys);

/* Whether s is an int or float setting with a finite value, in *v. */
bool scene_group_number(const config_setting_t *s, double *v);

/* dis.origin = [latitude, longitude, height] (degrees, degrees, metres) of the dis group dis (NULL,
 * or not a group: none), into origin and *have_origin when there; the rest of the dis group is
 * net/dis/dis_config.c's. 0, or -EINVAL with the error. */
int scene_group_read_origin(struct scene_reader *r, const config_setting_t *dis, double origin[3],
                            bool *have_origin);

#endif
