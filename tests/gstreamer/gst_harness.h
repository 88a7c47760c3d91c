/* What the GStreamer element's tests share (tests/gstreamer/test_gst_sbfx.c): GStreamer started
 * headless in each forked test, pipelines run into an appsink with their frames kept, the
 * element's stats, the bus's error. Header-only.
 *
 * The environment comes from tests/gstreamer/env.sh (tests/run.sh): GST_PLUGIN_PATH at the
 * build's libgstsbfx.so, LD_LIBRARY_PATH at its libsbfx.so, a registry of the run's own; and
 * GstGL headless: GST_GL_PLATFORM=egl GST_GL_WINDOW=egl-device (set here when missing). */
#ifndef SBFX_GST_HARNESS_H
#define SBFX_GST_HARNESS_H

#include <gst/app/gstappsink.h>
#include <gst/gl/gl.h>
#include <gst/gst.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

#define W 96
#define H 64
#define FRAME_BYTES ((size_t)W * H * 4)
#define MAX_FRAMES 256
/* the input the element sees: RGBA at 30 fps, a still pattern (no random noise) */
#define SOURCE "videotestsrc pattern=colors ! video/x-raw,width=96,height=64,framerate=30/1 ! glupload"
#define SINK "gldownload ! video/x-raw,format=RGBA ! appsink name=out sync=false max-buffers=4"

typedef struct run {
    int count;
    uint8_t *frames[MAX_FRAMES];
    GstClockTime pts[MAX_FRAMES];
    GstStructure *stats;        /* the element's, after the last frame (NULL without one) */
    char error[1024];           /* the bus's first error, "" without */
    char warning[1024];         /* ... and warning */
} run;

static bool gst_gles; /* GstGL's context is OpenGL ES (GST_GL_API=gles2), else desktop OpenGL */

/* The API of the context the probe pipeline's glupload got. */
static inline void note_api(GstElement *pipeline)
{
    GstElement *up = gst_bin_get_by_name(GST_BIN(pipeline), "up");
    GstGLContext *context = NULL;
    g_object_get(up, "context", &context, NULL);
    gst_gles = context && (gst_gl_context_get_gl_api(context) & GST_GL_API_GLES2);
    gst_clear_object(&context);
    gst_object_unref(up);
}

/* GStreamer, started in this (forked) test; skips the test when GstGL gets no context here. */
static inline void gst_start(void)
{
    setenv("GST_GL_PLATFORM", getenv("GST_GL_PLATFORM") ? getenv("GST_GL_PLATFORM") : "egl", 1);
    setenv("GST_GL_WINDOW", getenv("GST_GL_WINDOW") ? getenv("GST_GL_WINDOW") : "egl-device", 1);
    gst_init(NULL, NULL);
    GstElementFactory *f = gst_element_factory_find("sbfx");
    CHECK(f != NULL, "no element sbfx: GST_PLUGIN_PATH=%s, and libsbfx.so.1 on LD_LIBRARY_PATH=%s?",
          getenv("GST_PLUGIN_PATH"), getenv("LD_LIBRARY_PATH"));
    if (!f) exit(1);
    gst_object_unref(f);
    GError *e = NULL;
    GstElement *p = gst_parse_launch("videotestsrc num-buffers=1 ! glupload name=up ! gldownload ! fakesink", &e);
    if (!p) CHECK_SKIP("gst_parse_launch: %s", e ? e->message : "?");
    gst_element_set_state(p, GST_STATE_PLAYING);
    GstMessage *m = gst_bus_timed_pop_filtered(GST_ELEMENT_BUS(p), 20 * GST_SECOND, GST_MESSAGE_EOS | GST_MESSAGE_ERROR);
    char why[512] = "";
    if (!m || GST_MESSAGE_TYPE(m) == GST_MESSAGE_ERROR) {
        GError *err = NULL;
        if (m) gst_message_parse_error(m, &err, NULL);
        snprintf(why, sizeof(why), "%s", err ? err->message : "no EOS within 20 s");
        g_clear_error(&err);
    }
    if (m) gst_message_unref(m);
    if (!why[0]) note_api(p);
    gst_element_set_state(p, GST_STATE_NULL);
    gst_object_unref(p);
    if (why[0])
        CHECK_SKIP("GstGL gets no context here (GST_GL_PLATFORM=%s GST_GL_WINDOW=%s): %s", getenv("GST_GL_PLATFORM"),
                   getenv("GST_GL_WINDOW"), why);
}

static GstElement *pipeline_of(const char *description)
{
    GError *e = NULL;
    GstElement *p = gst_parse_launch(description, &e);
    CHECK(p && !e, "%s: %s", description, e ? e->message : "?");
    if (!p) exit(1);
    g_clear_error(&e);
    return p;
}

static GstElement *by_name(GstElement *pipeline, const char *name)
{
    return gst_bin_get_by_name(GST_BIN(pipeline), name); /* (transfer full) */
}

/* What the bus says: the first error and warning, into r. */
static inline void drain_bus(GstElement *pipeline, run *r)
{
    GstBus *bus = gst_element_get_bus(pipeline);
    GstMessage *m;
    while ((m = gst_bus_pop_filtered(bus, GST_MESSAGE_ERROR | GST_MESSAGE_WARNING))) {
        GError *e = NULL;
        gchar *debug = NULL;
        bool error = GST_MESSAGE_TYPE(m) == GST_MESSAGE_ERROR;
        if (error) gst_message_parse_error(m, &e, &debug);
        else gst_message_parse_warning(m, &e, &debug);
        char *into = error ? r->error : r->warning;
        if (!into[0]) snprintf(into, sizeof(r->error), "%s (%s)", e ? e->message : "?", debug ? debug : "");
        g_clear_error(&e);
        g_free(debug);
        gst_message_unref(m);
    }
    gst_object_unref(bus);
}

/* The next frame from appsink "out" into r; false at EOS, an error or after 30 s. */
static inline bool pull(GstElement *pipeline, run *r)
{
    GstElement *out = by_name(pipeline, "out");
    GstSample *s = gst_app_sink_try_pull_sample(GST_APP_SINK(out), 30 * GST_SECOND);
    gst_object_unref(out);
    if (!s) return false;
    GstBuffer *b = gst_sample_get_buffer(s);
    GstMapInfo map;
    bool ok = r->count < MAX_FRAMES && gst_buffer_map(b, &map, GST_MAP_READ);
    if (ok) {
        CHECK(map.size >= FRAME_BYTES, "a frame of %zu bytes", map.size);
        r->frames[r->count] = malloc(FRAME_BYTES);
        memcpy(r->frames[r->count], map.data, map.size < FRAME_BYTES ? map.size : FRAME_BYTES);
        r->pts[r->count++] = GST_BUFFER_PTS(b);
        gst_buffer_unmap(b, &map);
    }
    gst_sample_unref(s);
    return ok;
}

static inline void keep_stats(GstElement *pipeline, run *r)
{
    GstElement *fx = by_name(pipeline, "fx");
    if (!fx) return;
    if (r->stats) gst_structure_free(r->stats);
    g_object_get(fx, "stats", &r->stats, NULL);
    gst_object_unref(fx);
}

/* Plays a pipeline built from `description` to its end (or max frames), its frames into r. */
static inline void play_pipeline(GstElement *p, int max, run *r)
{
    memset(r, 0, sizeof(*r));
    gst_element_set_state(p, GST_STATE_PLAYING);
    while (r->count < max && pull(p, r)) {}
    keep_stats(p, r);
    drain_bus(p, r);
    gst_element_set_state(p, GST_STATE_NULL);
}

static inline void play(const char *description, int max, run *r)
{
    GstElement *p = pipeline_of(description);
    play_pipeline(p, max, r);
    gst_object_unref(p);
}

static inline void run_free(run *r)
{
    for (int i = 0; i < r->count; i++) free(r->frames[i]);
    if (r->stats) gst_structure_free(r->stats);
    memset(r, 0, sizeof(*r));
}

static inline guint64 stat_u64(const run *r, const char *field)
{
    guint64 v = 0;
    if (r->stats) gst_structure_get_uint64(r->stats, field, &v);
    return v;
}

static inline int stat_int(const run *r, const char *field)
{
    gint v = 0;
    if (r->stats) gst_structure_get_int(r->stats, field, &v);
    return v;
}

static inline double stat_double(const run *r, const char *field)
{
    gdouble v = 0;
    if (r->stats) gst_structure_get_double(r->stats, field, &v);
    return v;
}

/* Pixels of two frames whose colour differs by more than `tolerance` in any channel. */
static inline int pixels_differing(const uint8_t *a, const uint8_t *b, int tolerance)
{
    int n = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        for (int c = 0; c < 3; c++)
            if (abs((int)a[4 * i + c] - (int)b[4 * i + c]) > tolerance) {
                n++;
                break;
            }
    return n;
}

#endif
