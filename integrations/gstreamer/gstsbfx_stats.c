/* The `stats` property: a GstStructure "sbfx-stats" of the element's and the module's counters
 * (docs/hosts/gstreamer.md lists the fields). */
#include "gstsbfx.h"

static const char *format_name(sbfx_target_format f)
{
    switch (f) {
    case SBFX_FORMAT_RGBA8: return "rgba8";
    case SBFX_FORMAT_RGBA16F: return "rgba16f";
    case SBFX_FORMAT_RGBA32F: return "rgba32f";
    default: return "none";
    }
}

static void add_element_counts(GstStructure *s, const struct gst_sbfx_counts *c, unsigned dropped)
{
    gst_structure_set(s, "frames", G_TYPE_UINT64, c->frames, "frames-rendered", G_TYPE_UINT64, c->rendered,
                      "frames-forwarded", G_TYPE_UINT64, c->forwarded, "running-time", G_TYPE_DOUBLE,
                      c->running_time, "elapsed", G_TYPE_DOUBLE, c->elapsed, "frame-ms-last", G_TYPE_DOUBLE,
                      c->last_ms, "frame-ms-mean", G_TYPE_DOUBLE, c->rendered ? c->sum_ms / (double)c->rendered : 0.0,
                      "frame-ms-max", G_TYPE_DOUBLE, c->max_ms, "taps", G_TYPE_UINT64, c->taps, "taps-missed",
                      G_TYPE_UINT64, c->taps_missed, "triggers-failed", G_TYPE_UINT64, c->triggers_failed,
                      "triggers-dropped", G_TYPE_UINT64, (guint64)dropped, "restarts", G_TYPE_UINT64, c->restarts,
                      "scene-reloads", G_TYPE_UINT64, c->scene_reloads, "detail-slices", G_TYPE_UINT64,
                      c->detail_slices, "detail-distinct", G_TYPE_UINT64, c->detail_distinct, "untimed-buffers",
                      G_TYPE_UINT64, c->untimed, "clamped-steps", G_TYPE_UINT64, c->clamped, NULL);
}

static void add_module_counts(GstStructure *s, const sbfx_counters *m)
{
    gst_structure_set(s, "programs", G_TYPE_INT, m->programs, "textures", G_TYPE_INT, m->textures, "framebuffers",
                      G_TYPE_INT, m->framebuffers, "gpu-bytes", G_TYPE_UINT64, (guint64)m->gpu_bytes, "passes",
                      G_TYPE_INT, m->passes, "draw-calls", G_TYPE_INT, m->draw_calls, "particles-simulated",
                      G_TYPE_INT, m->particles_simulated, "particles-alive", G_TYPE_INT, m->particles_alive,
                      "particles-skipped", G_TYPE_INT, m->particles_skipped, "triggers-fired", G_TYPE_INT,
                      m->triggers_fired, "triggers-refused", G_TYPE_INT, m->triggers_refused,
                      "heap-allocs-after-load", G_TYPE_UINT64, (guint64)m->heap_allocs_after_load,
                      "target-format", G_TYPE_STRING, format_name(m->target_format), "gl-state-queries",
                      G_TYPE_INT, m->gl_state_queries, "quality", G_TYPE_STRING, m->quality, "budget-ms",
                      G_TYPE_DOUBLE, (double)m->budget_ms, "gpu-ms", G_TYPE_DOUBLE, (double)m->gpu_ms,
                      "frames-over-budget", G_TYPE_INT, m->frames_over_budget, "quality-changes", G_TYPE_INT,
                      m->quality_changes, "programs-compiled", G_TYPE_INT, m->programs_compiled,
                      "targets-created", G_TYPE_INT, m->targets_created, NULL);
}

GstStructure *gst_sbfx_stats(GstSbfx *self)
{
    GstStructure *s = gst_structure_new_empty("sbfx-stats");
    GST_OBJECT_LOCK(self);
    struct gst_sbfx_counts c = self->counts;
    unsigned dropped = self->pending.dropped;
    GST_OBJECT_UNLOCK(self);
    add_element_counts(s, &c, dropped);
    if (c.have_module) add_module_counts(s, &c.module);
    return s;
}
