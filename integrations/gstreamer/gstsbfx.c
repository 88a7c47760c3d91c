/* The element's type: properties, the `trigger` signal, the scene loaded at start (gstsbfx.h). */
#include "gstsbfx.h"

#include <string.h>

GST_DEBUG_CATEGORY(gst_sbfx_debug);
#define GST_CAT_DEFAULT gst_sbfx_debug

enum {
    PROP_0,
    PROP_SCENE,
    PROP_SCALE,
    PROP_OPACITY,
    PROP_UPSAMPLE,
    PROP_FORMAT,
    PROP_TONE_MAP,
    PROP_EXPOSURE,
    PROP_BUDGET_MS,
    PROP_SEED,
    PROP_TIMELINE,
    PROP_DETAIL_FROM_INPUT,
    PROP_BACKGROUND_DISTANCE,
    PROP_STATS,
};

enum { SIGNAL_TRIGGER, SIGNAL_COUNT };
static guint signals[SIGNAL_COUNT];

#define gst_sbfx_parent_class parent_class
G_DEFINE_TYPE(GstSbfx, gst_sbfx, GST_TYPE_GL_FILTER);

/* ---- the enum properties: the player's flags' names (sbfx-play --help) ---- */

static GType opacity_type(void)
{
    static const GEnumValue values[] = {
        {SBFX_OPACITY_DEFAULT, "The scene's (render.opacity; exact without one)", "default"},
        {SBFX_OPACITY_PLANAR, "Classic billboard: radial profile only", "planar"},
        {SBFX_OPACITY_SOFT, "Soft particles: planar faded near the depth", "soft"},
        {SBFX_OPACITY_SPHERICAL, "The seed's spherical billboards", "spherical"},
        {SBFX_OPACITY_EXACT, "The exact integral along the perspective ray", "exact"},
        {0, NULL, NULL},
    };
    static GType type;
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstSbfxOpacity", values));
    return type;
}

static GType upsample_type(void)
{
    static const GEnumValue values[] = {
        {SBFX_UPSAMPLE_DEFAULT, "The scene's (nearest-depth without one)", "default"},
        {SBFX_UPSAMPLE_BILINEAR, "Bilinear", "bilinear"},
        {SBFX_UPSAMPLE_NEAREST_DEPTH, "Nearest depth: no halos at opaque edges", "nearest-depth"},
        {SBFX_UPSAMPLE_MIXED, "Mixed resolution: nearest depth, refined at full resolution at edges", "mixed"},
        {0, NULL, NULL},
    };
    static GType type;
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstSbfxUpsample", values));
    return type;
}

static GType format_type(void)
{
    static const GEnumValue values[] = {
        {SBFX_FORMAT_DEFAULT, "RGBA16F where it is colour-renderable, else RGBA8", "auto"},
        {SBFX_FORMAT_RGBA8, "RGBA8", "rgba8"},
        {SBFX_FORMAT_RGBA16F, "RGBA16F", "rgba16f"},
        {SBFX_FORMAT_RGBA32F, "RGBA32F", "rgba32f"},
        {0, NULL, NULL},
    };
    static GType type;
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstSbfxFormat", values));
    return type;
}

static GType tone_map_type(void)
{
    static const GEnumValue values[] = {
        {SBFX_TONE_MAP_DEFAULT, "The scene's (filmic without one)", "default"},
        {SBFX_TONE_MAP_NONE, "Light added as computed, each channel clips", "none"},
        {SBFX_TONE_MAP_HUE_PRESERVING, "Hue kept, scaled into the room the picture leaves", "hue-preserving"},
        {SBFX_TONE_MAP_PER_CHANNEL, "Per channel: bright colours turn white", "per-channel"},
        {SBFX_TONE_MAP_FILMIC, "A path to white for fire", "filmic"},
        {0, NULL, NULL},
    };
    static GType type;
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstSbfxToneMap", values));
    return type;
}

/* ---- properties ---- */

#define MUTABLE_READY (G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_READY)
#define MUTABLE_PLAYING (G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_PLAYING)

static void install_properties(GObjectClass *oc)
{
    g_object_class_install_property(oc, PROP_SCENE, g_param_spec_string("scene", "Scene",
        "Scene file (docs/scene-format.md), required. Set while playing, the new file is loaded at the next "
        "frame; a file that does not load is reported (file:line) and the old scene plays on", NULL,
        MUTABLE_PLAYING));
    g_object_class_install_property(oc, PROP_SCALE, g_param_spec_uint("scale", "Scale",
        "Particle target = frame size / scale per axis: 1, 2, 4 or 8 (0: the scene's, else 4)", 0, 8, 0,
        MUTABLE_PLAYING));
    g_object_class_install_property(oc, PROP_OPACITY, g_param_spec_enum("opacity", "Opacity",
        "Opacity model of a particle", opacity_type(), SBFX_OPACITY_DEFAULT, MUTABLE_PLAYING));
    g_object_class_install_property(oc, PROP_UPSAMPLE, g_param_spec_enum("upsample", "Upsample",
        "Upsampling of the particle target", upsample_type(), SBFX_UPSAMPLE_DEFAULT, MUTABLE_PLAYING));
    g_object_class_install_property(oc, PROP_FORMAT, g_param_spec_enum("format", "Format",
        "Particle target format", format_type(), SBFX_FORMAT_DEFAULT, MUTABLE_PLAYING));
    g_object_class_install_property(oc, PROP_TONE_MAP, g_param_spec_enum("tone-map", "Tone map",
        "How the particles' light meets the picture (docs/look-fire.md)", tone_map_type(), SBFX_TONE_MAP_DEFAULT,
        MUTABLE_READY));
    g_object_class_install_property(oc, PROP_EXPOSURE, g_param_spec_double("exposure", "Exposure",
        "Scale of the particles' light, 0.01 .. 100 (0: the scene's, else 1)", 0.0, 100.0, 0.0, MUTABLE_READY));
    g_object_class_install_property(oc, PROP_BUDGET_MS, g_param_spec_double("budget-ms", "Frame budget (ms)",
        "sbfx's GPU time per frame: above it sbfx walks down a quality ladder (0: the scene's, else none; "
        "docs/quality-and-budgets.md)", 0.0, 10000.0, 0.0, MUTABLE_READY));
    g_object_class_install_property(oc, PROP_SEED, g_param_spec_uint("seed", "Seed",
        "Random seed of spawns and detail windows (0: the scene's, else 1)", 0, G_MAXUINT32, 0, MUTABLE_READY));
    g_object_class_install_property(oc, PROP_TIMELINE, g_param_spec_boolean("timeline", "Timeline",
        "Fire the scene's timeline (its times are the stream's running time since the first buffer or a seek)",
        TRUE, MUTABLE_READY));
    g_object_class_install_property(oc, PROP_DETAIL_FROM_INPUT, g_param_spec_boolean("detail-from-input",
        "Detail from input", "The incoming video's luma is the detail images' source, one slice per frame, as a "
        "V4L2 camera is for sbfx-play", FALSE, MUTABLE_READY));
    g_object_class_install_property(oc, PROP_BACKGROUND_DISTANCE, g_param_spec_double("background-distance",
        "Background distance", "The video as a plane this far in front of the camera, in metres, hiding what "
        "is behind it (0: at infinity, no depth)", 0.0, 1e6, 0.0, MUTABLE_READY));
    g_object_class_install_property(oc, PROP_STATS, g_param_spec_boxed("stats", "Statistics",
        "sbfx's counters and the frame times (a GstStructure \"sbfx-stats\"; docs/hosts/gstreamer.md)",
        GST_TYPE_STRUCTURE, G_PARAM_READABLE | G_PARAM_STATIC_STRINGS));
}

/* A property that changes the module: noted, taken over at the next frame while playing. */
static void quality_set(GstSbfx *self)
{
    self->quality_changed = TRUE;
}

static void set_scale(GstSbfx *self, guint scale)
{
    if (scale != 0 && scale != 1 && scale != 2 && scale != 4 && scale != 8) {
        GST_WARNING_OBJECT(self, "scale %u: use 1, 2, 4 or 8 (0: the scene's); kept %u", scale,
                           self->settings.scale);
        return;
    }
    self->settings.scale = scale;
    quality_set(self);
}

static void gst_sbfx_set_property(GObject *object, guint id, const GValue *value, GParamSpec *pspec)
{
    GstSbfx *self = GST_SBFX(object);
    struct gst_sbfx_settings *s = &self->settings;
    GST_OBJECT_LOCK(self);
    switch (id) {
    case PROP_SCENE:
        g_free(s->scene);
        s->scene = g_value_dup_string(value);
        self->scene_changed = TRUE;
        break;
    case PROP_SCALE: set_scale(self, g_value_get_uint(value)); break;
    case PROP_OPACITY: s->opacity = g_value_get_enum(value), quality_set(self); break;
    case PROP_UPSAMPLE: s->upsample = g_value_get_enum(value), quality_set(self); break;
    case PROP_FORMAT: s->format = g_value_get_enum(value), quality_set(self); break;
    case PROP_TONE_MAP: s->tone_map = g_value_get_enum(value); break;
    case PROP_EXPOSURE: s->exposure = g_value_get_double(value); break;
    case PROP_BUDGET_MS: s->budget_ms = g_value_get_double(value); break;
    case PROP_SEED: s->seed = g_value_get_uint(value); break;
    case PROP_TIMELINE: s->timeline = g_value_get_boolean(value); break;
    case PROP_DETAIL_FROM_INPUT: s->detail_from_input = g_value_get_boolean(value); break;
    case PROP_BACKGROUND_DISTANCE: s->background_distance = g_value_get_double(value); break;
    default: G_OBJECT_WARN_INVALID_PROPERTY_ID(object, id, pspec); break;
    }
    GST_OBJECT_UNLOCK(self);
}

static void gst_sbfx_get_property(GObject *object, guint id, GValue *value, GParamSpec *pspec)
{
    GstSbfx *self = GST_SBFX(object);
    const struct gst_sbfx_settings *s = &self->settings;
    if (id == PROP_STATS) { /* takes the lock itself */
        g_value_take_boxed(value, gst_sbfx_stats(self));
        return;
    }
    GST_OBJECT_LOCK(self);
    switch (id) {
    case PROP_SCENE: g_value_set_string(value, s->scene); break;
    case PROP_SCALE: g_value_set_uint(value, s->scale); break;
    case PROP_OPACITY: g_value_set_enum(value, s->opacity); break;
    case PROP_UPSAMPLE: g_value_set_enum(value, s->upsample); break;
    case PROP_FORMAT: g_value_set_enum(value, s->format); break;
    case PROP_TONE_MAP: g_value_set_enum(value, s->tone_map); break;
    case PROP_EXPOSURE: g_value_set_double(value, s->exposure); break;
    case PROP_BUDGET_MS: g_value_set_double(value, s->budget_ms); break;
    case PROP_SEED: g_value_set_uint(value, s->seed); break;
    case PROP_TIMELINE: g_value_set_boolean(value, s->timeline); break;
    case PROP_DETAIL_FROM_INPUT: g_value_set_boolean(value, s->detail_from_input); break;
    case PROP_BACKGROUND_DISTANCE: g_value_set_double(value, s->background_distance); break;
    default: G_OBJECT_WARN_INVALID_PROPERTY_ID(object, id, pspec); break;
    }
    GST_OBJECT_UNLOCK(self);
}

/* ---- the trigger signal: queued, started with the next buffer ---- */

static void trigger_handler(GstSbfx *self, const gchar *effect, gdouble x, gdouble y, gdouble z)
{
    struct pending_entry e = {.kind = PENDING_TRIGGER, .position = {(float)x, (float)y, (float)z}};
    if (!effect || strlen(effect) >= sizeof(e.effect)) {
        GST_WARNING_OBJECT(self, "trigger: %s effect name", effect ? "too long an" : "no");
        return;
    }
    strcpy(e.effect, effect);
    GST_OBJECT_LOCK(self);
    gboolean queued = pending_push(&self->pending, &e);
    GST_OBJECT_UNLOCK(self);
    if (!queued)
        GST_WARNING_OBJECT(self, "trigger \"%s\": %d triggers already wait for the next frame; dropped", effect,
                           PENDING_MAX);
}

static void install_signals(GstSbfxClass *klass)
{
    klass->trigger = trigger_handler;
    /* void trigger(const gchar *effect, gdouble x, gdouble y, gdouble z): starts the effect at the
     * world position with the next buffer (g_signal_emit_by_name(sbfx, "trigger", "explosion", 0.0,
     * 0.0, 0.0)); an effect the scene does not have is reported with the ones it has */
    signals[SIGNAL_TRIGGER] = g_signal_new("trigger", G_TYPE_FROM_CLASS(klass), G_SIGNAL_RUN_LAST | G_SIGNAL_ACTION,
                                           G_STRUCT_OFFSET(GstSbfxClass, trigger), NULL, NULL, NULL, G_TYPE_NONE, 4,
                                           G_TYPE_STRING, G_TYPE_DOUBLE, G_TYPE_DOUBLE, G_TYPE_DOUBLE);
}

/* ---- start and stop: the scene file, read when the pipeline goes to PAUSED ---- */

/* Loads the scene property's file; FALSE with the element's error posted (file:line). */
static gboolean load_scene(GstSbfx *self)
{
    GST_OBJECT_LOCK(self);
    gchar *path = g_strdup(self->settings.scene);
    self->scene_changed = FALSE;
    GST_OBJECT_UNLOCK(self);
    if (!path || !*path) {
        GST_ELEMENT_ERROR(self, RESOURCE, NOT_FOUND, ("sbfx: no scene: set the scene property to a scene file"),
                          ("e.g. scene=/usr/share/sbfx/scenes/explosion.cfg (docs/scene-format.md)"));
        g_free(path);
        return FALSE;
    }
    char err[1024];
    sbfx_scene *scene = NULL;
    if (sbfx_scene_load(path, &scene, err, sizeof(err)) != SBFX_OK) {
        GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS, ("sbfx: scene %s", err), ("the scene property is %s", path));
        g_free(path);
        return FALSE;
    }
    g_free(path);
    sbfx_scene_free(self->scene);
    self->scene = scene;
    sbfx_scene_camera_get(scene, &self->camera);
    return TRUE;
}

static gboolean gst_sbfx_start(GstBaseTransform *bt)
{
    GstSbfx *self = GST_SBFX(bt);
    stream_clock_reset(&self->clock);
    self->restart_due = FALSE;
    GST_OBJECT_LOCK(self);
    memset(&self->counts, 0, sizeof(self->counts));
    self->quality_changed = FALSE;
    GST_OBJECT_UNLOCK(self);
    if (!load_scene(self)) return FALSE;
    return GST_BASE_TRANSFORM_CLASS(parent_class)->start(bt);
}

/* What the run did, in the log (GST_DEBUG=sbfx:4): what a command line's user can see of stats. */
static void log_summary(GstSbfx *self)
{
    GST_OBJECT_LOCK(self);
    struct gst_sbfx_counts c = self->counts;
    GST_OBJECT_UNLOCK(self);
    GST_INFO_OBJECT(self, "stopped after %" G_GUINT64_FORMAT " frames: %" G_GUINT64_FORMAT " rendered, %"
                    G_GUINT64_FORMAT " forwarded; %d triggers fired, %" G_GUINT64_FORMAT " taps; %" G_GUINT64_FORMAT
                    " detail slices (%" G_GUINT64_FORMAT " distinct); %.2f ms a rendered frame (mean), %.2f max",
                    c.frames, c.rendered, c.forwarded, c.have_module ? c.module.triggers_fired : 0, c.taps,
                    c.detail_slices, c.detail_distinct, c.rendered ? c.sum_ms / (double)c.rendered : 0.0, c.max_ms);
}

static gboolean gst_sbfx_stop(GstBaseTransform *bt)
{
    GstSbfx *self = GST_SBFX(bt);
    log_summary(self);
    gboolean ok = GST_BASE_TRANSFORM_CLASS(parent_class)->stop(bt); /* gl_stop: the module goes */
    sbfx_scene_free(self->scene);
    self->scene = NULL;
    return ok;
}

/* ---- caps: the frame's size goes through unchanged ---- */

/* GstGLFilter's own lets the output take any size (it scales): sbfx draws over the input picture
 * pixel for pixel, and a sink that asks for its display's size (kmssink) must get a scaler
 * before or after the element, not a different output size from it. */
static GstCaps *same_caps(GstGLFilter *filter, GstPadDirection direction, GstCaps *caps, GstCaps *filter_caps)
{
    return gst_caps_ref(caps);
}

/* ---- the type ---- */

static void gst_sbfx_finalize(GObject *object)
{
    GstSbfx *self = GST_SBFX(object);
    g_free(self->settings.scene);
    sbfx_scene_free(self->scene);
    G_OBJECT_CLASS(parent_class)->finalize(object);
}

static void gst_sbfx_class_init(GstSbfxClass *klass)
{
    GObjectClass *oc = G_OBJECT_CLASS(klass);
    GstElementClass *ec = GST_ELEMENT_CLASS(klass);
    GstBaseTransformClass *bc = GST_BASE_TRANSFORM_CLASS(klass);
    GstGLBaseFilterClass *gc = GST_GL_BASE_FILTER_CLASS(klass);
    oc->set_property = gst_sbfx_set_property;
    oc->get_property = gst_sbfx_get_property;
    oc->finalize = gst_sbfx_finalize;
    install_properties(oc);
    install_signals(klass);
    gst_gl_filter_add_rgba_pad_templates(GST_GL_FILTER_CLASS(klass));
    gst_element_class_set_static_metadata(ec, "sbfx volumetric particle effects", "Filter/Effect/Video",
        "Composites sbfx's explosions, smoke, fire and heat shimmer over the video, on GStreamer's GL context",
        "the sbfx developers");
    bc->start = gst_sbfx_start;
    bc->stop = gst_sbfx_stop;
    bc->prepare_output_buffer = gst_sbfx_prepare_output_buffer;
    bc->transform = gst_sbfx_transform;
    bc->sink_event = gst_sbfx_sink_event;
    bc->src_event = gst_sbfx_src_event;
    gc->supported_gl_api = GST_GL_API_GLES2 | GST_GL_API_OPENGL3 | GST_GL_API_OPENGL;
    gc->gl_start = gst_sbfx_gl_start;
    gc->gl_stop = gst_sbfx_gl_stop;
    gc->gl_set_caps = gst_sbfx_gl_set_caps;
    GST_GL_FILTER_CLASS(klass)->filter_texture = gst_sbfx_filter_texture;
    GST_GL_FILTER_CLASS(klass)->transform_internal_caps = same_caps;
    gst_type_mark_as_plugin_api(opacity_type(), 0);
    gst_type_mark_as_plugin_api(upsample_type(), 0);
    gst_type_mark_as_plugin_api(format_type(), 0);
    gst_type_mark_as_plugin_api(tone_map_type(), 0);
    GST_DEBUG_CATEGORY_INIT(gst_sbfx_debug, "sbfx", 0, "sbfx volumetric particle effects");
}

static void gst_sbfx_init(GstSbfx *self)
{
    self->settings.timeline = TRUE;
}
