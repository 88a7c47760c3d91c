/* sbfx-play's authoring loop: --watch reloads the scene when its file or a file it @includes
 * changes (inputs/watch.c watches them), SIGHUP reloads it (inputs/signals.c), --loop replays its
 * timeline. The new scene replaces the old one in the live module (sbfx_set_scene) between two
 * frames; an author's mistake is logged and the old scene plays on. */
#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>

#include "player/player.h"

/* --watch: the scene file and the files it @includes (NULL scene: the file alone); nothing
 * without --watch or a scene file. */
int player_watch_files(struct player *p, const sbfx_scene *scene, char *err, size_t n)
{
    if (!p->opt->watch || !p->opt->scene_path) return 0;
    return scene_watch_files(&p->watch, p->opt->scene_path, scene, err, n);
}

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
    /* identified ones (world.c) start again at their own times: the new module drops the particles */
    memset(p->world.cli_fired, 0, sizeof(p->world.cli_fired));
    memset(p->world.timeline_fired, 0, sizeof(p->world.timeline_fired));
    for (int i = 0; i < p->opt->trigger_count; i++) {
        const struct player_trigger *t = &p->opt->triggers[i];
        if (world_trigger_identified(p, t)) continue;
        if (sbfx_schedule(p->fx, t->effect, now + t->seconds, t->position) != SBFX_OK)
            fprintf(stderr, "sbfx-play: --trigger %s@%g: %s\n", t->effect, t->seconds, sbfx_last_error(p->fx));
    }
    p->timeline_start = p->sim_time;
}

/* The scene's detail clip again (the new module's volume starts procedural). */
static void reopen_clip(struct player *p)
{
    char err[512];
    if (detail_open_clip(p->fx, player_log, p, err, sizeof(err)) != 0)
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
    /* --early-termination over the scene's render.early_termination, as at create */
    if (p->opt->early_termination) sbfx_set_early_termination(p->fx, p->opt->early_termination > 0);
    sbfx_scene_camera_get(scene, &p->camera); /* the same orbit on the same clock, unless edited */
    if (p->world.on) world_take_timeline(p, scene); /* started again at world times, drawn at their age */
    player_keep_scene(p, scene);
    if (p->opt->early_termination) sbfx_set_early_termination(p->fx, p->opt->early_termination > 0);
    schedule_triggers_again(p);
    reopen_clip(p);
    trigger_sources_reload(&p->triggers, p->fx); /* the dis group's placement and effects */
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
    bool hup = player_hup_taken();
    bool changed = scene_watch_due(&p->watch, player_now_ns());
    if ((hup || changed) && p->opt->scene_path) {
        /* read before the load: an edit during it is a change still to come */
        uint64_t content = scene_watch_content(&p->watch);
        if (!hup && content == p->watch.read_content) return 0; /* events, no edit: nothing to do */
        p->watch.read_content = content;
        return reload_scene(p) ? PLAYER_RELOADED : 0;
    }
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
        int timeout = scene_watch_timeout_ms(&p->watch, player_now_ns());
        if (poll(&fd, 1, timeout) < 0 && errno != EINTR) {
            int rc = -errno;
            snprintf(err, n, "--watch: poll: %s", strerror(errno));
            return rc;
        }
    }
    return 0;
}
