/* GstSbfx: sbfx as a GStreamer GL video filter, the element `sbfx` (docs/hosts/gstreamer.md).
 *
 *   gst-launch-1.0 v4l2src ! videoconvert ! glupload ! sbfx scene=explosion.cfg ! glimagesink
 *
 * A GstGLFilter: RGBA textures in GstGL's context in, the same size out. sbfx is created on
 * GstGL's context (OpenGL ES 3.0, or desktop OpenGL 3.3 core with GL_ARB_ES3_compatibility) when
 * the context is known, and composites its effects over each frame, seen through the scene
 * file's camera; the video is the background at infinity (or a plane at background-distance).
 * The effect's clock is the buffers' running time (stream_clock.h). A frame with no effect live
 * goes on as it came, the same buffer (no copy, no pass). Triggers: the `trigger` action signal,
 * the scene's timeline, and taps or clicks on the sink's window (navigation events), which start
 * the scene's first effect where the tap's ray meets the ground y = 0.
 *
 * Threads: properties, the signal and navigation events may come from any thread and only
 * touch what the object lock guards; the module lives on the streaming thread, which does all
 * GL work on GstGL's thread through gst_gl_context_thread_add, waiting for it. */
#ifndef SBFX_GST_SBFX_H
#define SBFX_GST_SBFX_H

#include <gst/gl/gl.h>
#include <gst/gst.h>

#include "gl_guest.h"
#include "input_detail.h"
#include "pending.h"
#include "sbfx.h"
#include "stream_clock.h"

G_BEGIN_DECLS

#define GST_TYPE_SBFX (gst_sbfx_get_type())
#define GST_SBFX(obj) (G_TYPE_CHECK_INSTANCE_CAST((obj), GST_TYPE_SBFX, GstSbfx))
#define GST_SBFX_CLASS(klass) (G_TYPE_CHECK_CLASS_CAST((klass), GST_TYPE_SBFX, GstSbfxClass))

typedef struct _GstSbfx GstSbfx;
typedef struct _GstSbfxClass GstSbfxClass;

/* What the properties say (the object lock). Zero, FALSE or NULL: the scene's own setting. */
struct gst_sbfx_settings {
    gchar *scene;                  /* scene file (required) */
    guint scale;                   /* particle target divisor: 0 (the scene's), 1, 2, 4, 8 */
    sbfx_opacity_mode opacity;
    sbfx_upsample upsample;
    sbfx_target_format format;
    sbfx_tone_map tone_map;
    gdouble exposure;
    gdouble budget_ms;
    guint seed;
    gboolean timeline;             /* fire the scene's timeline (default TRUE) */
    gboolean detail_from_input;
    gdouble background_distance;   /* metres; 0: at infinity */
};

/* What the element counts for `stats` (the object lock). */
struct gst_sbfx_counts {
    guint64 frames;                /* buffers processed */
    guint64 rendered;              /* ... that sbfx drew into (a copy and its passes) */
    guint64 forwarded;             /* ... that went on unchanged, the same buffer */
    guint64 taps;                  /* navigation taps that started an effect */
    guint64 taps_missed;           /* ... that met no ground (the sky) */
    guint64 triggers_failed;       /* signal or tap triggers sbfx refused (unknown effect, full pool) */
    guint64 restarts;              /* flushing seeks: the module restarted */
    guint64 scene_reloads;         /* scene property changes taken over while playing */
    guint64 detail_slices;         /* input frames pushed as detail slices */
    guint64 detail_distinct;       /* ... that differed from the one before */
    guint64 untimed;               /* buffers without a running time (stream_clock.h) */
    guint64 clamped;               /* running-time jumps cut to STREAM_CLOCK_MAX_STEP_NS */
    gdouble last_ms, max_ms, sum_ms; /* sbfx's CPU time per rendered frame: copy, update, render */
    gdouble running_time;          /* of the last buffer, s */
    gdouble elapsed;               /* sbfx_elapsed() after it */
    sbfx_counters module;          /* sbfx_stats() after the last frame */
    gboolean have_module;
};

struct _GstSbfx {
    GstGLFilter parent;

    /* the object lock */
    struct gst_sbfx_settings settings;
    gboolean scene_changed;        /* the scene property changed while playing */
    gboolean quality_changed;      /* a quality property changed while playing */
    struct pending pending;
    float view[16], projection[16]; /* the last frame's camera, for taps */
    gint width, height;
    struct gst_sbfx_counts counts;

    /* the streaming thread (and the GL thread it waits for) */
    sbfx_scene *scene;             /* loaded at start, kept for restarts */
    sbfx *fx;                      /* made in gl_start on GstGL's context */
    sbfx_quality created;          /* the quality fx was made with: a quality property set to
                                      its default returns to this */
    sbfx_scene_camera camera;
    struct stream_clock clock;
    gboolean restart_due;          /* a flush came: restart at the next buffer */
    gboolean frame_idle;           /* this buffer goes on unchanged */
    struct gl_guest gl;
    struct input_detail detail;
    gboolean detail_on;
    gdouble frame_cpu_ms;          /* this buffer's update time, before the render adds its own */
    gchar error[512];              /* a GL-thread step's failure, for the element's message */
};

struct _GstSbfxClass {
    GstGLFilterClass parent_class;
    /* the `trigger` action signal's class handler */
    void (*trigger)(GstSbfx *self, const gchar *effect, gdouble x, gdouble y, gdouble z);
};

GType gst_sbfx_get_type(void);

/* gstsbfx_gl.c: on GstGL's thread */
gboolean gst_sbfx_gl_start(GstGLBaseFilter *base);
void gst_sbfx_gl_stop(GstGLBaseFilter *base);
gboolean gst_sbfx_gl_set_caps(GstGLBaseFilter *base, GstCaps *incaps, GstCaps *outcaps);
gboolean gst_sbfx_filter_texture(GstGLFilter *filter, GstGLMemory *input, GstGLMemory *output);
/* from the streaming thread: each runs on GstGL's thread and waits; FALSE with self->error set */
gboolean gst_sbfx_run_make(GstSbfx *self); /* the module, when gl_start came before the scene */
gboolean gst_sbfx_run_restart(GstSbfx *self);
gboolean gst_sbfx_run_set_scene(GstSbfx *self, const sbfx_scene *scene);
gboolean gst_sbfx_run_set_quality(GstSbfx *self, const sbfx_quality *q);
gboolean gst_sbfx_run_detail(GstSbfx *self, GstBuffer *input);
/* the quality the properties ask for over the one fx was made with */
sbfx_quality gst_sbfx_wanted_quality(GstSbfx *self);

/* gstsbfx_stream.c: the streaming thread */
GstFlowReturn gst_sbfx_prepare_output_buffer(GstBaseTransform *bt, GstBuffer *input, GstBuffer **output);
GstFlowReturn gst_sbfx_transform(GstBaseTransform *bt, GstBuffer *input, GstBuffer *output);
gboolean gst_sbfx_sink_event(GstBaseTransform *bt, GstEvent *event);
gboolean gst_sbfx_src_event(GstBaseTransform *bt, GstEvent *event);
/* the camera at the module's time into view and projection (the frame's, y flipped for GstGL's
 * textures when `for_texture`) */
void gst_sbfx_camera(GstSbfx *self, gboolean for_texture, float view[16], float projection[16]);

/* gstsbfx_stats.c */
GstStructure *gst_sbfx_stats(GstSbfx *self);

G_END_DECLS

#endif
