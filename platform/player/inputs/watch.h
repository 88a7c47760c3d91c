/* The scene's files, watched for --watch (inputs.h; the reload itself is the authoring loop's,
 * authoring.c): inotify on the folders that hold the scene file and the files it @includes (an
 * editor that writes a new file and renames it over the old one replaces the inode: a watch on
 * the file itself would be lost), the events filtered by name. A change is due once no event
 * came for the settling time. */
#ifndef SBFX_PLAYER_WATCH_H
#define SBFX_PLAYER_WATCH_H

#include <limits.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sbfx.h"

#define SCENE_WATCH_FILES 16

struct scene_watch {
    int fd;                                  /* -1: not watching */
    int count;
    int wd[SCENE_WATCH_FILES];               /* the folder's watch */
    char name[SCENE_WATCH_FILES][NAME_MAX + 1]; /* the file's name in it */
    int64_t first_ns, last_ns;               /* the pending change's first and last event (0: none) */
};

#define SCENE_WATCH_SETTLE_NS INT64_C(150000000) /* quiet after the last event: one reload per save */
#define SCENE_WATCH_MAX_NS INT64_C(1000000000)   /* a writer that never stops still reloads each second */

/* Watches the file at path and the files of `scene` it @included (none when scene is NULL);
 * opens inotify on the first call. */
int scene_watch_files(struct scene_watch *w, const char *path, const sbfx_scene *scene, char *err, size_t n);
void scene_watch_close(struct scene_watch *w);
/* Reads the events that wait (never blocks); true when a change has settled (then cleared). */
bool scene_watch_due(struct scene_watch *w, int64_t now_ns);
/* Milliseconds until a pending change settles; -1 when none is pending. */
int scene_watch_timeout_ms(const struct scene_watch *w, int64_t now_ns);

#endif
