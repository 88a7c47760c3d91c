/* The element on GstGL's thread: the module made and destroyed on GstGL's context, the targets
 * of the negotiated size, each frame's copy, detail and render (gstsbfx.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gstsbfx.h"
#include "video/clip_detail.h"

GST_DEBUG_CATEGORY_EXTERN(gst_sbfx_debug);
#define GST_CAT_DEFAULT gst_sbfx_debug

#define CAMERA_NEAR 0.1 /* m: the projection's near plane (the player's) */

static void module_log(sbfx_log_level level, const char *message, void *user)
{
    GstSbfx *self = user;
    if (level == SBFX_LOG_ERROR) GST_ERROR_OBJECT(self, "%s", message);
    else if (level == SBFX_LOG_WARN) GST_WARNING_OBJECT(self, "%s", message);
    else GST_INFO_OBJECT(self, "%s", message);
}

/* The desc the properties ask for; zero fields take the scene's render settings. */
static sbfx_desc desc_of(GstSbfx *self)
{
    GST_OBJECT_LOCK(self);
    const struct gst_sbfx_settings *s = &self->settings;
    sbfx_desc d = {
        .target_divisor = (int)s->scale,
        .target_format = s->format,
        .upsample = s->upsample,
        .opacity = s->opacity,
        .seed = s->seed,
        .tone_map = s->tone_map,
        .exposure = (float)s->exposure,
        .frame_budget_ms = (float)s->budget_ms,
        .ignore_timeline = !s->timeline,
        .scene = self->scene,
        .log = module_log,
        .log_user = self,
    };
    self->detail_on = s->detail_from_input;
    GST_OBJECT_UNLOCK(self);
    return d;
}

/* A clip the scene names as its detail source, decoded and pushed (docs/detail-clips.md); a clip
 * that does not decode is a warning: procedural detail goes on. Not with detail-from-input. */
static void load_clip(GstSbfx *self)
{
    const char *clip = sbfx_detail_clip(self->fx);
    if (!clip || self->detail_on) return;
    char err[512];
    struct clip_info info;
    if (clip_detail_load(self->fx, clip, &info, err, sizeof(err)) != 0) {
        GST_ELEMENT_WARNING(self, RESOURCE, READ, ("sbfx: %s", err), ("procedural detail instead"));
        return;
    }
    char what[256];
    clip_describe(clip, &info, what, sizeof(what));
    GST_INFO_OBJECT(self, "detail clip %s", what);
}

static gboolean start_input_detail(GstSbfx *self)
{
    int size = 0, frames = 0;
    sbfx_detail_dimensions(self->fx, &size, &frames);
    if (input_detail_start(&self->detail, size, self->error, sizeof(self->error)) != 0) return FALSE;
    if (self->gl.width > 0 && gl_guest_detail_targets(&self->gl, size, self->error, sizeof(self->error)) != 0)
        return FALSE;
    if (!sbfx_wants_live_detail(self->fx))
        GST_INFO_OBJECT(self, "detail-from-input: the video feeds the detail of a scene whose detail source is "
                        "not \"v4l2\"");
    return TRUE;
}

/* Makes the module on the current (GstGL's) context; FALSE with self->error. */
static gboolean make_module(GstSbfx *self)
{
    sbfx_desc desc = desc_of(self);
    sbfx_result r = sbfx_create(&desc, &self->fx);
    if (r != SBFX_OK) {
        snprintf(self->error, sizeof(self->error), "sbfx_create: %s (on %s)", sbfx_result_string(r),
                 (const char *)glGetString(GL_VERSION));
        return FALSE; /* the module's message went to the log: module_log */
    }
    sbfx_get_quality(self->fx, &self->created);
    if (self->detail_on) return start_input_detail(self);
    if (sbfx_wants_live_detail(self->fx))
        GST_WARNING_OBJECT(self, "the scene's detail source is \"v4l2\": set detail-from-input=true to feed it "
                           "from the video (procedural detail meanwhile)");
    load_clip(self);
    return TRUE;
}

gboolean gst_sbfx_gl_start(GstGLBaseFilter *base)
{
    GstSbfx *self = GST_SBFX(base);
    if (self->fx || !self->scene) return TRUE; /* made, or made when the scene is loaded (start) */
    if (make_module(self)) return TRUE;
    GST_ELEMENT_ERROR(self, LIBRARY, INIT, ("sbfx: %s", self->error),
                      ("GstGL's context is %s; sbfx needs OpenGL ES 3.0, or desktop OpenGL 3.3 with "
                       "GL_ARB_ES3_compatibility (GST_GL_API=gles2 asks GstGL for OpenGL ES)",
                       (const char *)glGetString(GL_VERSION)));
    return FALSE;
}

void gst_sbfx_gl_stop(GstGLBaseFilter *base)
{
    GstSbfx *self = GST_SBFX(base);
    sbfx_destroy(self->fx);
    self->fx = NULL;
    input_detail_stop(&self->detail);
    gl_guest_release(&self->gl);
    GST_OBJECT_LOCK(self);
    self->counts.have_module = FALSE;
    GST_OBJECT_UNLOCK(self);
}

/* The window depth of the video: 1 (nothing there) at infinity, else the plane's under the
 * infinite-far projection the camera uses, 1 - near / distance. */
static float background_depth(GstSbfx *self)
{
    GST_OBJECT_LOCK(self);
    double distance = self->settings.background_distance;
    GST_OBJECT_UNLOCK(self);
    if (!(distance > 0.0)) return 1.0f;
    if (distance < 2.0 * CAMERA_NEAR) distance = 2.0 * CAMERA_NEAR;
    return (float)(1.0 - CAMERA_NEAR / distance);
}

static void luma_weights_of(GstSbfx *self, const GstVideoInfo *info)
{
    gdouble kr = 0.2126, kb = 0.0722; /* BT.709, sRGB's primaries: what RGB caps usually mean */
    if (!gst_video_color_matrix_get_Kr_Kb(info->colorimetry.matrix, &kr, &kb)) kr = 0.2126, kb = 0.0722;
    input_detail_set_weights(&self->detail, kr, kb);
}

gboolean gst_sbfx_gl_set_caps(GstGLBaseFilter *base, GstCaps *incaps, GstCaps *outcaps)
{
    /* GstGLFilter's own would make a framebuffer with a depth buffer of the frame's size that
     * this element never draws with: its framebuffers are gl_guest's */
    GstSbfx *self = GST_SBFX(base);
    const GstVideoInfo *info = &GST_GL_FILTER(base)->out_info;
    int w = GST_VIDEO_INFO_WIDTH(info), h = GST_VIDEO_INFO_HEIGHT(info);
    stream_clock_set_rate(&self->clock, GST_VIDEO_INFO_FPS_N(info), GST_VIDEO_INFO_FPS_D(info));
    if (gl_guest_targets(&self->gl, w, h, background_depth(self), self->error, sizeof(self->error)) != 0 ||
        (self->detail_on && self->detail.size > 0 &&
         gl_guest_detail_targets(&self->gl, self->detail.size, self->error, sizeof(self->error)) != 0)) {
        GST_ELEMENT_ERROR(self, RESOURCE, FAILED, ("sbfx: %s", self->error), (NULL));
        return FALSE;
    }
    luma_weights_of(self, &GST_GL_FILTER(base)->in_info);
    GST_OBJECT_LOCK(self);
    self->width = w, self->height = h;
    GST_OBJECT_UNLOCK(self);
    GST_INFO_OBJECT(self, "%dx%d at %d/%d fps", w, h, GST_VIDEO_INFO_FPS_N(info), GST_VIDEO_INFO_FPS_D(info));
    return TRUE;
}

/* ---- per frame ---- */

/* The input's luma, read back a frame ago, pushed as the next detail slice. */
static void feed_detail(GstSbfx *self, GLuint input)
{
    int taken = gl_guest_detail(&self->gl, input, input_detail_take, &self->detail);
    if (taken < 0) GST_WARNING_OBJECT(self, "detail-from-input: a GL error reading the frame back");
    if (taken <= 0 || !self->detail.ready) return;
    self->detail.ready = FALSE;
    if (sbfx_detail_push_slice(self->fx, self->detail.slice, self->detail.size) != SBFX_OK) {
        GST_ELEMENT_WARNING(self, LIBRARY, SETTINGS, ("sbfx: detail-from-input: %s", sbfx_last_error(self->fx)),
                            ("the video no longer feeds the detail"));
        self->detail_on = FALSE; /* said once */
        return;
    }
    GST_OBJECT_LOCK(self);
    self->counts.detail_slices++;
    self->counts.detail_distinct = self->detail.distinct;
    GST_OBJECT_UNLOCK(self);
}

/* The camera's projection for GstGL's textures, whose row 0 is the picture's top: y flipped. */
static void frame_of(GstSbfx *self, GLuint input, sbfx_frame *f)
{
    *f = (sbfx_frame){.scene_color_texture = input, .scene_depth_texture = self->gl.depth_texture,
                      .out_framebuffer = self->gl.draw_fbo, .width = self->gl.width, .height = self->gl.height};
    gst_sbfx_camera(self, TRUE, f->view, f->projection);
}

static void count_rendered(GstSbfx *self, double ms)
{
    GST_OBJECT_LOCK(self);
    struct gst_sbfx_counts *c = &self->counts;
    c->rendered++;
    c->last_ms = ms;
    c->sum_ms += ms;
    if (ms > c->max_ms) c->max_ms = ms;
    sbfx_stats(self->fx, &c->module);
    c->have_module = TRUE;
    GST_OBJECT_UNLOCK(self);
}

gboolean gst_sbfx_filter_texture(GstGLFilter *filter, GstGLMemory *input, GstGLMemory *output)
{
    GstSbfx *self = GST_SBFX(filter);
    gint64 t0 = g_get_monotonic_time();
    GLuint in = gst_gl_memory_get_texture_id(input), out = gst_gl_memory_get_texture_id(output);
    if (self->detail_on) feed_detail(self, in);
    if (gl_guest_copy(&self->gl, in, out) != 0) {
        GST_ELEMENT_ERROR(self, RESOURCE, FAILED, ("sbfx: copying the frame (texture %u into %u) failed", in, out),
                          ("a GL error: glBlitFramebuffer between two %dx%d RGBA textures", self->gl.width,
                           self->gl.height));
        return FALSE;
    }
    sbfx_frame frame;
    frame_of(self, in, &frame);
    sbfx_result r = sbfx_render(self->fx, &frame);
    gl_guest_detach(&self->gl);
    if (r != SBFX_OK) {
        GST_ELEMENT_ERROR(self, RESOURCE, FAILED, ("sbfx: %s", sbfx_last_error(self->fx)), ("sbfx_render"));
        return FALSE;
    }
    count_rendered(self, self->frame_cpu_ms + (double)(g_get_monotonic_time() - t0) / 1000.0);
    return TRUE;
}

/* ---- what the streaming thread asks of GstGL's thread ---- */

struct gl_call {
    GstSbfx *self;
    const sbfx_scene *scene;
    const sbfx_quality *quality;
    GLuint texture;
    gboolean ok;
};

static void call_restart(GstGLContext *context, gpointer data)
{
    struct gl_call *c = data;
    GstSbfx *self = c->self;
    c->ok = sbfx_restart(self->fx, self->scene) == SBFX_OK;
    if (!c->ok) snprintf(self->error, sizeof(self->error), "%s", sbfx_last_error(self->fx));
    else load_clip(self); /* pushed detail is not kept */
}

static void call_set_scene(GstGLContext *context, gpointer data)
{
    struct gl_call *c = data;
    GstSbfx *self = c->self;
    c->ok = sbfx_set_scene(self->fx, c->scene) == SBFX_OK;
    if (!c->ok) {
        snprintf(self->error, sizeof(self->error), "%s", sbfx_last_error(self->fx));
        return;
    }
    sbfx_get_quality(self->fx, &self->created);
    load_clip(self);
}

static void call_set_quality(GstGLContext *context, gpointer data)
{
    struct gl_call *c = data;
    c->ok = sbfx_set_quality(c->self->fx, c->quality) == SBFX_OK;
    if (!c->ok) snprintf(c->self->error, sizeof(c->self->error), "%s", sbfx_last_error(c->self->fx));
}

static void call_make(GstGLContext *context, gpointer data)
{
    struct gl_call *c = data;
    c->ok = make_module(c->self);
}

static void call_detail(GstGLContext *context, gpointer data)
{
    struct gl_call *c = data;
    feed_detail(c->self, c->texture);
    c->ok = TRUE;
}

static gboolean run(GstSbfx *self, GstGLContextThreadFunc fn, struct gl_call *c)
{
    GstGLContext *context = gst_gl_base_filter_get_gl_context(GST_GL_BASE_FILTER(self));
    if (!context) {
        snprintf(self->error, sizeof(self->error), "no GL context");
        return FALSE;
    }
    c->self = self;
    gst_gl_context_thread_add(context, fn, c);
    gst_object_unref(context);
    return c->ok;
}

gboolean gst_sbfx_run_make(GstSbfx *self)
{
    struct gl_call c = {0};
    if (!self->scene) {
        snprintf(self->error, sizeof(self->error), "no scene loaded");
        return FALSE;
    }
    return run(self, call_make, &c);
}

gboolean gst_sbfx_run_restart(GstSbfx *self)
{
    struct gl_call c = {0};
    return run(self, call_restart, &c);
}

gboolean gst_sbfx_run_set_scene(GstSbfx *self, const sbfx_scene *scene)
{
    struct gl_call c = {.scene = scene};
    return run(self, call_set_scene, &c);
}

gboolean gst_sbfx_run_set_quality(GstSbfx *self, const sbfx_quality *q)
{
    struct gl_call c = {.quality = q};
    return run(self, call_set_quality, &c);
}

gboolean gst_sbfx_run_detail(GstSbfx *self, GstBuffer *input)
{
    GstGLFilter *filter = GST_GL_FILTER(self);
    GstVideoFrame frame;
    if (!gst_video_frame_map(&frame, &filter->in_info, input, GST_MAP_READ | GST_MAP_GL)) {
        snprintf(self->error, sizeof(self->error), "detail-from-input: the input buffer does not map as GL memory");
        return FALSE;
    }
    GstGLSyncMeta *sync = gst_buffer_get_gl_sync_meta(input);
    GstGLContext *context = gst_gl_base_filter_get_gl_context(GST_GL_BASE_FILTER(self));
    if (sync && context) gst_gl_sync_meta_wait(sync, context);
    gst_clear_object(&context);
    struct gl_call c = {.texture = *(guint *)frame.data[0]};
    gboolean ok = run(self, call_detail, &c);
    gst_video_frame_unmap(&frame);
    return ok;
}

sbfx_quality gst_sbfx_wanted_quality(GstSbfx *self)
{
    sbfx_quality q = self->created;
    GST_OBJECT_LOCK(self);
    const struct gst_sbfx_settings *s = &self->settings;
    if (s->scale) q.target_divisor = (int)s->scale;
    if (s->opacity) q.opacity = s->opacity;
    if (s->upsample) q.upsample = s->upsample;
    if (s->format) q.target_format = s->format;
    GST_OBJECT_UNLOCK(self);
    return q;
}
