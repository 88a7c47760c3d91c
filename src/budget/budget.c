/* The frame budget (docs/design.md §6): the levels the module declares at load, the ladder the budget
 * walks below the top quality, and each frame: the governor's level applied before the passes,
 * sbfx's GPU time measured around them (gpu_timer.c) or, where GL_EXT_disjoint_timer_query is
 * missing, reported by the host (sbfx_report_frame_time), fed back to the governor. */
#include <math.h>
#include <stdio.h>
#include "budget/budget.h"
#include "budget/ladder_default.h"

_Static_assert(ARRAY_SIZE(sbfx_ladder_default) < SBFX_LADDER_MAX, "the default ladder and a top must fit a ladder");

/* desc.ladder (the scene's render.ladder), or with a budget and none given the default. */
static sbfx_result given_ladder(sbfx *fx, sbfx_quality *out, int *count)
{
    const sbfx_desc *d = &fx->scene->desc;
    const char *const *names = d->ladder;
    int n = d->ladder_count;
    const char *what = "ladder";
    if (!names && d->frame_budget_ms > 0) {
        names = sbfx_ladder_default;
        n = (int)ARRAY_SIZE(sbfx_ladder_default);
        what = "the default ladder";
    }
    *count = 0;
    for (int i = 0; i < n && names; i++) {
        char err[256];
        if (sbfx_quality_parse(names[i], &out[i], err, sizeof(err)) != SBFX_OK)
            return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "%s[%d]: %s", what, i, err);
        sbfx_quality_resolve(&out[i], NULL, 0);
    }
    *count = names ? n : 0;
    return SBFX_OK;
}

/* A level the top may fall to when the top is not on the given ladder: it costs less on an
 * axis a level names without costing more on another: a coarser target, or the same target
 * with fewer particles drawn (level of detail). */
static bool cheaper_than_top(const sbfx_quality *top, const sbfx_quality *q)
{
    if (q->target_divisor != top->target_divisor) return q->target_divisor > top->target_divisor;
    return q->lod_particles && (!top->lod_particles || q->lod_particles < top->lod_particles);
}

/* Where the top stands on the given ladder: after the level equal to it, else after the level
 * that differs from it in target format only (the format moves the error least:
 * docs/accuracy-and-benchmarks.md); -1 when neither is there. */
static int after_top(const sbfx_quality *top, const sbfx_quality *given, int count)
{
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < count; i++) {
            sbfx_quality q = given[i];
            if (pass == 1) q.target_format = top->target_format;
            if (sbfx_quality_equal(&q, top)) return i + 1;
        }
    return -1;
}

/* The budget's ladder: the top first, then the given ladder's levels below it — those after
 * the top's place on it (after_top; the ladder is ordered most accurate first), else those
 * cheaper than the top (above). The governor never goes above level 0. */
static void build_ladder(sbfx *fx, const sbfx_quality *given, int count)
{
    sbfx_budget *b = fx->budget;
    int from = after_top(&fx->scene->top, given, count);
    b->ladder[0] = fx->scene->top;
    b->count = 1;
    for (int i = from < 0 ? 0 : from; i < count && b->count < SBFX_LADDER_MAX; i++)
        if (from >= 0 || cheaper_than_top(&fx->scene->top, &given[i])) b->ladder[b->count++] = given[i];
}

static void declare(sbfx *fx, const sbfx_quality *q)
{
    for (int i = 0; i < fx->scene->declared_count; i++)
        if (sbfx_quality_equal(&fx->scene->declared[i], q)) return;
    if (fx->scene->declared_count < (int)ARRAY_SIZE(fx->scene->declared)) fx->scene->declared[fx->scene->declared_count++] = *q;
}

sbfx_result sbfx_budget_init(sbfx *fx)
{
    sbfx_budget *b = fx->budget;
    sbfx_quality given[SBFX_LADDER_MAX];
    int count = 0;
    fx->scene->top = sbfx_quality_from_desc(&fx->scene->desc);
    sbfx_quality_resolve(&fx->scene->top, NULL, 0);
    fx->scene->current = fx->scene->top;
    fx->scene->declared_count = 0;
    declare(fx, &fx->scene->top);
    sbfx_result r = given_ladder(fx, given, &count);
    if (r != SBFX_OK) return r;
    fx->counters.budget_ms = fx->scene->desc.frame_budget_ms;
    if (!(fx->scene->desc.frame_budget_ms > 0)) {
        for (int i = 0; i < count; i++) declare(fx, &given[i]); /* for sbfx_set_quality */
        return SBFX_OK;
    }
    build_ladder(fx, given, count);
    for (int i = 0; i < b->count; i++) declare(fx, &b->ladder[i]);
    governor_init(&b->gov, fx->scene->desc.frame_budget_ms, b->count);
    sbfx_ladder_prior(b->ladder, b->count, &b->gov);
    b->on = true;
    b->level = 0;
    return SBFX_OK;
}

bool sbfx_budget_active(const sbfx *fx) { return fx->budget->on; }

void sbfx_budget_gl_init(sbfx *fx)
{
    sbfx_budget *b = fx->budget;
    if (!b->on) return;
    b->level = 0; /* the load made the top current */
    if (!gpu_timer_init(&b->timer))
        sbfx_log(fx, SBFX_LOG_INFO, "frame budget: no GL_EXT_disjoint_timer_query here: the budget follows the "
                 "frame times the host reports (sbfx_report_frame_time)");
}

void sbfx_budget_gl_destroy(sbfx *fx)
{
    if (fx->budget->on) gpu_timer_destroy(&fx->budget->timer);
}

static void publish(sbfx *fx)
{
    const governor *g = &fx->budget->gov;
    fx->counters.gpu_ms = (float)governor_smoothed_ms(g);
    fx->counters.frames_over_budget = governor_frames_over(g);
    fx->counters.quality_changes = governor_changes(g);
}

/* Measurements that have arrived (a few frames late) go to the governor. */
static void collect(sbfx *fx)
{
    sbfx_budget *b = fx->budget;
    double ms;
    int level;
    bool valid;
    while (b->timer.ok && gpu_timer_poll(&b->timer, &ms, &level, &valid)) governor_observe(&b->gov, level, ms, valid);
    if (!b->timer.ok && b->timer.failed && !b->warned) {
        b->warned = true;
        sbfx_log(fx, SBFX_LOG_WARN, "frame budget: %s failed (GL error 0x%04x): the budget follows the frame "
                 "times the host reports (sbfx_report_frame_time) from now on", b->timer.failed, b->timer.error);
    }
}

sbfx_result sbfx_budget_begin_frame(sbfx *fx)
{
    sbfx_budget *b = fx->budget;
    if (!b->on) return SBFX_OK;
    collect(fx);
    int level = governor_level(&b->gov);
    if (level != b->level) {
        sbfx_result r = sbfx_quality_apply(fx, &b->ladder[level]);
        if (r != SBFX_OK) return r;
        b->level = level;
    }
    b->timing = b->timer.ok;
    if (b->timing) gpu_timer_begin(&b->timer, level);
    publish(fx);
    return SBFX_OK;
}

void sbfx_budget_end_frame(sbfx *fx)
{
    sbfx_budget *b = fx->budget;
    if (!b->timing) return;
    gpu_timer_end(&b->timer);
    b->timing = false;
}

void sbfx_report_frame_time(sbfx *fx, double ms)
{
    if (!fx || !fx->budget->on || fx->budget->timer.ok) return;
    governor_observe(&fx->budget->gov, fx->budget->level, ms, isfinite(ms) && ms >= 0.0);
    publish(fx);
}
