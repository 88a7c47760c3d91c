/* sbfx-play: renders sbfx effects over the test scene, headless into PNG frames or on a DRM/KMS
 * display as a kiosk, with GPIO lines, DIS detonations, MQTT messages and a V4L2 camera as
 * inputs.
 *
 * One frame: test scene -> its colour is copied into the display's framebuffer (so an idle
 * sbfx, which issues no pass, still leaves the scene there) -> sbfx_update -> sbfx_render into
 * that framebuffer -> the display presents it (headless: glReadPixels -> PNG; drm: page flip).
 * The command line is in options/args.c, the loop in loop.c, the inputs in inputs/ (player.h
 * has the map). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "player/player.h"
#include "player/outputs/stats.h"

/* ---- setup -------------------------------------------------------------------------------- */

/* mkdir -p: every missing component of path, then a check that it is a directory. */
static int make_dirs(const char *path, char *err, size_t n)
{
    char buf[PATH_MAX];
    if (snprintf(buf, sizeof(buf), "%s", path) >= (int)sizeof(buf)) {
        snprintf(err, n, "--out: path too long: %s", path);
        return -ENAMETOOLONG;
    }
    for (char *p = buf + 1; *p; p++) {
        if (*p != '/') continue;
        *p = '\0';
        if (mkdir(buf, 0777) != 0 && errno != EEXIST) goto err_mkdir;
        *p = '/';
    }
    if (mkdir(buf, 0777) != 0 && errno != EEXIST) goto err_mkdir;
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode)) {
        snprintf(err, n, "--out: %s exists and is not a directory", path);
        return -ENOTDIR;
    }
    return 0;

err_mkdir: {
    int rc = -errno;
    snprintf(err, n, "--out: cannot create %.512s: %s", buf, strerror(errno));
    return rc;
}
}

/* A bad --stats path should fail before the run, not after minutes of rendering. */
static int check_writable(const char *path, char *err, size_t n)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        int rc = -errno;
        snprintf(err, n, "--stats: cannot create %s: %s", path, strerror(errno));
        return rc;
    }
    fclose(f);
    return 0;
}

static int create_headless(struct player *p, char *err, size_t n)
{
    const struct player_options *opt = p->opt;
    int rc = make_dirs(opt->out_dir, err, n);
    if (rc) return rc;
    if (!realpath(opt->out_dir, p->out_dir)) {
        rc = -errno;
        snprintf(err, n, "--out: %s: %s", opt->out_dir, strerror(errno));
        return rc;
    }
    if (opt->stats_path && (rc = check_writable(opt->stats_path, err, n)) != 0) return rc;
    const struct display_headless_desc desc = {
        .width = opt->width, .height = opt->height, .out_dir = p->out_dir,
        .contact_sheet = opt->contact_sheet, .frames = opt->frames,
    };
    p->measure_gpu = true;
    return display_headless_create(&desc, &p->display, err, n);
}

static const char *either(const char *flag, const char *board_value)
{
    return flag ? flag : (board_value[0] ? board_value : NULL);
}

static int create_drm(struct player *p, char *err, size_t n)
{
    const struct player_options *opt = p->opt;
    int rc = 0;
    if (opt->stats_path && (rc = check_writable(opt->stats_path, err, n)) != 0) return rc;
    const struct board_profile *b = &p->board;
    const struct display_drm_desc desc = {
        .device = either(opt->device, b->drm_device),
        .connector = either(opt->connector, b->connector),
        .mode = either(opt->mode, b->mode),
        .modeset = opt->modeset >= 0 ? opt->modeset : (int)b->modeset,
        .screenshot = opt->screenshot,
    };
    p->realtime = !opt->fps_set;
    char why[768];
    rc = display_drm_create(&desc, &p->display, why, sizeof(why));
    if (rc) snprintf(err, n, "--display drm: %s", why);
    return rc;
}

/* A client of the compositor of WAYLAND_DISPLAY: full screen, or --size where it refuses. */
static int create_wayland(struct player *p, char *err, size_t n)
{
    const struct player_options *opt = p->opt;
    int rc = 0;
    if (opt->stats_path && (rc = check_writable(opt->stats_path, err, n)) != 0) return rc;
    const struct display_wayland_desc desc = {
        .width = opt->width, .height = opt->height, .size_set = opt->size_set,
    };
    p->realtime = !opt->fps_set;
    char why[768];
    rc = display_wayland_create(&desc, &p->display, why, sizeof(why));
    if (rc) snprintf(err, n, "--display wayland: %s", why);
    return rc;
}

static int create_display(struct player *p, char *err, size_t n)
{
    switch (p->opt->display) {
    case PLAYER_DISPLAY_DRM: return create_drm(p, err, n);
    case PLAYER_DISPLAY_WAYLAND: return create_wayland(p, err, n);
    case PLAYER_DISPLAY_HEADLESS: break;
    }
    return create_headless(p, err, n);
}

static int load_board(struct player *p, char *err, size_t n)
{
    board_profile_defaults(&p->board);
    if (!p->opt->board_path) return 0;
    char why[512];
    int rc = board_load(p->opt->board_path, &p->board, why, sizeof(why));
    if (rc) {
        snprintf(err, n, "--board: %s", why);
        return rc;
    }
    p->have_board = true;
    return 0;
}

/* The inputs the scene, the board and the flags name: GPIO lines (the scene's were collected
 * with the scene, player_create_fx), DIS (placed by the scene's dis group), MQTT, the scene's
 * detail clip, the camera. */
static int open_inputs(struct player *p, char *err, size_t n)
{
    const struct player_options *opt = p->opt;
    int rc = gpio_source_add_options(&p->gpio, &p->board, opt, err, n);
    if (rc == 0) rc = gpio_source_open(&p->gpio, &p->triggers, p->fx, player_now_ns(), player_log, p, err, n);
    if (rc == 0) rc = dis_source_open(&p->dis, &p->triggers, opt, &p->board, p->fx, player_log, p, err, n);
    if (rc == 0) rc = cigi_source_open(&p->cigi, &p->triggers, opt, p->fx, player_log, p, err, n);
    if (rc == 0) rc = mqtt_source_open(&p->mqtt, &p->triggers, opt, &p->board, player_log, p, err, n);
    /* headless with a real-time source, or on the system clock: frames at their times on the clock */
    p->paced = !player_on_screen(opt) &&
               (trigger_sources_realtime(&p->triggers) || (p->world.on && opt->world_clock == PLAYER_CLOCK_SYSTEM));
    if (rc == 0) rc = detail_open_clip(p->fx, player_log, p, err, n);
    if (rc == 0) rc = detail_open_camera(&p->detail, p->fx, opt->video, &p->board, player_log, p, err, n);
    return rc;
}

/* The channel: the board's view, each part the flags give replacing the board's. */
static void merge_channel(struct player *p)
{
    const struct player_channel *flags = &p->opt->channel;
    p->channel = p->board.channel;
    if (flags->have_frustum) memcpy(p->channel.frustum, flags->frustum, sizeof(flags->frustum));
    if (flags->have_offset) memcpy(p->channel.offset, flags->offset, sizeof(flags->offset));
    p->channel.have_frustum |= flags->have_frustum;
    p->channel.have_offset |= flags->have_offset;
}

static int setup(struct player *p, char *err, size_t n)
{
    int rc = load_board(p, err, n);
    if (rc == 0) merge_channel(p);
    if (rc == 0) rc = world_setup(p, err, n);
    if (rc == 0) rc = player_parse_scene(p, err, n);
    if (rc) return rc;
    rc = create_display(p, err, n);
    if (rc) return rc;
    struct display *d = p->display;
    if ((rc = test_scene_create(&p->scene, d->width, d->height, err, n)) != 0) return rc;
    p->scene_made = true;
    player_reset_setup(p);
    if ((rc = player_create_fx(p, err, n)) != 0) return rc;
    return open_inputs(p, err, n);
}

/* Undoes whatever part of setup() happened: every member starts zeroed. */
static void teardown(struct player *p)
{
    trigger_sources_close(&p->triggers);
    detail_close(&p->detail);
    scene_watch_close(&p->watch);
    player_keep_scene(p, NULL);
    sbfx_scene_free(p->scene_first);
    p->scene_first = NULL;
    if (p->fx) sbfx_destroy(p->fx);
    if (p->scene_made) test_scene_destroy(&p->scene);
    if (p->display) p->display->ops->destroy(p->display);
    p->fx = NULL;
    p->display = NULL;
}

/* ---- results -------------------------------------------------------------------------- */

/* The trigger path's numbers: the queue's refusals and log, DIS's and MQTT's counters. A GPIO
 * edge the queue took counts as fired by its line until the pool refuses it. */
static void collect_triggers(const struct player *p, struct player_stats_record *r)
{
    const struct trigger_queue *q = &p->triggers.queue;
    const struct dis_counts *d = dis_source_counts(&p->dis);
    struct mqtt_counts m;
    mqtt_source_counts(&p->mqtt, &m);
    r->dis_on = d != NULL;
    r->mqtt_on = p->mqtt.client != NULL;
    r->kiosk_on = r->kiosk_on || r->dis_on || r->mqtt_on;
    r->triggers_refused += (long long)(trigger_queue_refused(q) + m.overflows);
    r->gpio_fired -= (long long)q->pool_full[TRIGGER_GPIO];
    r->gpio_refused += (long long)q->pool_full[TRIGGER_GPIO];
    _Static_assert(TRIGGER_LOG_MAX <= STATS_TRIGGER_LOG_MAX, "the --stats record holds the whole log");
    struct trigger_log_entry log[TRIGGER_LOG_MAX];
    r->trigger_log_count = trigger_queue_log(q, log);
    for (int i = 0; i < r->trigger_log_count; i++) {
        struct stats_trigger *t = &r->trigger_log[i];
        t->source = trigger_kind_name(log[i].kind);
        snprintf(t->effect, sizeof(t->effect), "%s", log[i].effect);
        memcpy(t->at, log[i].at, sizeof(t->at));
        t->time = log[i].time;
    }
    if (d) {
        r->dis_pdus = (long long)d->pdus, r->dis_detonations = (long long)d->detonations;
        r->dis_ignored = (long long)d->ignored, r->dis_malformed = (long long)d->malformed;
    }
    const struct cigi_counts *g = cigi_source_counts(&p->cigi);
    r->cigi_on = g != NULL;
    r->kiosk_on = r->kiosk_on || r->cigi_on;
    if (g) {
        r->cigi_messages = (long long)g->messages, r->cigi_malformed = (long long)g->malformed;
        r->cigi_ignored = (long long)g->ignored, r->cigi_entities = (long long)g->entities;
        r->cigi_stopped = (long long)q->stopped[TRIGGER_CIGI], r->cigi_start_of_frame = (long long)g->sof_sent;
    }
    r->world_on = p->world.on;
    r->world_time = p->sim_time;
    r->triggers_expired = (long long)sbfx_triggers_expired(p->fx);
    r->mqtt_messages = (long long)m.messages;
    r->mqtt_malformed = (long long)(p->mqtt.bad_syntax + p->mqtt.bad_effect);
    r->mqtt_reconnects = (long long)m.reconnects;
}

static void collect_stats(const struct player *p, struct player_stats_record *r)
{
    const sbfx_counters *c = &p->last;
    const struct display_counts *d = &p->display->counts;
    const struct gpio_trigger_counts *g = &p->gpio.lines.counts;
    const struct live_detail_counts *v = &p->detail.camera.counts;
    *r = (struct player_stats_record){
        .programs = c->programs, .textures = c->textures, .framebuffers = c->framebuffers,
        .gpu_bytes = (long long)c->gpu_bytes, .passes = c->passes, .draw_calls = c->draw_calls,
        .composite_tiles = c->composite_tiles, .composite_pixels = c->composite_pixels,
        .particles_simulated = p->frame_simulated,
        .heap_allocs_after_load = (long long)c->heap_allocs_after_load,
        .budget_ms = c->budget_ms, .gpu_ms = c->gpu_ms,
        .frames_over_budget = c->frames_over_budget, .quality_changes = c->quality_changes,
        .gpu_resets = (long long)p->gpu_resets, .gpu_reset_notification = p->reset.status ? 1 : 0,
        .frames = p->frames_done, .flips = (long long)d->flips, .missed_vblanks = (long long)d->missed,
        .triggers_fired = c->triggers_fired, .triggers_refused = c->triggers_refused,
        .display_unplugs = (long long)d->unplugs, .display_replugs = (long long)d->replugs,
        .display_paused_frames = (long long)d->paused,
        .presented_frames = (long long)d->feedback_presented,
        .discarded_frames = (long long)d->feedback_discarded,
        .latency_ms_mean = d->feedback_presented ? (double)d->latency_ns_sum / (double)d->feedback_presented / 1e6 : 0.0,
        .latency_ms_max = (double)d->latency_ns_max / 1e6,
        .gpio_edges = (long long)g->edges, .gpio_fired = (long long)g->fired,
        .gpio_filtered = (long long)g->filtered, .gpio_refused = (long long)g->refused,
        .gpio_overflows = (long long)g->overflows, .gpio_losses = (long long)g->losses,
        .gpio_returns = (long long)g->returns, .gpio_retries = (long long)g->retries,
        .gpio_absent = (long long)g->absent, .gpio_appeared = (long long)g->appeared,
        .video_frames = (long long)v->frames, .video_distinct = (long long)v->distinct,
        .video_losses = (long long)v->losses, .video_reopens = (long long)v->reopens,
        .video_takeovers = (long long)v->takeovers,
        .kiosk_on = p->display->fd >= 0 || p->gpio.on || p->detail.camera_on,
        .gpio_on = p->gpio.on, .video_on = p->detail.camera_on, .presentation_on = p->display->presentation,
    };
    snprintf(r->quality, sizeof(r->quality), "%s", c->quality);
    collect_triggers(p, r);
}

/* The --stats file: one JSON object, from the table in outputs/stats.c. */
static int write_stats(const struct player *p, const char *path, char *err, size_t n)
{
    struct player_stats_record record;
    collect_stats(p, &record);
    FILE *f = fopen(path, "w");
    if (!f) {
        int rc = -errno;
        snprintf(err, n, "--stats: cannot create %s: %s", path, strerror(errno));
        return rc;
    }
    bool failed = player_stats_write(&record, f) != 0;
    if (fclose(f) != 0 || failed) {
        snprintf(err, n, "--stats: writing %s failed: %s", path, strerror(errno));
        return -EIO;
    }
    return 0;
}

static const char *format_name(sbfx_target_format format)
{
    static const char *const names[] = {"not reported", "RGBA8", "RGBA16F", "RGBA32F"};
    return (unsigned)format < SBFX_FORMAT_COUNT ? names[format] : "?";
}

static void print_headless_summary(const struct player *p)
{
    const struct frame_times *t = &p->times;
    int frames = (int)p->frames_done; /* headless runs are limited by --frames (per take: --watch) */
    int take = (int)(p->frames_done - p->take_first);
    printf("sbfx-play: %d frames of %dx%d in %s (frame-0000.png .. frame-%04d.png)\n", frames,
           p->opt->width, p->opt->height, p->out_dir, take - 1);
    if (p->opt->contact_sheet) printf("sbfx-play: contact sheet: %s/contact-sheet.png\n", p->out_dir);
    printf("sbfx-play: sbfx update+render+glFinish: mean %.2f ms, max %.2f ms per frame "
           "(particle target %s)\n", t->sbfx_sum / frames, t->sbfx_max,
           format_name(p->last.target_format));
    printf("sbfx-play: whole frame (scene, sbfx, readback, PNG): mean %.2f ms, max %.2f ms\n",
           t->total_sum / frames, t->total_max);
}

/* What the compositor reported of the frames (wayland's presentation-time feedback). */
static void print_presentation(const struct display_counts *c)
{
    double mean = c->feedback_presented ? (double)c->latency_ns_sum / (double)c->feedback_presented / 1e6 : 0.0;
    printf("sbfx-play: presentation feedback: %llu presented, %llu discarded; commit to screen mean "
           "%.2f ms, max %.2f ms\n", (unsigned long long)c->feedback_presented,
           (unsigned long long)c->feedback_discarded, mean, (double)c->latency_ns_max / 1e6);
}

static void print_screen_summary(const struct player *p)
{
    const struct display_counts *c = &p->display->counts;
    double seconds = (double)(player_now_ns() - p->run_start_ns) / 1e9;
    long long frames = (long long)p->frames_done;
    printf("sbfx-play: %lld frames in %.1f s (%.1f fps) on %s; flips %llu, missed vblanks %llu; "
           "sbfx update+render mean %.2f ms, max %.2f ms (particle target %s)\n", frames, seconds,
           seconds > 0 ? (double)frames / seconds : 0.0, p->display->description,
           (unsigned long long)c->flips, (unsigned long long)c->missed,
           frames ? p->times.sbfx_sum / (double)frames : 0.0, p->times.sbfx_max, format_name(p->last.target_format));
    if (p->display->presentation) print_presentation(c);
    if (p->opt->screenshot) printf("sbfx-play: screenshot: %s\n", p->opt->screenshot);
}

static int finish(struct player *p, char *err, size_t n)
{
    int rc = 0;
    /* GPIO triggers may have fired after the last render: their counters are current now (the
     * per-frame ones - passes, draw calls - are still the last render's). */
    sbfx_stats(p->fx, &p->last);
    if (p->opt->stats_path && (rc = write_stats(p, p->opt->stats_path, err, n)) != 0) return rc;
    if (p->opt->quiet) return 0;
    if (player_on_screen(p->opt)) print_screen_summary(p);
    else print_headless_summary(p);
    return 0;
}

static void print_banner(const struct player *p)
{
    const struct player_options *opt = p->opt;
    const char *version = (const char *)glGetString(GL_VERSION);
    if (!version) version = "?";
    if (!player_on_screen(opt)) {
        printf("sbfx-play: %s, %s, %s; %dx%d, %d frames at %g fps\n", display_gl_renderer(),
               version, p->display->description, opt->width, opt->height, opt->frames, opt->fps);
        return;
    }
    char frames[32] = "until stopped", pace[48] = "simulation follows the clock";
    if (opt->frames_set) snprintf(frames, sizeof(frames), "%d frames", opt->frames);
    if (!p->realtime) snprintf(pace, sizeof(pace), "%g simulated fps", opt->fps);
    printf("sbfx-play: %s, %s, %s; %s, %s\n", display_gl_renderer(), version,
           p->display->description, frames, pace);
    fflush(stdout);
}

static int play(const struct player_options *opt)
{
    static struct player player; /* large (PATH_MAX, trigger tables): off the stack */
    struct player *p = &player;
    memset(p, 0, sizeof(*p));
    p->opt = opt;
    p->watch.fd = -1;
    char err[1024] = "";
    int rc = setup(p, err, sizeof(err));
    if (rc == 0) {
        if (!opt->quiet) print_banner(p);
        if (player_on_screen(opt)) player_catch_signals();
        if (opt->watch && !player_on_screen(opt)) player_catch_signals(); /* runs until stopped */
        if (p->paced) player_catch_signals(); /* stopped early: the stats are still written */
        if (opt->watch || player_on_screen(opt)) player_catch_hup();       /* a reload */
        rc = player_run_frames(p, err, sizeof(err));
    }
    if (rc == 0) rc = finish(p, err, sizeof(err));
    if (rc) fprintf(stderr, "sbfx-play: %s\n", err);
    bool lost = p->display && p->display->lost;
    teardown(p);
    if (rc == 0) return 0;
    return lost ? PLAYER_EXIT_DISPLAY_LOST : 1;
}

/* --board's display.backend, where the command line chose no display: read before the run,
 * as --display is, so that the flags are checked against it. */
static int board_display(struct player_options *opt, char *err, size_t n)
{
    if (!opt->board_path || opt->display_set || opt->headless_flag) return 0;
    static struct board_profile board; /* large (GPIO table): off the stack */
    char why[512];
    if (board_load(opt->board_path, &board, why, sizeof(why)) != 0) return 0; /* setup says why */
    int rc = player_board_display(opt, board.backend, why, sizeof(why));
    if (rc) snprintf(err, n, "--board %.200s: display.backend = \"%s\": %.256s", opt->board_path, board.backend, why);
    return rc;
}

int main(int argc, char **argv)
{
    static struct player_options opt; /* the trigger table is large: off the stack */
    char err[512] = "";
    player_options_defaults(&opt);
    if (player_parse_args(&opt, argc, argv, err, sizeof(err)) != 0) {
        fprintf(stderr, "sbfx-play: %s\n", err);
        return 1;
    }
    if (opt.help) {
        player_usage(stdout);
        return 0;
    }
    if (opt.version) {
        player_version(stdout);
        return 0;
    }
    if (board_display(&opt, err, sizeof(err)) != 0) {
        fprintf(stderr, "sbfx-play: %s\n", err);
        return 1;
    }
    return play(&opt);
}
