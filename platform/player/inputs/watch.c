/* The scene's files, watched for --watch (watch.h).
 *
 * Editors save in different ways: in place (open with O_TRUNC, one or several writes, close), by
 * writing a new file and renaming it over the old one, or by moving the old one aside first.
 * Watching the folders and filtering by name sees all of them (a rename brings IN_MOVED_TO, an
 * in-place write IN_MODIFY and IN_CLOSE_WRITE); whatever the events, the reload waits until none
 * came for SCENE_WATCH_SETTLE_NS, so one save gives one reload, after its last write. */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/inotify.h>
#include <unistd.h>

#include "player/inputs/watch.h"

#define WATCH_EVENTS (IN_CLOSE_WRITE | IN_MODIFY | IN_MOVED_TO | IN_CREATE | IN_DELETE | IN_MOVED_FROM | IN_ATTRIB)

/* ---- the watch ------------------------------------------------------------------------ */

/* The file's name in its folder: what an event names. */
static const char *file_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

/* "dir/name" -> watch "dir" (or "." for a bare name), remember the path. */
static int add_file(struct scene_watch *w, const char *path, char *err, size_t n)
{
    char dir[PATH_MAX];
    const char *slash = strrchr(path, '/');
    const char *name = file_name(path);
    if (!*name || strlen(name) > NAME_MAX || strlen(path) >= sizeof(dir)) {
        snprintf(err, n, "--watch: %s: not a file name that can be watched", path);
        return -EINVAL;
    }
    if (!slash) snprintf(dir, sizeof(dir), ".");
    else if (slash == path) snprintf(dir, sizeof(dir), "/");
    else snprintf(dir, sizeof(dir), "%.*s", (int)(slash - path), path);
    int wd = inotify_add_watch(w->fd, dir, WATCH_EVENTS);
    if (wd < 0) {
        int rc = -errno;
        snprintf(err, n, "--watch: cannot watch the folder %s of %s: %s", dir, path, strerror(errno));
        return rc;
    }
    w->wd[w->count] = wd;
    snprintf(w->path[w->count], sizeof(w->path[0]), "%s", path);
    w->count++;
    return 0;
}

/* Watches are per folder (inotify gives the same one for a folder added twice): removing them
 * all and adding the new list keeps it simple; nothing is lost, the pending change stays. */
static void forget_all(struct scene_watch *w)
{
    for (int i = 0; i < w->count; i++) inotify_rm_watch(w->fd, w->wd[i]); /* EINVAL for a repeat: harmless */
    w->count = 0;
}

int scene_watch_files(struct scene_watch *w, const char *path, const sbfx_scene *scene, char *err, size_t n)
{
    if (w->fd < 0 && (w->fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC)) < 0) {
        int rc = -errno;
        snprintf(err, n, "--watch: inotify_init1: %s (fs.inotify.max_user_instances?)", strerror(errno));
        return rc;
    }
    forget_all(w);
    int rc = add_file(w, path, err, n);
    for (int i = 1; rc == 0 && sbfx_scene_file(scene, i) && w->count < SCENE_WATCH_FILES; i++)
        rc = add_file(w, sbfx_scene_file(scene, i), err, n);
    return rc;
}

void scene_watch_close(struct scene_watch *w)
{
    if (w->fd >= 0) close(w->fd);
    w->fd = -1;
    w->count = 0;
}

/* ---- the files' content ----------------------------------------------------------------- */

/* FNV-1a, 64 bits: enough to tell an edit from no edit (the library's own, base/hash.h, is not
 * in its public header, the one the player builds on). */
static uint64_t fnv1a(uint64_t h, const void *data, size_t size)
{
    const unsigned char *b = data;
    for (size_t i = 0; i < size; i++) h = (h ^ b[i]) * UINT64_C(0x100000001b3);
    return h;
}

uint64_t scene_watch_content(const struct scene_watch *w)
{
    uint64_t h = UINT64_C(0xcbf29ce484222325);
    char buf[4096];
    for (int i = 0; i < w->count; i++) {
        h = fnv1a(h, w->path[i], strlen(w->path[i]) + 1);
        FILE *f = fopen(w->path[i], "rb");
        if (!f) {
            h = fnv1a(h, "missing", 8);
            continue;
        }
        size_t got;
        while ((got = fread(buf, 1, sizeof(buf), f)) > 0) h = fnv1a(h, buf, got);
        if (ferror(f)) h = fnv1a(h, "unreadable", 11);
        fclose(f);
    }
    return h ? h : 1; /* 0 means "not read yet" */
}

static bool watched(const struct scene_watch *w, const struct inotify_event *e)
{
    if (e->mask & IN_Q_OVERFLOW) return true; /* events were lost: one of them may have been ours */
    for (int i = 0; i < w->count; i++)
        if (w->wd[i] == e->wd && e->len && strcmp(file_name(w->path[i]), e->name) == 0) return true;
    return false;
}

static void read_events(struct scene_watch *w, int64_t now_ns)
{
    char buf[4096] __attribute__((aligned(__alignof__(struct inotify_event))));
    for (;;) {
        ssize_t len = read(w->fd, buf, sizeof(buf));
        if (len <= 0) return; /* EAGAIN: none left */
        for (char *at = buf; at < buf + len;) {
            const struct inotify_event *e = (const struct inotify_event *)at;
            if (watched(w, e)) {
                if (!w->first_ns) w->first_ns = now_ns;
                w->last_ns = now_ns;
            }
            at += sizeof(*e) + e->len;
        }
    }
}

static int64_t due_at(const struct scene_watch *w)
{
    int64_t settled = w->last_ns + SCENE_WATCH_SETTLE_NS, bound = w->first_ns + SCENE_WATCH_MAX_NS;
    return settled < bound ? settled : bound;
}

bool scene_watch_due(struct scene_watch *w, int64_t now_ns)
{
    if (w->fd < 0) return false;
    read_events(w, now_ns);
    if (!w->first_ns || now_ns < due_at(w)) return false;
    w->first_ns = w->last_ns = 0;
    return true;
}

int scene_watch_timeout_ms(const struct scene_watch *w, int64_t now_ns)
{
    if (w->fd < 0 || !w->first_ns) return -1;
    int64_t left = due_at(w) - now_ns;
    return left > 0 ? (int)(left / 1000000) + 1 : 0;
}
