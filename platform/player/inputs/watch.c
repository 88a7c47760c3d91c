/* sbfx-play's authoring loop: --watch, SIGHUP and --loop (player_watch.h).
 *
 * Editors save in different ways: in place (open with O_TRUNC, one or several writes, close), by
 * writing a new file and renaming it over the old one, or by moving the old one aside first.
 * Watching the folders and filtering by name sees all of them (a rename brings IN_MOVED_TO, an
 * in-place write IN_MODIFY and IN_CLOSE_WRITE); whatever the events, the reload waits until none
 * came for PLAYER_WATCH_SETTLE_NS, so one save gives one reload, after its last write. */
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/inotify.h>
#include <unistd.h>

#include "player/player.h"

#define WATCH_EVENTS (IN_CLOSE_WRITE | IN_MODIFY | IN_MOVED_TO | IN_CREATE | IN_DELETE | IN_MOVED_FROM | IN_ATTRIB)

static volatile sig_atomic_t hup_signal;

static void on_hup(int sig)
{
    (void)sig;
    hup_signal = 1;
}

/* No SA_RESTART: a headless run waiting for a change wakes at once. */
void player_catch_hup(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_hup;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGHUP, &sa, NULL);
}

static bool hup_taken(void)
{
    if (!hup_signal) return false;
    hup_signal = 0;
    return true;
}

/* ---- the watch ------------------------------------------------------------------------ */

/* "dir/name" -> watch "dir" (or "." for a bare name), remember "name". */
static int add_file(struct player_watch *w, const char *path, char *err, size_t n)
{
    char dir[PATH_MAX];
    const char *slash = strrchr(path, '/');
    const char *name = slash ? slash + 1 : path;
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
    snprintf(w->name[w->count], sizeof(w->name[0]), "%s", name);
    w->count++;
    return 0;
}

/* Watches are per folder (inotify gives the same one for a folder added twice): removing them
 * all and adding the new list keeps it simple; nothing is lost, the pending change stays. */
static void forget_all(struct player_watch *w)
{
    for (int i = 0; i < w->count; i++) inotify_rm_watch(w->fd, w->wd[i]); /* EINVAL for a repeat: harmless */
    w->count = 0;
}

int player_watch_files(struct player *p, const sbfx_scene *scene, char *err, size_t n)
{
    struct player_watch *w = &p->watch;
    if (!p->opt->watch || !p->opt->scene_path) return 0;
    if (w->fd < 0 && (w->fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC)) < 0) {
        int rc = -errno;
        snprintf(err, n, "--watch: inotify_init1: %s (fs.inotify.max_user_instances?)", strerror(errno));
        return rc;
    }
    forget_all(w);
    int rc = add_file(w, p->opt->scene_path, err, n);
    for (int i = 1; rc == 0 && sbfx_scene_file(scene, i) && w->count < PLAYER_WATCH_FILES; i++)
        rc = add_file(w, sbfx_scene_file(scene, i), err, n);
    return rc;
}

void player_watch_close(struct player *p)
{
    if (p->watch.fd >= 0) close(p->watch.fd);
    p->watch.fd = -1;
    p->watch.count = 0;
}

static bool watched(const struct player_watch *w, const struct inotify_event *e)
{
    if (e->mask & IN_Q_OVERFLOW) return true; /* events were lost: one of them may have been ours */
    for (int i = 0; i < w->count; i++)
        if (w->wd[i] == e->wd && e->len && strcmp(w->name[i], e->name) == 0) return true;
    return false;
}

static void read_events(struct player_watch *w, int64_t now_ns)
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

static int64_t due_at(const struct player_watch *w)
{
    int64_t settled = w->last_ns + PLAYER_WATCH_SETTLE_NS, bound = w->first_ns + PLAYER_WATCH_MAX_NS;
    return settled < bound ? settled : bound;
}

bool player_watch_due(struct player_watch *w, int64_t now_ns)
{
    if (w->fd < 0) return false;
    read_events(w, now_ns);
    if (!w->first_ns || now_ns < due_at(w)) return false;
    w->first_ns = w->last_ns = 0;
    return true;
}

int player_watch_timeout_ms(const struct player_watch *w, int64_t now_ns)
{
    if (w->fd < 0 || !w->first_ns) return -1;
    int64_t left = due_at(w) - now_ns;
    return left > 0 ? (int)(left / 1000000) + 1 : 0;
}

/* ---- reloading ------------------------------------------------------------------------ */

void player_keep_scene(struct player *p, sbfx_scene *scene)
{
    if (scene == p->scene_kept) return;
    sbfx_scene_free(p->scene_kept);
    p->scene_kept = NULL;
    if (p->opt->loop_seconds > 0) p->scene_kept = scene; /* what --loop replays */
    else sbfx_scene_free(scene);
}

/* The timeline starts again: --trigger entries too, counted from now. */
static void schedule_triggers_again(struct player *p)
{
    double now = sbfx_elapsed(p->fx);
    for (int i = 0; i < p->opt->trigger_count; i++) {
        const struct player_trigger *t = &p->opt->triggers[i];
        if (sbfx_schedule(p->fx, t->effect, now + t->seconds, t->position) != SBFX_OK)
            fprintf(stderr, "sbfx-play: --trigger %s@%g: %s\n", t->effect, t->seconds, sbfx_last_error(p->fx));
    }
    p->timeline_start = p->sim_time;
}

/* The scene's detail clip again (the new module's volume starts procedural). */
static void reopen_clip(struct player *p)
{
    char err[512];
    if (player_open_clip(p, err, sizeof(err)) != 0)
        fprintf(stderr, "sbfx-play: %s (procedural detail instead)\n", err);
}

static double ms_since(int64_t start_ns)
{
    return (double)(player_now_ns() - start_ns) / 1e6;
}

/* Reads the scene file again and hands it to the module. 1: it took over; 0: refused, logged. */
static int reload_scene(struct player *p)
{
    const char *path = p->opt->scene_path;
    int64_t start = player_now_ns();
    char why[1024];
    sbfx_scene *scene = NULL;
    if (sbfx_scene_load(path, &scene, why, sizeof(why)) != SBFX_OK) {
        fprintf(stderr, "sbfx-play: scene not reloaded: %s (the previous scene plays on)\n", why);
        return 0;
    }
    if (player_watch_files(p, scene, why, sizeof(why)) != 0) fprintf(stderr, "sbfx-play: %s\n", why);
    sbfx_counters before, after;
    sbfx_stats(p->fx, &before);
    sbfx_result r = sbfx_set_scene(p->fx, scene);
    if (r != SBFX_OK) {
        fprintf(stderr, "sbfx-play: scene not reloaded: %s: %s: %s (the previous scene plays on)\n", path,
                sbfx_result_string(r), sbfx_last_error(p->fx));
        sbfx_scene_free(scene);
        return 0;
    }
    sbfx_scene_camera_get(scene, &p->camera); /* the same orbit on the same clock, unless edited */
    player_keep_scene(p, scene);
    schedule_triggers_again(p);
    reopen_clip(p);
    fprintf(stderr, "sbfx-play: scene reloaded: %s (%.0f ms)\n", path, ms_since(start));
    sbfx_stats(p->fx, &after);
    if (!p->opt->quiet) /* what the edit cost: nothing for a change of numbers */
        printf("sbfx-play: the new scene compiled %d shader programs and made %d targets\n",
               after.programs_compiled - before.programs_compiled, after.targets_created - before.targets_created);
    fflush(stdout);
    return 1;
}

/* --loop and SIGHUP without a scene file: the kept scene again (NULL: the built-in explosion),
 * the timeline from now. Nothing changed, so nothing is compiled or made (sbfx_set_scene). */
static int replay(struct player *p)
{
    sbfx_result r = sbfx_set_scene(p->fx, p->scene_kept);
    if (r != SBFX_OK) {
        fprintf(stderr, "sbfx-play: replaying the timeline: %s: %s\n", sbfx_result_string(r), sbfx_last_error(p->fx));
        p->timeline_start = p->sim_time; /* tried again a period later */
        return 0;
    }
    schedule_triggers_again(p);
    reopen_clip(p);
    if (!p->opt->quiet) printf("sbfx-play: timeline replayed at %.3f s\n", p->sim_time);
    return PLAYER_REPLAYED;
}

int player_watch_service(struct player *p)
{
    bool hup = hup_taken();
    bool changed = player_watch_due(&p->watch, player_now_ns());
    if ((hup || changed) && p->opt->scene_path) return reload_scene(p) ? PLAYER_RELOADED : 0;
    if (hup) { /* the built-in explosion: nothing to read */
        fprintf(stderr, "sbfx-play: SIGHUP: no --scene file to reload: the timeline starts again\n");
        return replay(p);
    }
    double loop = p->opt->loop_seconds;
    /* the player's clock (frame i at i/F exactly, or the wall clock), not the module's, which
     * counts whole steps and may be most of one behind it */
    if (loop > 0 && p->sim_time - p->timeline_start >= loop) return replay(p);
    return 0;
}

int player_watch_wait(struct player *p, char *err, size_t n)
{
    while (!player_stop_requested()) {
        if (player_watch_service(p) == PLAYER_RELOADED) return 1;
        struct pollfd fd = {.fd = p->watch.fd, .events = POLLIN};
        int timeout = player_watch_timeout_ms(&p->watch, player_now_ns());
        if (poll(&fd, 1, timeout) < 0 && errno != EINTR) {
            int rc = -errno;
            snprintf(err, n, "--watch: poll: %s", strerror(errno));
            return rc;
        }
    }
    return 0;
}
