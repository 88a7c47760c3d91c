/* sbfx-play's frame loop. Per frame: wait until the display can take a frame (a page flip in
 * flight completes; the trigger sources are serviced while waiting, the detail feeds once;
 * headless with a real-time source, until the frame's time), start the triggers queued
 * meanwhile, draw the test scene, copy it into the display's framebuffer, sbfx_update +
 * sbfx_render over it, present; on a screen, a line of counters once a second. It reaches its
 * inputs and outputs through their contracts only: the display (display/display.h), the trigger
 * sources, their queue and the detail feeds (inputs/inputs.h), systemd's notify
 * (outputs/notify.h). Nothing here allocates. */
#include <errno.h>
#include <limits.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>

#include "egl/gl_check.h"
#include "player/player.h"

#define FLIP_TIMEOUT_NS INT64_C(1000000000)
#define MAX_REALTIME_STEP 0.25 /* s: a stalled frame does not make the simulation jump */
#define NS_PER_S 1e9

/* ---- waiting for the display ---------------------------------------------------------- */

static int collect_fds(struct player *p, struct pollfd *fds, int max, int *display_slot)
{
    int count = 0;
    *display_slot = -1;
    if (p->display->busy && p->display->fd >= 0) {
        *display_slot = count;
        fds[count++] = (struct pollfd){.fd = p->display->fd, .events = POLLIN};
    }
    count += trigger_sources_pollfds(&p->triggers, fds + count, max - count);
    return count;
}

/* Polls the display (while a flip is in flight) and the trigger sources (inputs.h: the GPIO lines
 * and whatever else the run has); returns when the display can take the next frame, or a signal
 * asks to stop. The detail feeds are serviced once per frame. */
static int wait_ready(struct player *p, char *err, size_t n)
{
    struct display *d = p->display;
    int64_t deadline = player_now_ns() + FLIP_TIMEOUT_NS;
    for (;;) {
        struct pollfd fds[1 + TRIGGER_POLLFDS_MAX];
        int slot = -1, count = collect_fds(p, fds, (int)(sizeof(fds) / sizeof(fds[0])), &slot);
        int64_t left = deadline - player_now_ns();
        int timeout = d->busy ? (int)(left > 0 ? left / 1000000 + 1 : 0) : 0;
        int r = count ? poll(fds, (nfds_t)count, timeout) : 0;
        if (r < 0 && errno != EINTR) {
            int rc = -errno;
            snprintf(err, n, "poll: %s", strerror(errno));
            return rc;
        }
        if (r > 0 && slot >= 0 && fds[slot].revents) {
            int rc = d->ops->dispatch(d, err, n);
            if (rc) return rc;
        }
        trigger_sources_service(&p->triggers, p->fx, player_now_ns());
        if (!d->busy || player_stop_requested() || d->closed) break;
        if (player_now_ns() < deadline) continue;
        if (!d->ops->stalled) {
            snprintf(err, n, "%s: a page flip did not complete within 1 s", d->description);
            return -ETIMEDOUT;
        }
        int rc = d->ops->stalled(d, err, n); /* wayland: a hidden window; frames go on unshown */
        if (rc) return rc;
    }
    detail_service(&p->detail, player_now_ns());
    return 0;
}

/* Headless with a real-time trigger source (p->paced: the network's senders keep the wall clock):
 * waits until the frame's time (the run's start + frames / --fps), the sources serviced
 * meanwhile; at once otherwise, or when a stop is asked. */
static int pace(struct player *p, char *err, size_t n)
{
    if (!p->paced) return 0;
    int64_t due = p->run_start_ns + (int64_t)((double)p->frames_done * NS_PER_S / p->opt->fps);
    if (p->world.on && p->opt->world_clock == PLAYER_CLOCK_SYSTEM) /* the frame's world time on the system clock */
        due = player_now_ns() + (int64_t)((world_frame_time(p, p->frames_done) - world_system_seconds()) * NS_PER_S);
    for (;;) {
        trigger_sources_service(&p->triggers, p->fx, player_now_ns());
        int64_t now = player_now_ns();
        if (now >= due || player_stop_requested()) return 0;
        struct pollfd fds[TRIGGER_POLLFDS_MAX];
        int count = trigger_sources_pollfds(&p->triggers, fds, TRIGGER_POLLFDS_MAX);
        if (poll(fds, (nfds_t)count, (int)((due - now) / 1000000) + 1) < 0 && errno != EINTR) {
            int rc = -errno;
            snprintf(err, n, "poll (waiting for the frame's time): %s", strerror(errno));
            return rc;
        }
    }
}

/* ---- one frame ------------------------------------------------------------------------ */

static int draw_scene(struct player *p, double t, sbfx_frame *frame, char *err, size_t n)
{
    int w = p->display->width, h = p->display->height;
    test_scene_camera(&p->camera, t, (float)w / (float)h, frame->view, frame->projection);
    world_eyepoint(p, frame->view); /* CIGI's entity 0 or --follow's DIS entity, where there is one */
    const struct player_channel channel = world_channel(p);
    world_channel_view(&channel, TEST_SCENE_NEAR, TEST_SCENE_FAR, frame->view, frame->projection);
    if (test_scene_draw(&p->scene, frame->view, frame->projection) != 0) {
        snprintf(err, n, "test scene: GL error while drawing");
        return -EIO;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, p->scene.framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, p->display->framebuffer);
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    frame->scene_color_texture = p->scene.color_texture;
    frame->scene_depth_texture = p->scene.depth_texture;
    frame->out_framebuffer = p->display->framebuffer;
    frame->width = w;
    frame->height = h;
    if (p->measure_gpu) glFinish(); /* so the timed part below holds sbfx's GPU work only */
    return platform_gl_check("scene copy to the output framebuffer", err, n);
}

static int run_fx(struct player *p, double t, const sbfx_frame *frame, char *err, size_t n)
{
    int rc = player_update(p, t, err, n);
    if (rc) return rc;
    sbfx_result r = sbfx_render(p->fx, frame);
    if (r != SBFX_OK) {
        snprintf(err, n, "sbfx_render at t=%.4f s: %s: %s", t, sbfx_result_string(r),
                 sbfx_last_error(p->fx));
        return -EIO;
    }
    if (p->measure_gpu) glFinish();
    return 0;
}

/* The frame-budget fallback where the module cannot time itself: headless runs measure sbfx's
 * work between two glFinish calls (the module ignores it when its own timer queries work). */
static void report_time(struct player *p, double sbfx_ms)
{
    if (p->measure_gpu && p->last.budget_ms > 0) sbfx_report_frame_time(p->fx, sbfx_ms);
}

static void record_times(struct frame_times *t, double sbfx_ms, double total_ms)
{
    t->sbfx_sum += sbfx_ms;
    t->total_sum += total_ms;
    if (sbfx_ms > t->sbfx_max) t->sbfx_max = sbfx_ms;
    if (total_ms > t->total_max) t->total_max = total_ms;
}

/* Simulated time of frame i: i/F, or (drm without --fps) the clock since the first frame,
 * advancing at most MAX_REALTIME_STEP per frame. */
static double frame_time(struct player *p, int64_t index, int64_t now)
{
    double host = 0.0;
    if (p->world.on && p->opt->world_clock == PLAYER_CLOCK_CIGI) /* the host's clock once heard; until then still */
        return cigi_source_time(&p->cigi, now, &host) && host > p->sim_time ? host : p->sim_time;
    if (p->world.on && p->opt->world_clock == PLAYER_CLOCK_DIS) /* the exercise's timestamps, the same way */
        return dis_source_time(&p->dis, now, &host) && host > p->sim_time ? host : p->sim_time;
    if (p->world.on && p->opt->world_clock == PLAYER_CLOCK_SYSTEM && p->realtime) return world_system_seconds();
    if (p->world.on && !p->realtime) return world_frame_time(p, index);
    if (!p->realtime) return (double)index / p->opt->fps;
    if (index == 0) return p->world.on ? world_frame_time(p, 0) : 0.0;
    double dt = (double)(now - p->last_frame_ns) / NS_PER_S;
    return p->sim_time + (dt < MAX_REALTIME_STEP ? dt : MAX_REALTIME_STEP);
}

/* The display's size changed (a Wayland configure): the test scene's targets follow; sbfx's
 * follow the frame's size by themselves. */
static int follow_resize(struct player *p, char *err, size_t n)
{
    struct display *d = p->display;
    d->resized = false;
    test_scene_destroy(&p->scene);
    p->scene_made = false;
    int rc = test_scene_create(&p->scene, d->width, d->height, err, n);
    if (rc) return rc;
    p->scene_made = true;
    if (!p->opt->quiet) fprintf(stderr, "sbfx-play: %s: the window is %dx%d now\n", d->name, d->width, d->height);
    return 0;
}

static int play_frame(struct player *p, int64_t index, char *err, size_t n)
{
    int rc = player_check_gpu_reset(p, index, err, n);
    if (rc == 0 && p->display->resized) rc = follow_resize(p, err, n);
    if (rc) return rc;
    int64_t start = player_now_ns();
    double t = frame_time(p, index, start);
    p->last_frame_ns = start;
    sbfx_frame frame;
    memset(&frame, 0, sizeof(frame));
    p->frame_simulated = 0;
    /* what arrived during the last frame starts at this one's first step */
    trigger_sources_fire(&p->triggers, p->fx, player_now_ns());
    rc = world_fire_due(p, p->world.on ? t : p->opt->start_time + t, err, n); /* identified ones at their time */
    if (rc) return rc;
    rc = player_host_prepare(p, t, err, n);
    if (rc) return rc;
    rc = draw_scene(p, t, &frame, err, n);
    if (rc) return rc;
    int64_t fx_start = player_now_ns();
    rc = run_fx(p, t, &frame, err, n);
    if (rc) return rc;
    int64_t fx_end = player_now_ns();
    sbfx_stats(p->fx, &p->last);
    /* headless runs stop at --frames (int); a kiosk's display does not name its frames */
    int64_t shown = index - p->take_first; /* headless --watch: each take writes frame-0000.png on */
    rc = p->display->ops->present(p->display, shown < INT_MAX ? (int)shown : INT_MAX, err, n);
    if (rc) return rc;
    cigi_source_frame_done(&p->cigi, player_now_ns()); /* Start of Frame: this frame is drawn */
    report_time(p, (double)(fx_end - fx_start) / 1e6);
    record_times(&p->times, (double)(fx_end - fx_start) / 1e6, (double)(player_now_ns() - start) / 1e6);
    return 0;
}

/* ---- the once-a-second line ------------------------------------------------------------- */

static void second_reset(struct player *p, int64_t now)
{
    struct second_stats *s = &p->second;
    s->start_ns = now;
    s->frames = (uint64_t)p->frames_done;
    s->flips = p->display->counts.flips;
    s->missed = p->display->counts.missed;
    s->fired = (uint64_t)p->last.triggers_fired;
    s->video = p->detail.camera_on ? p->detail.camera.counts.frames : 0;
    s->shown = p->display->counts.feedback_presented;
    s->latency_ns = p->display->counts.latency_ns_sum;
    s->frame_ms_sum = p->times.total_sum;
    s->frame_ms_max = 0.0;
}

static void stats_line(struct player *p, int64_t now)
{
    struct second_stats *s = &p->second;
    const struct display_counts *c = &p->display->counts;
    double seconds = (double)(now - s->start_ns) / NS_PER_S;
    uint64_t frames = (uint64_t)p->frames_done - s->frames;
    char video[96] = "";
    if (p->detail.camera_on) {
        char what[64];
        live_detail_describe(&p->detail.camera, what, sizeof(what));
        snprintf(video, sizeof(video), ", video %llu frames (%s)",
                 (unsigned long long)(p->detail.camera.counts.frames - s->video), what);
    }
    char latency[64] = "";
    if (p->display->presentation && c->feedback_presented > s->shown)
        snprintf(latency, sizeof(latency), ", latency %.1f ms",
                 (double)(c->latency_ns_sum - s->latency_ns) / (double)(c->feedback_presented - s->shown) / 1e6);
    char budget[96] = "";
    if (p->last.budget_ms > 0)
        snprintf(budget, sizeof(budget), " (gpu %.1f of %.1f ms, %d changes)", (double)p->last.gpu_ms,
                 (double)p->last.budget_ms, p->last.quality_changes);
    printf("sbfx-play: %.1f fps, frame %.1f ms (max %.1f), flips %llu, missed vblanks %llu, "
           "particles %d, triggers %llu, quality %s%s%s%s\n",
           (double)frames / seconds, frames ? (p->times.total_sum - s->frame_ms_sum) / (double)frames : 0.0,
           s->frame_ms_max, (unsigned long long)(c->flips - s->flips),
           (unsigned long long)(c->missed - s->missed), p->last.particles_alive,
           (unsigned long long)((uint64_t)p->last.triggers_fired - s->fired), p->last.quality, budget, video,
           latency);
    fflush(stdout);
}

static void stats_tick(struct player *p)
{
    if (p->display->fd < 0) return; /* headless: the summary at the end says it all */
    int64_t now = player_now_ns();
    double last_ms = (double)(now - p->last_frame_ns) / 1e6;
    if (last_ms > p->second.frame_ms_max) p->second.frame_ms_max = last_ms;
    if (now - p->second.start_ns < 1000000000) return;
    if (!p->opt->quiet) stats_line(p, now);
    second_reset(p, now);
}

/* ---- the loop --------------------------------------------------------------------------- */

/* Frames from *next on: until --frames (a take: a reload starts another one headless), or
 * until stopped. */
static int run_take(struct player *p, int64_t *next, char *err, size_t n)
{
    const struct player_options *opt = p->opt;
    bool limited = !player_on_screen(opt) || opt->frames_set;
    bool takes = opt->watch && !player_on_screen(opt);
    for (int64_t i = *next; !limited || i < p->take_first + opt->frames; i++, *next = i) {
        char why[1024];
        if (player_watch_service(p) == PLAYER_RELOADED && takes) p->take_first = i; /* the new scene from frame 0000 */
        int rc = wait_ready(p, why, sizeof(why));
        if (rc == 0) rc = pace(p, why, sizeof(why));
        if (rc == 0 && (player_stop_requested() || p->display->closed)) {
            player_notify_stopping();
            break;
        }
        if (rc == 0) rc = play_frame(p, i, why, sizeof(why));
        if (rc) {
            snprintf(err, n, "frame %lld: %s", (long long)i, why);
            return rc;
        }
        p->frames_done++;
        player_notify_frame(&p->notify, p->frames_done, player_now_ns());
        player_notify_test_hang(&p->notify, p->frames_done);
        stats_tick(p);
    }
    return 0;
}

int player_run_frames(struct player *p, char *err, size_t n)
{
    p->run_start_ns = player_now_ns();
    second_reset(p, p->run_start_ns);
    player_notify_init(&p->notify);
    bool takes = p->opt->watch && !player_on_screen(p->opt);
    for (int64_t next = 0;;) {
        int rc = run_take(p, &next, err, n);
        if (rc == 0) rc = p->display->ops->finish(p->display, err, n); /* headless: the contact sheet */
        if (rc || !takes || player_stop_requested()) return rc;
        if (!p->opt->quiet) printf("sbfx-play: %lld frames written; waiting for a change of %s\n",
                                   (long long)(next - p->take_first), p->opt->scene_path);
        fflush(stdout);
        if ((rc = player_watch_wait(p, err, n)) <= 0) return rc; /* stopped (0) or an error */
        p->take_first = next;
    }
}
