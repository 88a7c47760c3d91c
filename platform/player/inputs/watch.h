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
    char path[SCENE_WATCH_FILES][PATH_MAX];  /* the file (its name: what the folder's events name) */
    int64_t first_ns, last_ns;               /* the pending change's first and last event (0: none) */
    uint64_t read_content;                   /* their content when last read (0: not yet) */
};

#define SCENE_WATCH_SETTLE_NS INT64_C(150000000) /* quiet after the last event: one reload per save */
#define SCENE_WATCH_MAX_NS INT64_C(1000000000)   /* a writer that never stops still reloads each second */

/* Watches the file at path and the files of `scene` it @included (none when scene is NULL);
 * opens inotify on the first call. */
int scene_watch_files(struct scene_watch *w, const char *path, const sbfx_scene *scene, char *err, size_t n);
void scene_watch_close(struct scene_watch *w);
/* Reads the events that wait (never blocks); true when a change has settled (then cleared). */
bool scene_watch_due(struct scene_watch *w, int64_t now_ns);
/* A hash of the watched files' bytes now (a missing or unreadable file counts as such): a settled
 * change whose content equals the last one read changed nothing (a late close or a touch under
 * load, long after the write) and needs no reload. */
uint64_t scene_watch_content(const struct scene_watch *w);
/* Milliseconds until a pending change settles; -1 when none is pending. */
int scene_watch_timeout_ms(const struct scene_watch *w, int64_t now_ns);

#endif
