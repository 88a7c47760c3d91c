/* sbfx-play's authoring loop (player_watch.c): --watch reloads the scene when its file or a file
 * it @includes changes, SIGHUP reloads it, --loop replays its timeline. The new scene replaces the
 * old one in the live module (sbfx_set_scene) between two frames. */
#ifndef SBFX_PLAYER_WATCH_H
#define SBFX_PLAYER_WATCH_H

#include <limits.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sbfx.h"

#define PLAYER_WATCH_FILES 16

/* inotify on the folders that hold the scene's files (an editor that writes a new file and
 * renames it over the old one replaces the inode: a watch on the file itself would be lost),
 * the events filtered by name. A change is due once no event came for the settling time. */
struct player_watch {
    int fd;                                  /* -1: not watching */
    int count;
    int wd[PLAYER_WATCH_FILES];              /* the folder's watch */
    char name[PLAYER_WATCH_FILES][NAME_MAX + 1]; /* the file's name in it */
    int64_t first_ns, last_ns;               /* the pending change's first and last event (0: none) */
};

#define PLAYER_WATCH_SETTLE_NS INT64_C(150000000) /* quiet after the last event: one reload per save */
#define PLAYER_WATCH_MAX_NS INT64_C(1000000000)   /* a writer that never stops still reloads each second */

struct player;

/* Watches the files of `scene` (the scene file itself when it is NULL); keeps the old list when a
 * folder cannot be watched (logged). Opens inotify on the first call. */
int player_watch_files(struct player *p, const sbfx_scene *scene, char *err, size_t n);
void player_watch_close(struct player *p);
/* Reads the events that wait (never blocks); true when a change has settled (then cleared). */
bool player_watch_due(struct player_watch *w, int64_t now_ns);
/* Milliseconds until a pending change settles; -1 when none is pending. */
int player_watch_timeout_ms(const struct player_watch *w, int64_t now_ns);

/* SIGHUP asks for a reload (a kiosk's `systemctl reload`). */
void player_catch_hup(void);

/* Between two frames: a SIGHUP, a settled change or --loop's period. Returns PLAYER_RELOADED when
 * a new scene took over, PLAYER_REPLAYED when --loop started the timeline again, 0 when nothing
 * did (a refused edit is logged, and the old scene goes on); never an error: an author's
 * mistake does not stop the player. */
enum { PLAYER_RELOADED = 1, PLAYER_REPLAYED = 2 };
int player_watch_service(struct player *p);
/* Headless --watch after a take: waits for a reload (1) or a stop signal (0). */
int player_watch_wait(struct player *p, char *err, size_t n);
/* Keeps the scene (for --loop and the watch list) or frees it. */
void player_keep_scene(struct player *p, sbfx_scene *scene);

#endif
