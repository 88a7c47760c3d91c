/* The GStreamer element sbfx (issue 34; docs/hosts/gstreamer.md) in headless pipelines,
 * videotestsrc ! glupload ! sbfx ! gldownload ! appsink, checked by their pixels and the
 * element's stats: the explosion shows over the video and moves; with no effect live every
 * buffer goes on as it came, the same buffer; the trigger signal starts an effect at the running
 * time it is emitted at; a bad scene fails the state change naming its file and line; the same
 * stream gives the same frames twice, at a variable frame rate too; a seek restarts the effect;
 * a tap starts the first effect on the ground under it; a paused live pipeline pauses the
 * effect; another GL element after sbfx (glshader) draws exactly what it draws without sbfx's state; 200 frames leave no object alive
 * (the leaks tracer). */
#include <gst/video/navigation.h>
#include <unistd.h>

#include "gst_harness.h"

#define EXPLOSION "scenes/explosion.cfg"

static const char *pipeline_with(const char *element, char *buf, size_t n)
{
    snprintf(buf, n, SOURCE " ! %s ! " SINK, element);
    return buf;
}

/* The input as the element sees it: uploaded and downloaded, nothing between. */
static void reference(int frames, run *r)
{
    char d[512];
    snprintf(d, sizeof(d), "videotestsrc pattern=colors num-buffers=%d ! video/x-raw,width=96,height=64,"
             "framerate=30/1 ! glupload ! " SINK, frames);
    play(d, frames, r);
    CHECK(r->count == frames && !r->error[0], "reference: %d frames, %s", r->count, r->error);
}

static void play_fx(const char *properties, int frames, run *r)
{
    char element[512], d[1024];
    snprintf(element, sizeof(element), "sbfx name=fx %s", properties);
    snprintf(d, sizeof(d), "videotestsrc pattern=colors num-buffers=%d ! video/x-raw,width=96,height=64,"
             "framerate=30/1 ! glupload ! %s ! " SINK, frames, element);
    play(d, frames, r);
}

CHECK_TEST(explosion_shows_over_the_video_and_moves)
{
    gst_start();
    run in, out;
    reference(24, &in);
    play_fx("scene=" EXPLOSION, 24, &out);
    CHECK(out.count == 24 && !out.error[0], "%d frames: %s", out.count, out.error);
    int covered = 0, moved = 0;
    for (int i = 1; i < out.count && i < in.count; i++) {
        int c = pixels_differing(in.frames[i], out.frames[i], 8);
        if (c > covered) covered = c;
        if (pixels_differing(out.frames[i - 1], out.frames[i], 8) > 20) moved++;
    }
    printf("# the explosion covers up to %d of %d pixels; %d of %d frames moved\n", covered, W * H, moved,
           out.count - 1);
    CHECK(covered > W * H / 20, "the explosion covers %d pixels at most", covered);
    CHECK(moved >= out.count / 2, "only %d frames moved", moved);
    CHECK(stat_u64(&out, "frames-rendered") >= 20 && stat_int(&out, "triggers-fired") == 1,
          "rendered %llu, fired %d", (unsigned long long)stat_u64(&out, "frames-rendered"),
          stat_int(&out, "triggers-fired"));
    CHECK(stat_u64(&out, "heap-allocs-after-load") == 0, "sbfx allocated %llu times after load",
          (unsigned long long)stat_u64(&out, "heap-allocs-after-load"));
    run_free(&in);
    run_free(&out);
}

/* Buffers seen on the element's sink and source pads, in order. */
typedef struct seen {
    GstBuffer *in[MAX_FRAMES], *out[MAX_FRAMES];
    int ins, outs;
} seen;

static GstPadProbeReturn see_in(GstPad *pad, GstPadProbeInfo *info, gpointer user)
{
    seen *s = user;
    if (s->ins < MAX_FRAMES) s->in[s->ins++] = GST_PAD_PROBE_INFO_BUFFER(info);
    return GST_PAD_PROBE_OK;
}

static GstPadProbeReturn see_out(GstPad *pad, GstPadProbeInfo *info, gpointer user)
{
    seen *s = user;
    if (s->outs < MAX_FRAMES) s->out[s->outs++] = GST_PAD_PROBE_INFO_BUFFER(info);
    return GST_PAD_PROBE_OK;
}

static void probe(GstElement *pipeline, const char *element, const char *pad, GstPadProbeCallback fn, void *user)
{
    GstElement *e = by_name(pipeline, element);
    GstPad *p = gst_element_get_static_pad(e, pad);
    gst_pad_add_probe(p, GST_PAD_PROBE_TYPE_BUFFER, fn, user, NULL);
    gst_object_unref(p);
    gst_object_unref(e);
}

CHECK_TEST(idle_frames_are_the_input_buffers_forwarded)
{
    gst_start();
    run in, out;
    reference(16, &in);
    char d[512];
    GstElement *p = pipeline_of(pipeline_with("sbfx name=fx scene=" EXPLOSION " timeline=false", d, sizeof(d)));
    seen s = {0};
    probe(p, "fx", "sink", see_in, &s);
    probe(p, "fx", "src", see_out, &s);
    play_pipeline(p, 16, &out);
    gst_object_unref(p);
    int same_buffer = 0;
    for (int i = 0; i < s.ins && i < s.outs; i++) same_buffer += s.in[i] == s.out[i];
    CHECK(out.count == 16 && !out.error[0], "%d frames: %s", out.count, out.error);
    for (int i = 0; i < out.count && i < in.count; i++)
        CHECK(memcmp(in.frames[i], out.frames[i], FRAME_BYTES) == 0, "idle frame %d differs from the input "
              "(%d pixels)", i, pixels_differing(in.frames[i], out.frames[i], 0));
    CHECK(same_buffer >= 16, "%d of %d buffers went on as they came", same_buffer, s.outs);
    CHECK(stat_u64(&out, "frames-forwarded") == stat_u64(&out, "frames") && stat_u64(&out, "frames-rendered") == 0,
          "forwarded %llu of %llu, rendered %llu", (unsigned long long)stat_u64(&out, "frames-forwarded"),
          (unsigned long long)stat_u64(&out, "frames"), (unsigned long long)stat_u64(&out, "frames-rendered"));
    CHECK(stat_int(&out, "passes") == 0, "%d sbfx passes while idle", stat_int(&out, "passes"));
    run_free(&in);
    run_free(&out);
}

/* Emits `trigger` from the element's sink pad when the buffer of running time `at` comes in,
 * before the element sees it: the application's call at that moment of the stream. */
typedef struct trigger_at {
    GstElement *fx;
    GstClockTime at;
    const char *effect;
    int emitted;
} trigger_at;

static GstPadProbeReturn emit_at(GstPad *pad, GstPadProbeInfo *info, gpointer user)
{
    trigger_at *t = user;
    if (GST_BUFFER_PTS(GST_PAD_PROBE_INFO_BUFFER(info)) == t->at) {
        g_signal_emit_by_name(t->fx, "trigger", t->effect, 0.0, 0.0, 0.0);
        t->emitted++;
    }
    return GST_PAD_PROBE_OK;
}

static void play_triggered(const char *effect, GstClockTime at, int frames, run *out)
{
    char d[512];
    snprintf(d, sizeof(d), "videotestsrc pattern=colors num-buffers=%d ! video/x-raw,width=96,height=64,"
             "framerate=30/1 ! glupload ! sbfx name=fx scene=%s timeline=false ! " SINK, frames, EXPLOSION);
    GstElement *p = pipeline_of(d);
    trigger_at t = {.fx = by_name(p, "fx"), .at = at, .effect = effect};
    probe(p, "fx", "sink", emit_at, &t);
    play_pipeline(p, frames, out);
    CHECK(t.emitted == 1, "emitted %d times", t.emitted);
    gst_object_unref(t.fx);
    gst_object_unref(p);
}

CHECK_TEST(trigger_signal_starts_the_effect_at_its_running_time)
{
    gst_start();
    run in, out;
    reference(20, &in);
    const int at = 10; /* frame 10: running time 1/3 s */
    play_triggered("explosion", gst_util_uint64_scale(at, GST_SECOND, 30), 20, &out);
    CHECK(out.count == 20 && !out.error[0], "%d frames: %s", out.count, out.error);
    int first = -1;
    for (int i = 0; i < out.count && i < in.count; i++)
        if (first < 0 && pixels_differing(in.frames[i], out.frames[i], 8) > 0) first = i;
    CHECK(first == at, "the first frame with the effect is %d, the trigger came with frame %d", first, at);
    CHECK(stat_int(&out, "triggers-fired") == 1 && stat_u64(&out, "frames-forwarded") == (guint64)at,
          "fired %d, forwarded %llu", stat_int(&out, "triggers-fired"),
          (unsigned long long)stat_u64(&out, "frames-forwarded"));
    run_free(&in);
    run_free(&out);
}

CHECK_TEST(unknown_effect_is_reported_with_the_scene_effects)
{
    gst_start();
    run out;
    play_triggered("fireworks", gst_util_uint64_scale(3, GST_SECOND, 30), 6, &out);
    CHECK(!out.error[0] && strstr(out.warning, "fireworks") && strstr(out.warning, "explosion"),
          "warning: \"%s\", error: \"%s\"", out.warning, out.error);
    CHECK(stat_u64(&out, "triggers-failed") == 1 && stat_u64(&out, "frames-forwarded") == 6, "failed %llu",
          (unsigned long long)stat_u64(&out, "triggers-failed"));
    run_free(&out);
}

/* A pipeline that must not reach PLAYING: the state change fails, the error names `want`, and
 * the pipeline goes back to NULL. */
static void fails_with(const char *properties, const char *want)
{
    char element[512], d[1024];
    snprintf(element, sizeof(element), "sbfx name=fx %s", properties);
    GstElement *p = pipeline_of(pipeline_with(element, d, sizeof(d)));
    GstStateChangeReturn r = gst_element_set_state(p, GST_STATE_PLAYING);
    if (r == GST_STATE_CHANGE_ASYNC) r = gst_element_get_state(p, NULL, NULL, 20 * GST_SECOND);
    run got = {0};
    drain_bus(p, &got);
    CHECK(r == GST_STATE_CHANGE_FAILURE, "the state change returned %s", gst_element_state_change_return_get_name(r));
    CHECK(strstr(got.error, want) != NULL, "the error \"%s\" does not name \"%s\"", got.error, want);
    printf("# %s\n", got.error);
    CHECK(gst_element_set_state(p, GST_STATE_NULL) == GST_STATE_CHANGE_SUCCESS, "back to NULL");
    gst_object_unref(p);
}

CHECK_TEST(bad_scene_fails_the_state_change_with_file_and_line)
{
    gst_start();
    char dir[] = "/tmp/sbfx-gst-XXXXXX", path[256], properties[320];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof(path), "%s/bad.cfg", dir);
    FILE *f = fopen(path, "w");
    fputs("# a scene with a typo on line 3\nrender = { target_scale = 4; };\nmedia = { smoke = { albedo = 0.2; "
          "densty = 0.5; }; };\n", f);
    fclose(f);
    snprintf(properties, sizeof(properties), "scene=%s", path);
    char want[300];
    snprintf(want, sizeof(want), "%s:3", path);
    fails_with(properties, want);
    fails_with("scene=/nonexistent/scene.cfg", "/nonexistent/scene.cfg");
    fails_with("", "no scene");
    unlink(path);
    rmdir(dir);
}

static bool same_frames(const run *a, const run *b, int *first)
{
    *first = -1;
    for (int i = 0; i < a->count && i < b->count; i++)
        if (memcmp(a->frames[i], b->frames[i], FRAME_BYTES) != 0) {
            *first = i;
            return false;
        }
    return a->count == b->count;
}

CHECK_TEST(same_stream_twice_gives_the_same_frames)
{
    gst_start();
    run a, b;
    play_fx("scene=" EXPLOSION, 20, &a);
    play_fx("scene=" EXPLOSION, 20, &b);
    int first = -1;
    CHECK(a.count == 20 && same_frames(&a, &b, &first), "%d and %d frames; frame %d differs", a.count, b.count,
          first);
    /* the clock at the last buffer's running time, counted in whole simulation steps */
    CHECK_NEAR(stat_double(&a, "elapsed"), 19.0 / 30.0, 1.0 / 120.0);
    run_free(&a);
    run_free(&b);
}

/* A variable frame rate: buffer i at i^2 / 400 s (dt from 2.5 ms to 95 ms), duration unset. */
static GstPadProbeReturn variable_rate(GstPad *pad, GstPadProbeInfo *info, gpointer user)
{
    int *i = user;
    GstBuffer *b = gst_buffer_make_writable(GST_PAD_PROBE_INFO_BUFFER(info));
    GST_BUFFER_PTS(b) = gst_util_uint64_scale((guint64)*i * *i, GST_SECOND, 400);
    GST_BUFFER_DURATION(b) = GST_CLOCK_TIME_NONE;
    GST_PAD_PROBE_INFO_DATA(info) = b;
    (*i)++;
    return GST_PAD_PROBE_OK;
}

static void play_variable(run *r)
{
    char d[512];
    snprintf(d, sizeof(d), "videotestsrc pattern=colors num-buffers=20 ! video/x-raw,width=96,height=64,"
             "framerate=0/1 ! glupload name=up ! sbfx name=fx scene=%s ! " SINK, EXPLOSION);
    GstElement *p = pipeline_of(d);
    int i = 0;
    probe(p, "up", "src", variable_rate, &i);
    play_pipeline(p, 20, r);
    gst_object_unref(p);
}

CHECK_TEST(variable_frame_rate_is_followed_and_repeatable)
{
    gst_start();
    run a, b;
    play_variable(&a);
    play_variable(&b);
    int first = -1;
    CHECK(a.count == 20 && !a.error[0] && same_frames(&a, &b, &first), "%d frames (%s); frame %d differs", a.count,
          a.error, first);
    /* the module's clock is the running time of the last buffer, to the simulation step */
    CHECK_NEAR(stat_double(&a, "running-time"), 19.0 * 19.0 / 400.0, 1e-9);
    CHECK_NEAR(stat_double(&a, "elapsed"), stat_double(&a, "running-time"), 1.0 / 120.0);
    CHECK(stat_u64(&a, "untimed-buffers") == 0, "%llu untimed", (unsigned long long)stat_u64(&a, "untimed-buffers"));
    run_free(&a);
    run_free(&b);
}

CHECK_TEST(seek_restarts_the_effect)
{
    gst_start();
    run first;
    play_fx("scene=" EXPLOSION, 12, &first);
    char d[512];
    GstElement *p = pipeline_of(pipeline_with("sbfx name=fx scene=" EXPLOSION, d, sizeof(d)));
    run again;
    memset(&again, 0, sizeof(again));
    gst_element_set_state(p, GST_STATE_PLAYING);
    for (int i = 0; i < 20; i++) pull(p, &again); /* 2/3 s in: the explosion is well on */
    for (int i = 0; i < again.count; i++) free(again.frames[i]);
    again.count = 0;
    CHECK(gst_element_seek_simple(p, GST_FORMAT_TIME, GST_SEEK_FLAG_FLUSH | GST_SEEK_FLAG_ACCURATE, 0), "seek");
    for (int i = 0; i < 12; i++) pull(p, &again);
    keep_stats(p, &again);
    drain_bus(p, &again);
    gst_element_set_state(p, GST_STATE_NULL);
    gst_object_unref(p);
    int differ = -1;
    CHECK(again.count == 12 && same_frames(&first, &again, &differ), "%d frames after the seek; frame %d differs "
          "from the first pass's", again.count, differ);
    CHECK(stat_u64(&again, "restarts") == 1, "%llu restarts", (unsigned long long)stat_u64(&again, "restarts"));
    run_free(&first);
    run_free(&again);
}

/* A click at pixel (x, y) of the picture, as glimagesink sends it upstream (videotestsrc, at the
 * end, handles no navigation: the push itself returns FALSE). */
static void click(GstElement *pipeline, double x, double y)
{
    GstElement *out = by_name(pipeline, "out");
    GstPad *pad = gst_element_get_static_pad(out, "sink");
    gst_pad_push_event(pad, gst_navigation_event_new_mouse_button_press(1, x, y, 0));
    gst_object_unref(pad);
    gst_object_unref(out);
}

/* Where a frame differs from the input: how many pixels, and their centroid. */
static int changed_centroid(const uint8_t *in, const uint8_t *out, double *cx, double *cy)
{
    int n = 0;
    double sx = 0, sy = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *a = in + 4 * (y * W + x), *b = out + 4 * (y * W + x);
            if (abs(a[0] - b[0]) + abs(a[1] - b[1]) + abs(a[2] - b[2]) <= 24) continue;
            n++;
            sx += x;
            sy += y;
        }
    *cx = n ? sx / n : -1;
    *cy = n ? sy / n : -1;
    return n;
}

typedef struct tapped {
    int changed;
    double cx, cy;
    guint64 taps, missed;
    int fired;
} tapped;

/* The element's input held before a buffer (a blocking probe on its sink pad): a tap queued
 * while it waits starts in that buffer, whatever the pipeline's threads did before. */
typedef struct held {
    GMutex lock;
    GCond arrived;
    GstClockTime pts; /* of the buffer held (GST_CLOCK_TIME_NONE until one is) */
} held;

static GstPadProbeReturn hold_buffer(GstPad *pad, GstPadProbeInfo *info, gpointer user)
{
    held *h = user;
    g_mutex_lock(&h->lock);
    if (!GST_CLOCK_TIME_IS_VALID(h->pts)) h->pts = GST_BUFFER_PTS(GST_PAD_PROBE_INFO_BUFFER(info));
    g_cond_signal(&h->arrived);
    g_mutex_unlock(&h->lock);
    return GST_PAD_PROBE_OK; /* stays blocked until the probe is removed */
}

/* Clicks on the sky, then at (x, y), while the element's input is held; returns the PTS of the
 * buffer the taps start in (GST_CLOCK_TIME_NONE: none came). The frames the element made before
 * it are pulled into `out` meanwhile: a full appsink would keep the next buffer from coming. */
static GstClockTime click_held(GstElement *p, run *out, double x, double y)
{
    held h = {.pts = GST_CLOCK_TIME_NONE};
    g_mutex_init(&h.lock);
    g_cond_init(&h.arrived);
    GstElement *fx = by_name(p, "fx");
    GstPad *pad = gst_element_get_static_pad(fx, "sink");
    gulong id = gst_pad_add_probe(pad, GST_PAD_PROBE_TYPE_BUFFER | GST_PAD_PROBE_TYPE_BLOCK, hold_buffer, &h, NULL);
    for (int tries = 0; tries < 20; tries++) {
        g_mutex_lock(&h.lock);
        if (!GST_CLOCK_TIME_IS_VALID(h.pts))
            g_cond_wait_until(&h.arrived, &h.lock, g_get_monotonic_time() + G_USEC_PER_SEC / 10);
        bool arrived = GST_CLOCK_TIME_IS_VALID(h.pts);
        g_mutex_unlock(&h.lock);
        if (arrived || !pull(p, out)) break;
    }
    click(p, W / 2, 2.0); /* the sky: no ground under it */
    click(p, x, y);
    gst_pad_remove_probe(pad, id);
    gst_object_unref(pad);
    gst_object_unref(fx);
    g_mutex_lock(&h.lock);
    GstClockTime pts = h.pts;
    g_mutex_unlock(&h.lock);
    g_cond_clear(&h.arrived);
    g_mutex_clear(&h.lock);
    return pts;
}

/* Three frames, a click on the sky and one at (x, y), then the frame five frames (1/6 s) after
 * the one the taps start in: what it shows. The same age for every tap, however far ahead of the
 * test the pipeline ran (appsink holds up to 4 buffers). */
static tapped tap_at(const run *in, double x, double y)
{
    char d[512];
    GstElement *p = pipeline_of(pipeline_with("sbfx name=fx scene=" EXPLOSION " timeline=false", d, sizeof(d)));
    run out;
    memset(&out, 0, sizeof(out));
    gst_element_set_state(p, GST_STATE_PLAYING);
    for (int i = 0; i < 3; i++) pull(p, &out);
    GstClockTime start = click_held(p, &out, x, y);
    bool started = GST_CLOCK_TIME_IS_VALID(start);
    GstClockTime at = started ? start + 5 * GST_SECOND / 30 - GST_MSECOND : 0; /* (PTS are rounded to ns) */
    while (started && out.count < 60 && (out.count == 0 || out.pts[out.count - 1] < at) && pull(p, &out)) {
    }
    keep_stats(p, &out);
    gst_element_set_state(p, GST_STATE_NULL);
    gst_object_unref(p);
    tapped t = {.taps = stat_u64(&out, "taps"), .missed = stat_u64(&out, "taps-missed"),
                .fired = stat_int(&out, "triggers-fired")};
    GstClockTime last = out.count ? out.pts[out.count - 1] : 0;
    bool reached = started && last >= at && last < at + GST_SECOND / 30;
    if (reached) t.changed = changed_centroid(in->frames[0], out.frames[out.count - 1], &t.cx, &t.cy);
    printf("# tap at (%.0f, %.0f): started in the frame at %.3f s; 5 frames on, %d pixels changed around "
           "(%.1f, %.1f)%s\n", x, y, started ? (double)start / GST_SECOND : -1.0, t.changed, t.cx, t.cy,
           reached ? "" : " (that frame never came)");
    run_free(&out);
    return t;
}

CHECK_TEST(tap_starts_the_first_effect_on_the_ground)
{
    gst_start();
    run in;
    reference(1, &in);
    tapped near = tap_at(&in, 0.7 * W, 0.85 * H), far = tap_at(&in, 0.7 * W, 0.62 * H);
    CHECK(near.taps == 1 && near.missed == 1 && near.fired == 1 && far.taps == 1 && far.fired == 1,
          "taps %llu and %llu, missed %llu, fired %d and %d", (unsigned long long)near.taps,
          (unsigned long long)far.taps, (unsigned long long)near.missed, near.fired, far.fired);
    /* the explosion stands on the ground under each tap: centred on its x; the farther one is
     * smaller and higher in the picture */
    CHECK(near.changed > 40 && fabs(near.cx - 0.7 * W) < 0.12 * W && fabs(far.cx - 0.7 * W) < 0.12 * W,
          "%d pixels around x %.1f and %.1f (taps at x %.1f)", near.changed, near.cx, far.cx, 0.7 * W);
    CHECK(far.changed < near.changed && far.cy < near.cy, "the farther tap: %d pixels at y %.1f, the nearer: %d at "
          "y %.1f", far.changed, far.cy, near.changed, near.cy);
    run_free(&in);
}

/* The element's clock and the running time of its last buffer, from its stats. */
static void clock_of(GstElement *fx, double *elapsed, double *running)
{
    run r = {0};
    g_object_get(fx, "stats", &r.stats, NULL);
    *elapsed = stat_double(&r, "elapsed");
    *running = stat_double(&r, "running-time");
    if (r.stats) gst_structure_free(r.stats);
}

/* Waits until the element's clock reaches `until`: the frames come when a loaded machine lets
 * them, so the test waits for them rather than for a time (10 s at most). */
static bool wait_clock(GstElement *fx, double until, double *elapsed, double *running)
{
    gint64 end = g_get_monotonic_time() + 10 * G_USEC_PER_SEC;
    do {
        clock_of(fx, elapsed, running);
        if (*elapsed >= until) return true;
        g_usleep(20000);
    } while (g_get_monotonic_time() < end);
    return false;
}

/* A live source paused for 1 s: the running time, and the effect's clock with it, goes on after
 * the pause from where it stood; had the pause counted, the clock would jump by 1 s or more. */
CHECK_TEST(paused_live_pipeline_pauses_the_effect)
{
    gst_start();
    char d[512];
    snprintf(d, sizeof(d), "videotestsrc is-live=true pattern=colors ! video/x-raw,width=32,height=24,"
             "framerate=30/1 ! glupload ! sbfx name=fx scene=%s ! gldownload ! fakesink sync=true", EXPLOSION);
    GstElement *p = pipeline_of(d), *fx = by_name(p, "fx");
    double e0 = 0, r0 = 0, e1 = 0, r1 = 0;
    gst_element_set_state(p, GST_STATE_PLAYING);
    bool started = wait_clock(fx, 0.3, &e0, &r0);
    gint64 t0 = g_get_monotonic_time();
    gst_element_set_state(p, GST_STATE_PAUSED);
    g_usleep(1000000);
    gst_element_set_state(p, GST_STATE_PLAYING);
    bool resumed = started && wait_clock(fx, e0 + 0.1, &e1, &r1);
    double wall = (double)(g_get_monotonic_time() - t0) / 1e6;
    gst_element_set_state(p, GST_STATE_NULL);
    printf("# paused 1 s: the effect's clock %.3f -> %.3f s, the stream's running time %.3f -> %.3f s, %.2f s of "
           "wall time apart\n", e0, e1, r0, r1, wall);
    CHECK(started && resumed, "the effect's clock at %.3f s and %.3f s after 10 s each (0.3 s, then 0.1 s more, "
          "wanted)", e0, e1);
    CHECK(e1 <= r1 + 1e-9 && e1 - e0 < 0.9 && r1 - r0 < 0.9,
          "the effect's clock %.3f -> %.3f s, running time %.3f -> %.3f s across a pause of 1 s", e0, e1, r0, r1);
    gst_object_unref(fx);
    gst_object_unref(p);
}

/* glshader drawing 1 - colour: GLSL ES 1.00, or 1.50 on a desktop core context (both stages: the
 * versions must match, and glshader's own vertex shader is not 1.50). */
static const char *const negate_gles[2] = {
    "#version 100\nattribute vec4 a_position;\nattribute vec2 a_texcoord;\nvarying vec2 v_texcoord;\n"
    "void main() { gl_Position = a_position; v_texcoord = a_texcoord; }\n",
    "#version 100\nprecision mediump float;\nvarying vec2 v_texcoord;\nuniform sampler2D tex;\n"
    "void main() { vec4 c = texture2D(tex, v_texcoord); gl_FragColor = vec4(vec3(1.0) - c.rgb, c.a); }\n"};
static const char *const negate_core[2] = {
    "#version 150\nin vec4 a_position;\nin vec2 a_texcoord;\nout vec2 v_texcoord;\n"
    "void main() { gl_Position = a_position; v_texcoord = a_texcoord; }\n",
    "#version 150\nin vec2 v_texcoord;\nout vec4 color;\nuniform sampler2D tex;\n"
    "void main() { vec4 c = texture(tex, v_texcoord); color = vec4(vec3(1.0) - c.rgb, c.a); }\n"};

CHECK_TEST(gl_element_after_it_renders_as_without_it)
{
    gst_start();
    run plain, negated;
    play_fx("scene=" EXPLOSION, 12, &plain);
    char d[512];
    snprintf(d, sizeof(d), "videotestsrc pattern=colors num-buffers=12 ! video/x-raw,width=96,height=64,"
             "framerate=30/1 ! glupload ! sbfx name=fx scene=%s ! glshader name=after ! " SINK, EXPLOSION);
    GstElement *p = pipeline_of(d), *after = by_name(p, "after");
    const char *const *shaders = gst_gles ? negate_gles : negate_core;
    g_object_set(after, "vertex", shaders[0], "fragment", shaders[1], NULL);
    gst_object_unref(after);
    play_pipeline(p, 12, &negated);
    gst_object_unref(p);
    CHECK(plain.count == 12 && negated.count == 12 && !negated.error[0], "%d, %d frames: %s", plain.count,
          negated.count, negated.error);
    int worst = 0, at = -1;
    for (int i = 0; i < plain.count && i < negated.count; i++) {
        for (size_t k = 0; k < FRAME_BYTES; k++)
            if (k % 4 != 3) plain.frames[i][k] = (uint8_t)(255 - plain.frames[i][k]);
        int n = pixels_differing(plain.frames[i], negated.frames[i], 0);
        if (n > worst) worst = n, at = i;
    }
    CHECK(worst == 0, "frame %d: %d pixels of glshader's picture after sbfx differ from sbfx's own, negated", at,
          worst);
    run_free(&plain);
    run_free(&negated);
}

CHECK_TEST(detail_from_input_feeds_the_video_as_detail)
{
    gst_start();
    run procedural, fed;
    char d[512];
    /* a moving ball: each frame a different slice */
    snprintf(d, sizeof(d), "videotestsrc pattern=ball num-buffers=16 ! video/x-raw,width=96,height=64,"
             "framerate=30/1 ! glupload ! sbfx name=fx scene=%s ! " SINK, EXPLOSION);
    play(d, 16, &procedural);
    snprintf(d, sizeof(d), "videotestsrc pattern=ball num-buffers=16 ! video/x-raw,width=96,height=64,"
             "framerate=30/1 ! glupload ! sbfx name=fx scene=%s detail-from-input=true ! " SINK, EXPLOSION);
    play(d, 16, &fed);
    CHECK(fed.count == 16 && !fed.error[0] && !fed.warning[0], "%d frames: %s %s", fed.count, fed.error, fed.warning);
    /* one frame late: the first frame's read-back is taken with the second */
    CHECK(stat_u64(&fed, "detail-slices") == 15 && stat_u64(&fed, "detail-distinct") >= 10,
          "%llu slices pushed, %llu distinct", (unsigned long long)stat_u64(&fed, "detail-slices"),
          (unsigned long long)stat_u64(&fed, "detail-distinct"));
    int differ = 0;
    for (int i = 0; i < fed.count && i < procedural.count; i++)
        differ += pixels_differing(procedural.frames[i], fed.frames[i], 2) > 0;
    CHECK(differ >= 8, "only %d frames look different with the video's detail", differ);
    CHECK(stat_u64(&fed, "heap-allocs-after-load") == 0, "sbfx allocated after load");
    run_free(&procedural);
    run_free(&fed);
}

CHECK_TEST(background_plane_hides_what_is_behind_it)
{
    gst_start();
    run in, near, far;
    reference(12, &in);
    play_fx("scene=" EXPLOSION " background-distance=3", 12, &near); /* the explosion is about 6.5 m away */
    play_fx("scene=" EXPLOSION " background-distance=20", 12, &far);
    int hidden = 0, shown = 0;
    for (int i = 0; i < in.count && i < near.count && i < far.count; i++) {
        hidden += pixels_differing(in.frames[i], near.frames[i], 1);
        shown += pixels_differing(in.frames[i], far.frames[i], 8);
    }
    CHECK(stat_u64(&near, "frames-rendered") >= 10 && hidden == 0, "%llu frames rendered, %d pixels changed in "
          "front of a plane at 3 m", (unsigned long long)stat_u64(&near, "frames-rendered"), hidden);
    CHECK(shown > 1000, "a plane at 20 m leaves %d pixels changed in 12 frames", shown);
    run_free(&in);
    run_free(&near);
    run_free(&far);
}

static void pull_n(GstElement *p, run *r, int n)
{
    for (int i = 0; i < n; i++) pull(p, r);
}

CHECK_TEST(scene_and_quality_change_while_playing)
{
    gst_start();
    char d[512], dir[] = "/tmp/sbfx-gst-XXXXXX", bad[256];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(bad, sizeof(bad), "%s/broken.cfg", dir);
    FILE *f = fopen(bad, "w");
    fputs("render = {\n  target_scale = 5;\n};\n", f);
    fclose(f);
    GstElement *p = pipeline_of(pipeline_with("sbfx name=fx scene=" EXPLOSION, d, sizeof(d)));
    GstElement *fx = by_name(p, "fx");
    run r;
    memset(&r, 0, sizeof(r));
    gst_element_set_state(p, GST_STATE_PLAYING);
    pull_n(p, &r, 6);
    g_object_set(fx, "scene", "scenes/barrage.cfg", "scale", 8, NULL);
    pull_n(p, &r, 14); /* barrage's timeline from now: explosions at 0, 0.12, 0.24, 0.36 s */
    keep_stats(p, &r);
    char quality[64] = "";
    snprintf(quality, sizeof(quality), "%s", r.stats ? gst_structure_get_string(r.stats, "quality") : "");
    CHECK(stat_u64(&r, "scene-reloads") == 1 && stat_int(&r, "triggers-fired") >= 4 && strstr(quality, "/8/"),
          "reloads %llu, fired %d, quality %s", (unsigned long long)stat_u64(&r, "scene-reloads"),
          stat_int(&r, "triggers-fired"), quality);
    g_object_set(fx, "scene", bad, NULL);
    pull_n(p, &r, 3);
    keep_stats(p, &r);
    drain_bus(p, &r);
    gst_element_set_state(p, GST_STATE_NULL);
    char want[300];
    snprintf(want, sizeof(want), "%s:2", bad);
    CHECK(r.count == 23 && !r.error[0] && strstr(r.warning, want), "%d frames; error \"%s\", warning \"%s\"",
          r.count, r.error, r.warning);
    CHECK(stat_u64(&r, "scene-reloads") == 1, "a broken scene was taken over");
    gst_object_unref(fx);
    gst_object_unref(p);
    run_free(&r);
    unlink(bad);
    rmdir(dir);
}

CHECK_TEST(output_is_the_input_size)
{
    gst_start();
    GError *e = NULL;
    GstElement *p = gst_parse_launch("videotestsrc num-buffers=1 ! video/x-raw,width=96,height=64 ! glupload ! "
                                     "sbfx scene=" EXPLOSION " ! video/x-raw(memory:GLMemory),width=192,height=128 ! "
                                     "fakesink", &e);
    /* GstGLFilter scales; sbfx draws over the picture pixel for pixel: a scaler goes before or after it */
    CHECK(e && strstr(e->message, "could not link sbfx"), "a 96x64 input linked to a 192x128 output: %s",
          e ? e->message : "no error");
    g_clear_error(&e);
    if (p) gst_object_unref(p);
}

/* What the leaks tracer saw created and not destroyed since its tracking began (its
 * activity-start-tracking and activity-get-checkpoint actions), by address: each checkpoint's
 * created objects count up, its destroyed ones down. A checkpoint carries type names and
 * addresses only. get-live-objects is no use here: its list takes over a reference of every
 * object it names, so freeing it destroys objects still in use (GstGL's, from gst_start()'s probe
 * pipeline, were still going away when it was asked once on a loaded machine: 18 objects
 * destroyed under their owners, then GObject's criticals). Objects that were alive before the
 * tracking began and go away during it are not counted. */
typedef struct alive_object {
    int count;
    char type[64];
} alive_object;

static void checkpoint_list(const GstStructure *s, const char *field, int sign, GHashTable *alive)
{
    const GValue *list = s ? gst_structure_get_value(s, field) : NULL;
    for (guint i = 0; list && i < gst_value_list_get_size(list); i++) {
        const GstStructure *o = gst_value_get_structure(gst_value_list_get_value(list, i));
        const char *address = gst_structure_get_string(o, "address"), *type = gst_structure_get_string(o, "type-name");
        if (!address) continue;
        alive_object *a = g_hash_table_lookup(alive, address);
        if (!a && sign < 0) continue; /* alive before the tracking began */
        if (!a) {
            a = g_new0(alive_object, 1);
            g_hash_table_insert(alive, g_strdup(address), a);
        }
        a->count += sign;
        if (sign > 0) snprintf(a->type, sizeof(a->type), "%s", type ? type : "?");
        if (a->count == 0) g_hash_table_remove(alive, address);
    }
}

/* An object GStreamer marks as one that may stay (a class's pad templates and their caps, made
 * when an element of the class is first made): the tracer's own list leaves them out too. It is
 * alive (made and not destroyed since), so its flags can be read. */
static bool may_be_leaked(const char *address, const char *type_name)
{
    void *object = NULL;
    GType type = g_type_from_name(type_name);
    if (sscanf(address, "%p", &object) != 1 || !object || !type) return false;
    if (g_type_is_a(type, G_TYPE_OBJECT)) return GST_OBJECT_FLAG_IS_SET(object, GST_OBJECT_FLAG_MAY_BE_LEAKED);
    return GST_MINI_OBJECT_FLAG_IS_SET(object, GST_MINI_OBJECT_FLAG_MAY_BE_LEAKED);
}

/* A checkpoint into `alive`: how many objects made since the tracking began are alive now, those
 * that may stay left out (and forgotten). */
static int alive_after_checkpoint(GstTracer *leaks, GHashTable *alive)
{
    GstStructure *s = NULL;
    g_signal_emit_by_name(leaks, "activity-get-checkpoint", &s);
    checkpoint_list(s, "objects-created-list", 1, alive);  /* made in the interval (and maybe gone) */
    checkpoint_list(s, "objects-removed-list", -1, alive); /* gone in it */
    if (s) gst_structure_free(s);
    int n = 0;
    GHashTableIter i;
    gpointer key, value;
    g_hash_table_iter_init(&i, alive);
    while (g_hash_table_iter_next(&i, &key, &value)) {
        const alive_object *a = value;
        if (may_be_leaked(key, a->type)) g_hash_table_iter_remove(&i);
        else n += a->count;
    }
    return n;
}

static void print_alive(GHashTable *alive)
{
    GHashTableIter i;
    gpointer key, value;
    int shown = 0;
    g_hash_table_iter_init(&i, alive);
    while (g_hash_table_iter_next(&i, &key, &value) && shown++ < 8)
        printf("#   alive: %s at %s\n", ((alive_object *)value)->type, (const char *)key);
}

CHECK_TEST(no_object_alive_after_200_frames)
{
    setenv("GST_TRACERS", "leaks", 1);
    gst_start();
    GstTracer *leaks = NULL;
    GList *tracers = gst_tracing_get_active_tracers();
    for (GList *t = tracers; t; t = t->next)
        if (strcmp(G_OBJECT_TYPE_NAME(t->data), "GstLeaksTracer") == 0) leaks = gst_object_ref(t->data);
    g_list_free_full(tracers, gst_object_unref);
    if (!leaks) CHECK_SKIP("the leaks tracer is not here (GStreamer's core tracers: libgstcoretracers.so)");
    GHashTable *alive = g_hash_table_new_full(g_str_hash, g_str_equal, g_free, g_free);
    g_signal_emit_by_name(leaks, "activity-start-tracking");
    char d[512];
    snprintf(d, sizeof(d), "videotestsrc num-buffers=200 ! video/x-raw,width=32,height=24 ! glupload ! "
             "sbfx name=fx scene=%s ! gldownload ! fakesink", EXPLOSION);
    GstElement *p = pipeline_of(d);
    gst_element_set_state(p, GST_STATE_PLAYING);
    GstMessage *m = gst_bus_timed_pop_filtered(GST_ELEMENT_BUS(p), 120 * GST_SECOND,
                                               GST_MESSAGE_EOS | GST_MESSAGE_ERROR);
    CHECK(m && GST_MESSAGE_TYPE(m) == GST_MESSAGE_EOS, "the 200 frames did not end with EOS");
    if (m) gst_message_unref(m);
    int during = alive_after_checkpoint(leaks, alive);
    gst_element_set_state(p, GST_STATE_NULL);
    gst_object_unref(p);
    /* GstGL's threads let their objects go after the pipeline's: they have 10 s (a leak never does) */
    int after = alive_after_checkpoint(leaks, alive);
    for (int i = 0; i < 500 && after > 0; i++) {
        g_usleep(20000);
        after = alive_after_checkpoint(leaks, alive);
    }
    if (after) print_alive(alive);
    /* the tracer sees what is alive: one buffer made and not freed */
    GstBuffer *kept = gst_buffer_new();
    int control = alive_after_checkpoint(leaks, alive);
    printf("# objects made by the pipeline: %d alive at its EOS, %d after it went; %d with a buffer left alive\n",
           during, after, control);
    CHECK(during > 0, "the tracer saw no object of the pipeline alive while it played");
    CHECK(after == 0, "%d objects of the pipeline alive after it went", after);
    CHECK(control == after + 1, "the tracer does not see a buffer left alive (%d objects)", control);
    gst_buffer_unref(kept);
    g_signal_emit_by_name(leaks, "activity-stop-tracking");
    g_hash_table_destroy(alive);
    gst_object_unref(leaks);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
