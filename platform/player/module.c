/* The player's module: sbfx made from the scene file and the options (again after a GPU reset,
 * reset.c), its triggers scheduled, and advanced to the player's time. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "gpio/effect_names.h"
#include "player/player.h"

static void on_sbfx_log(sbfx_log_level level, const char *message, void *user)
{
    const struct player_options *opt = user;
    static const char *const prefix[] = {"error", "warning", "info"};
    if (level == SBFX_LOG_INFO && opt->quiet) return;
    const char *name = (unsigned)level <= SBFX_LOG_INFO ? prefix[level] : "?";
    fprintf(stderr, "sbfx: %s: %s\n", name, message);
}

/* --trigger entries go to the module's schedule: each fires at the first simulation step at
 * or after its time, so a run does not depend on --fps. The default timeline (one explosion at
 * t=0 at the origin) is the scene's own; --no-timeline turns it off (desc.ignore_timeline). */
static int schedule_triggers(struct player *p, char *err, size_t n)
{
    const struct player_options *opt = p->opt;
    for (int i = 0; i < opt->trigger_count; i++) {
        const struct player_trigger *t = &opt->triggers[i];
        if (world_trigger_identified(p, t)) continue; /* started at its time by world_fire_due */
        double at = t->seconds;
        if (p->recovering) { /* a new module after a GPU reset: its time 0 is the player's now */
            if (at <= p->fx_time_lost) continue; /* fired before the reset */
            at = at > p->sim_time ? at - p->sim_time : 0.0;
        }
        sbfx_result r = sbfx_schedule(p->fx, t->effect, at, t->position);
        if (r != SBFX_OK) {
            char names[256] = "";
            if (r == SBFX_ERR_UNKNOWN_EFFECT) effect_names(p->fx, names, sizeof(names));
            snprintf(err, n, "--trigger %s@%g: %s: %s%s%s%s", t->effect, t->seconds,
                     sbfx_result_string(r), sbfx_last_error(p->fx), names[0] ? " (the scene's effects: " : "",
                     names, names[0] ? ")" : "");
            return -EINVAL;
        }
    }
    return 0;
}

static int load_scene(const char *path, sbfx_scene **scene, char *err, size_t n)
{
    *scene = NULL;
    if (!path) return 0; /* the library's built-in explosion */
    char why[512];
    if (sbfx_scene_load(path, scene, why, sizeof(why)) != SBFX_OK) {
        snprintf(err, n, "--scene %s", why);
        return -EINVAL;
    }
    return 0;
}

int player_parse_scene(struct player *p, char *err, size_t n)
{
    return load_scene(p->opt->scene_path, &p->scene_first, err, n);
}

int player_create_fx(struct player *p, char *err, size_t n)
{
    const struct player_options *opt = p->opt;
    sbfx_scene *scene = p->scene_first;
    p->scene_first = NULL;
    int rc = scene ? 0 : load_scene(opt->scene_path, &scene, err, n);
    if (rc == 0 && !p->recovering) rc = gpio_source_add_scene(&p->gpio, scene, &p->board, err, n);
    sbfx_scene_camera_get(scene, &p->camera); /* the default orbit without a camera group */
    sbfx_scene_host_get(scene, &p->host);     /* the test scene's fixed daylight without `sky` */
    if (rc) {
        sbfx_scene_free(scene);
        return rc;
    }
    const sbfx_desc desc = {
        .target_divisor = opt->scale ? opt->scale : p->board.target_scale,
        .target_format = opt->format,
        .upsample = opt->upsample,
        .opacity = opt->opacity,
        .tone_map = opt->tone_map,
        .exposure = opt->exposure,
        .seed = opt->seed,
        .start_time = p->recovering ? p->fx_clock_lost : p->world.on ? p->world.base : opt->start_time,
        .frame_budget_ms = opt->budget_ms,
        .max_particles = p->board.max_particles,
        .scene = scene,
        /* not replayed after a reset; in world mode the player starts it at world times */
        .ignore_timeline = opt->no_timeline || p->recovering || p->world.on,
        .log = on_sbfx_log,
        .log_user = (void *)opt,
    };
    if (p->world.on) world_take_timeline(p, scene);
    /* identified triggers start again in a new module (after a GPU reset: at their age) */
    memset(p->world.cli_fired, 0, sizeof(p->world.cli_fired));
    if (p->world.on && !p->recovering) p->sim_time = p->world.base;
    sbfx_result r = sbfx_create(&desc, &p->fx);
    rc = r == SBFX_OK ? player_watch_files(p, scene, err, n) : 0; /* --watch: the file and its includes */
    player_keep_scene(p, scene); /* the module keeps what it needs; --loop replays the scene */
    if (r != SBFX_OK) { /* the reason went through the log callback */
        snprintf(err, n, "sbfx_create failed: %s", sbfx_result_string(r));
        return -EIO;
    }
    if (opt->early_termination && sbfx_set_early_termination(p->fx, opt->early_termination > 0) != SBFX_OK) {
        snprintf(err, n, "--early-termination: %s", sbfx_last_error(p->fx));
        return -EIO;
    }
    if (rc) return rc;
    trigger_sources_listen(&p->triggers, p->fx); /* the trigger log hears of the timeline and --trigger too */
    p->timeline_start = p->sim_time; /* --loop counts from here */
    p->fx_created_at = p->recovering ? p->sim_time : 0.0;
    return schedule_triggers(p, err, n);
}

#define UPDATE_MAX 0.25 /* s: what sbfx_update takes at a time (more is cut there) */
#define CATCH_UP_MAX 600.0 /* s a frame: a world clock that jumps further is followed over frames */

/* In world mode dt in updates of at most UPDATE_MAX, so the module's clock is the world's: a
 * world-mode module is brought from its base to the first frame (up to a minute) in whole steps,
 * as if it had run. A world clock that jumps ahead (a
 * host's clock that was set, CIGI's or DIS's time heard for the first time far from the system
 * clock's) is followed at most CATCH_UP_MAX a frame (72,000 empty steps, a few ms), said once. */
static int advance(struct player *p, double dt, char *err, size_t n)
{
    if (dt <= 0.0) return 0; /* already there (player_host_prepare advanced it) */
    if (p->world.on && dt > CATCH_UP_MAX) {
        if (!p->world.jump_said++)
            fprintf(stderr, "sbfx-play: the world clock is %.0f s ahead of the module's: followed %.0f s a frame\n",
                    dt, CATCH_UP_MAX);
        dt = CATCH_UP_MAX;
    }
    double target = p->sim_time + dt;
    while (dt > 0.0) {
        /* outside world mode one update, as always: sbfx_update cuts a long dt at its 0.25 s */
        double part = p->world.on && dt > UPDATE_MAX ? UPDATE_MAX : dt;
        sbfx_result r = sbfx_update(p->fx, part);
        if (r != SBFX_OK) {
            snprintf(err, n, "sbfx_update(%g) at t=%.4f s: %s: %s", part, p->sim_time,
                     sbfx_result_string(r), sbfx_last_error(p->fx));
            return -EIO;
        }
        sbfx_counters c;
        sbfx_stats(p->fx, &c);
        p->frame_simulated += c.particles_simulated;
        dt -= part;
    }
    p->sim_time = target;
    return 0;
}

int player_update(struct player *p, double t, char *err, size_t n) { return advance(p, t - p->sim_time, err, n); }
