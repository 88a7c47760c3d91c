/* The element on the streaming thread: each buffer's time, triggers, camera and whether it goes
 * on unchanged; flushes and taps (gstsbfx.h). */
#include <gst/video/navigation.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ground_tap.h"
#include "gstsbfx.h"

GST_DEBUG_CATEGORY_EXTERN(gst_sbfx_debug);
#define GST_CAT_DEFAULT gst_sbfx_debug

#define CAMERA_NEAR 0.1f     /* m, as the player's camera */
#define MAX_UPDATE 0.25      /* s: what one sbfx_update takes at most */

static GstBaseTransformClass *gl_filter_class(void)
{
    return GST_BASE_TRANSFORM_CLASS(g_type_class_peek(GST_TYPE_GL_FILTER));
}

/* ---- the camera: the scene file's, on the module's clock ---- */

void gst_sbfx_camera(GstSbfx *self, gboolean for_texture, float view[16], float projection[16])
{
    const sbfx_scene_camera *c = &self->camera;
    /* the orbit's angle reduced in double before it becomes a float (docs/design.md §7) */
    double degrees = fmod(c->azimuth + c->orbit * sbfx_elapsed(self->fx), 360.0), a = degrees * G_PI / 180.0;
    const float eye[3] = {c->target[0] + c->distance * (float)sin(a), c->height,
                          c->target[2] + c->distance * (float)cos(a)};
    const float up[3] = {0.0f, 1.0f, 0.0f};
    sbfx_look_at(view, eye, c->target, up);
    const GstVideoInfo *info = &GST_GL_FILTER(self)->out_info;
    double aspect = (double)GST_VIDEO_INFO_WIDTH(info) * GST_VIDEO_INFO_PAR_N(info) /
                    ((double)GST_VIDEO_INFO_HEIGHT(info) * GST_VIDEO_INFO_PAR_D(info));
    sbfx_perspective(projection, c->fov * (float)G_PI / 180.0f, isfinite(aspect) && aspect > 0 ? (float)aspect : 1.0f,
                     CAMERA_NEAR, INFINITY);
    if (for_texture) projection[5] = -projection[5]; /* GstGL's row 0 is the picture's top */
}

/* ---- triggers ---- */

static void name_effects(const sbfx *fx, char *out, size_t n)
{
    out[0] = '\0';
    for (int i = 0; sbfx_effect_name(fx, i); i++) {
        size_t used = strlen(out);
        snprintf(out + used, n - used, "%s%s", i ? ", " : "", sbfx_effect_name(fx, i));
    }
}

static void start_one(GstSbfx *self, const struct pending_entry *e)
{
    const char *effect = e->kind == PENDING_TAP ? sbfx_effect_name(self->fx, 0) : e->effect;
    sbfx_result r = effect ? sbfx_trigger(self->fx, effect, e->position) : SBFX_ERR_UNKNOWN_EFFECT;
    GST_OBJECT_LOCK(self);
    if (r != SBFX_OK) self->counts.triggers_failed++;
    else if (e->kind == PENDING_TAP) self->counts.taps++;
    GST_OBJECT_UNLOCK(self);
    if (r == SBFX_ERR_UNKNOWN_EFFECT) {
        char names[256];
        name_effects(self->fx, names, sizeof(names));
        GST_ELEMENT_WARNING(self, STREAM, FAILED, ("sbfx: trigger \"%s\": the scene has no such effect",
                            effect ? effect : "(none)"), ("its effects: %s", names));
    } else if (r != SBFX_OK) {
        GST_WARNING_OBJECT(self, "trigger \"%s\": %s", effect, sbfx_last_error(self->fx));
    } else {
        GST_INFO_OBJECT(self, "%s \"%s\" at (%.2f, %.2f, %.2f)", e->kind == PENDING_TAP ? "tap:" : "trigger", effect,
                        e->position[0], e->position[1], e->position[2]);
    }
}

/* Everything the signal and taps queued since the last buffer, started now: within the frame
 * interval that ends at this buffer, so this buffer already shows it. */
static void start_pending(GstSbfx *self)
{
    struct pending_entry batch[PENDING_MAX];
    int n = 0;
    GST_OBJECT_LOCK(self);
    while (n < PENDING_MAX && pending_pop(&self->pending, &batch[n])) n++;
    GST_OBJECT_UNLOCK(self);
    for (int i = 0; i < n; i++) start_one(self, &batch[i]);
}

/* ---- time ---- */

static guint64 running_time_of(GstBaseTransform *bt, GstBuffer *input)
{
    GstClockTime ts = GST_BUFFER_PTS_IS_VALID(input) ? GST_BUFFER_PTS(input) : GST_BUFFER_DTS(input);
    if (bt->segment.format != GST_FORMAT_TIME || !GST_CLOCK_TIME_IS_VALID(ts)) return STREAM_CLOCK_NONE;
    GstClockTime rt = gst_segment_to_running_time(&bt->segment, GST_FORMAT_TIME, ts);
    return GST_CLOCK_TIME_IS_VALID(rt) ? rt : STREAM_CLOCK_NONE;
}

static gboolean update(GstSbfx *self, double dt)
{
    for (; dt > MAX_UPDATE; dt -= MAX_UPDATE)
        if (sbfx_update(self->fx, MAX_UPDATE) != SBFX_OK) return FALSE;
    return sbfx_update(self->fx, dt) == SBFX_OK;
}

/* The module brought to this buffer's running time, with what was triggered meanwhile. */
static gboolean advance(GstSbfx *self, GstBaseTransform *bt, GstBuffer *input)
{
    guint64 rt = running_time_of(bt, input);
    GstClockTime duration = GST_BUFFER_DURATION(input);
    uint64_t step = stream_clock_advance(&self->clock, rt, GST_CLOCK_TIME_IS_VALID(duration) ? duration
                                                                                               : STREAM_CLOCK_NONE);
    start_pending(self);
    if (!update(self, (double)step * 1e-9)) {
        GST_ELEMENT_ERROR(self, LIBRARY, FAILED, ("sbfx: %s", sbfx_last_error(self->fx)), ("sbfx_update"));
        return FALSE;
    }
    float view[16], projection[16];
    gst_sbfx_camera(self, FALSE, view, projection);
    GST_OBJECT_LOCK(self);
    memcpy(self->view, view, sizeof(view));
    memcpy(self->projection, projection, sizeof(projection));
    self->counts.running_time = rt == STREAM_CLOCK_NONE ? -1.0 : (double)rt * 1e-9;
    self->counts.elapsed = sbfx_elapsed(self->fx);
    self->counts.untimed = self->clock.untimed;
    self->counts.clamped = self->clock.clamped;
    GST_OBJECT_UNLOCK(self);
    return TRUE;
}

/* ---- property changes taken over between frames, and restarts ---- */

/* A new scene file while playing: loaded and taken over, or reported with the old one kept. */
static void take_new_scene(GstSbfx *self, const gchar *path)
{
    char err[1024];
    sbfx_scene *scene = NULL;
    if (!path || sbfx_scene_load(path, &scene, err, sizeof(err)) != SBFX_OK) {
        GST_ELEMENT_WARNING(self, RESOURCE, SETTINGS, ("sbfx: scene %s", path ? err : "(none)"),
                            ("the scene playing goes on"));
        return;
    }
    if (!gst_sbfx_run_set_scene(self, scene)) {
        GST_ELEMENT_WARNING(self, LIBRARY, SETTINGS, ("sbfx: scene %s: %s", path, self->error),
                            ("the scene playing goes on"));
        sbfx_scene_free(scene);
        return;
    }
    sbfx_scene_free(self->scene);
    self->scene = scene;
    sbfx_scene_camera_get(scene, &self->camera);
    GST_OBJECT_LOCK(self);
    self->counts.scene_reloads++;
    self->quality_changed = TRUE; /* the quality properties over the new scene's */
    GST_OBJECT_UNLOCK(self);
}

static void apply_changes(GstSbfx *self)
{
    GST_OBJECT_LOCK(self);
    gboolean scene_changed = self->scene_changed;
    gchar *path = scene_changed ? g_strdup(self->settings.scene) : NULL;
    self->scene_changed = FALSE;
    GST_OBJECT_UNLOCK(self);
    if (scene_changed) take_new_scene(self, path);
    g_free(path);
    if (self->restart_due) {
        self->restart_due = FALSE;
        if (gst_sbfx_run_restart(self)) {
            GST_OBJECT_LOCK(self);
            self->counts.restarts++;
            GST_OBJECT_UNLOCK(self);
        } else {
            GST_ELEMENT_WARNING(self, LIBRARY, FAILED, ("sbfx: restart after a seek: %s", self->error), (NULL));
        }
    }
    GST_OBJECT_LOCK(self);
    gboolean quality_changed = self->quality_changed;
    self->quality_changed = FALSE;
    GST_OBJECT_UNLOCK(self);
    if (!quality_changed) return;
    sbfx_quality q = gst_sbfx_wanted_quality(self);
    if (!gst_sbfx_run_set_quality(self, &q))
        GST_ELEMENT_WARNING(self, LIBRARY, SETTINGS, ("sbfx: quality: %s", self->error), ("the quality is kept"));
}

/* ---- the buffer ---- */

static void count_frame(GstSbfx *self, gboolean forwarded)
{
    GST_OBJECT_LOCK(self);
    self->counts.frames++;
    if (forwarded) {
        self->counts.forwarded++;
        sbfx_stats(self->fx, &self->counts.module);
        self->counts.have_module = TRUE;
    }
    GST_OBJECT_UNLOCK(self);
}

GstFlowReturn gst_sbfx_prepare_output_buffer(GstBaseTransform *bt, GstBuffer *input, GstBuffer **output)
{
    GstSbfx *self = GST_SBFX(bt);
    if (!self->fx && !gst_sbfx_run_make(self)) {
        GST_ELEMENT_ERROR(self, LIBRARY, INIT, ("sbfx: %s", self->error), (NULL));
        return GST_FLOW_ERROR;
    }
    gint64 t0 = g_get_monotonic_time();
    apply_changes(self);
    if (!advance(self, bt, input)) return GST_FLOW_ERROR;
    self->frame_idle = sbfx_idle(self->fx);
    self->frame_cpu_ms = (double)(g_get_monotonic_time() - t0) / 1000.0;
    count_frame(self, self->frame_idle);
    if (!self->frame_idle) return gl_filter_class()->prepare_output_buffer(bt, input, output);
    /* no effect live: the buffer goes on as it came (its texture, its metadata, no copy) */
    if (self->detail_on && !gst_sbfx_run_detail(self, input))
        GST_WARNING_OBJECT(self, "%s", self->error);
    *output = input;
    return GST_FLOW_OK;
}

GstFlowReturn gst_sbfx_transform(GstBaseTransform *bt, GstBuffer *input, GstBuffer *output)
{
    if (output == input) return GST_FLOW_OK; /* forwarded: nothing to draw */
    return gl_filter_class()->transform(bt, input, output);
}

/* ---- events ---- */

gboolean gst_sbfx_sink_event(GstBaseTransform *bt, GstEvent *event)
{
    GstSbfx *self = GST_SBFX(bt);
    if (GST_EVENT_TYPE(event) == GST_EVENT_FLUSH_STOP) {
        /* a flushing seek: the running time starts again, and so does the effect */
        stream_clock_reset(&self->clock);
        self->restart_due = TRUE;
    }
    return gl_filter_class()->sink_event(bt, event);
}

/* A tap or a click at (x, y) of the picture: the scene's first effect where its ray meets the
 * ground, seen by the camera of the last frame (the one on the screen). */
static void queue_tap(GstSbfx *self, double x, double y)
{
    struct pending_entry e = {.kind = PENDING_TAP};
    GST_OBJECT_LOCK(self);
    if (ground_tap(x, y, self->width, self->height, self->view, self->projection, e.position))
        pending_push(&self->pending, &e);
    else
        self->counts.taps_missed++;
    GST_OBJECT_UNLOCK(self);
}

gboolean gst_sbfx_src_event(GstBaseTransform *bt, GstEvent *event)
{
    GstSbfx *self = GST_SBFX(bt);
    if (GST_EVENT_TYPE(event) == GST_EVENT_NAVIGATION) {
        gdouble x = 0, y = 0, pressure = 0;
        gint button = 0;
        guint id = 0;
        switch (gst_navigation_event_get_type(event)) {
        case GST_NAVIGATION_EVENT_MOUSE_BUTTON_PRESS:
            if (gst_navigation_event_parse_mouse_button_event(event, &button, &x, &y) && button == 1)
                queue_tap(self, x, y);
            break;
        case GST_NAVIGATION_EVENT_TOUCH_DOWN:
            if (gst_navigation_event_parse_touch_event(event, &id, &x, &y, &pressure)) queue_tap(self, x, y);
            break;
        default: break;
        }
    }
    return gl_filter_class()->src_event(bt, event); /* upstream too: others may want it */
}
