/* The frame-budget governor: governor.h says what it does and why. */
#include "budget/governor.h"

#include <math.h>

#define GOVERNOR_DEFAULT_STEP 0.7 /* prior: each rung costs this share of the one above */

static bool governor_enabled(const governor *g)
{
    return isfinite(g->budget_ms) && g->budget_ms > 0.0;
}

void governor_init(governor *g, double budget_ms, int level_count)
{
    *g = (governor){0};
    g->budget_ms = budget_ms;
    g->level_count = level_count < 1 ? 1
                   : level_count > GOVERNOR_MAX_LEVELS ? GOVERNOR_MAX_LEVELS : level_count;
    g->from_level = -1;
    double rel = 1.0;
    for (int i = 0; i < GOVERNOR_MAX_LEVELS; i++) {
        g->rel[i] = rel;
        g->up_wait[i] = GOVERNOR_UP_FRAMES;
        rel *= GOVERNOR_DEFAULT_STEP;
    }
}

void governor_set_prior(governor *g, const double *cost, int count)
{
    double rel[GOVERNOR_MAX_LEVELS];
    int known = -1; /* the last level with a cost */
    for (int i = 0; i < g->level_count; i++) {
        bool valid = i < count && isfinite(cost[i]) && cost[i] > 0.0;
        rel[i] = valid ? cost[i] : 0.0;
        if (valid && known < 0) /* levels above the first given cost: the default step */
            for (int k = i - 1; k >= 0; k--) rel[k] = rel[k + 1] / GOVERNOR_DEFAULT_STEP;
        if (!valid && known >= 0)
            rel[i] = rel[i - 1] * GOVERNOR_DEFAULT_STEP;
        if (valid || known >= 0)
            known = i;
    }
    if (known < 0)
        return; /* nothing given: the default prior stays */
    for (int i = 0; i < g->level_count; i++)
        g->rel[i] = rel[i];
}

/* est(j) = smoothed × rel[j] / rel[level]; before the first measurement of this level, from
 * the level it was reached from. */
double governor_estimate_ms(const governor *g, int level)
{
    if (level < 0 || level >= g->level_count)
        return 0.0;
    if (g->samples > 0)
        return g->smoothed * g->rel[level] / g->rel[g->level];
    if (g->from_level >= 0)
        return g->from_ms * g->rel[level] / g->rel[g->from_level];
    return 0.0;
}

/* Makes rel[lo] / rel[hi] the measured ratio c_lo / c_hi (lo above hi on the ladder): the
 * prior's steps between them are scaled in log space (equal steps if the prior had none), the
 * rungs below hi move with it. A rung measured cheaper than one below it counts as equal. */
static void governor_learn(governor *g, int a, double ca, int b, double cb)
{
    int lo = a < b ? a : b, hi = a < b ? b : a;
    double c_lo = a < b ? ca : cb, c_hi = a < b ? cb : ca;
    if (lo == hi || !(c_lo > 0.0) || !(c_hi > 0.0))
        return;
    double want = fmax(0.0, log(c_lo / c_hi));
    double have = log(g->rel[lo] / g->rel[hi]);
    double old_hi = g->rel[hi];
    for (int k = lo; k < hi; k++) {
        double step = log(g->rel[k] / g->rel[k + 1]);
        step = have > 1e-9 && step > 0.0 ? step * want / have : want / (hi - lo);
        g->rel[k + 1] = g->rel[k] * exp(-step);
    }
    for (int k = hi + 1; k < g->level_count; k++)
        g->rel[k] *= g->rel[hi] / old_hi;
}

/* The median of n <= GOVERNOR_WINDOW values: one frame stretched by another job moves it not. */
static double governor_median(const double *v, int n)
{
    double s[GOVERNOR_WINDOW];
    for (int i = 0; i < n; i++) {
        int k = i;
        for (; k > 0 && s[k - 1] > v[i]; k--) s[k] = s[k - 1];
        s[k] = v[i];
    }
    return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

static void governor_switch(governor *g, int level)
{
    if (!g->learned && g->from_level >= 0 && g->samples >= GOVERNOR_DOWN_SAMPLES)
        governor_learn(g, g->from_level, g->from_ms, g->level, g->smoothed);
    g->from_level = g->level;
    g->from_ms = g->smoothed;
    g->level = level;
    g->smoothed = 0.0;
    g->samples = g->room_run = g->over_run = g->frames_here = 0;
    g->learned = g->went_up = false;
    g->changes++;
}

/* The first rung below whose estimate fits the fill target; the last resort if none does. The
 * estimate starts from the least of the over-budget run's times when that run moved it (what
 * the level costs at least: a few frames stretched by another job do not throw it further). */
static int governor_down_target(const governor *g)
{
    double base = g->over_run >= GOVERNOR_DOWN_SAMPLES ? fmin(g->over_min, g->smoothed) : g->smoothed;
    for (int j = g->level + 1; j < g->level_count; j++)
        if (base * g->rel[j] / g->rel[g->level] <= GOVERNOR_DOWN_FILL * g->budget_ms)
            return j;
    return g->level_count - 1;
}

static bool governor_try_down(governor *g)
{
    bool over = g->over_run >= GOVERNOR_DOWN_SAMPLES
             || (g->samples >= GOVERNOR_LEARN_SAMPLES && g->smoothed > g->budget_ms);
    if (!over || g->level == g->level_count - 1)
        return false;
    if (g->went_up && g->frames_here < GOVERNOR_SETTLE_FRAMES) {
        int w = 2 * g->up_wait[g->level];
        g->up_wait[g->level] = w > GOVERNOR_UP_FRAMES_MAX ? GOVERNOR_UP_FRAMES_MAX : w;
    }
    governor_switch(g, governor_down_target(g));
    return true;
}

static void governor_try_up(governor *g)
{
    if (g->level == 0)
        return;
    if (governor_estimate_ms(g, g->level - 1) * GOVERNOR_UP_MARGIN <= g->budget_ms)
        g->room_run++;
    else
        g->room_run = 0;
    if (g->room_run >= g->up_wait[g->level - 1]) {
        governor_switch(g, g->level - 1);
        g->went_up = true;
    }
}

void governor_observe(governor *g, int level_rendered, double gpu_ms, bool valid)
{
    if (!governor_enabled(g) || !valid || !isfinite(gpu_ms) || gpu_ms < 0.0
        || level_rendered < 0 || level_rendered >= g->level_count)
        return;
    g->observed++;
    if (gpu_ms > g->budget_ms)
        g->frames_over++;
    if (level_rendered != g->level) {
        g->last_ms[level_rendered] = gpu_ms; /* late: from a level already left */
        return;
    }
    g->window[g->samples % GOVERNOR_WINDOW] = gpu_ms;
    g->smoothed = governor_median(g->window, g->samples + 1 < GOVERNOR_WINDOW ? g->samples + 1 : GOVERNOR_WINDOW);
    g->samples++;
    g->frames_here++;
    g->over_min = g->over_run == 0 ? gpu_ms : fmin(g->over_min, gpu_ms);
    g->over_run = gpu_ms > g->budget_ms ? g->over_run + 1 : 0;
    g->last_ms[g->level] = g->smoothed;
    if (!g->learned && g->from_level >= 0 && g->samples >= GOVERNOR_LEARN_SAMPLES) {
        governor_learn(g, g->from_level, g->from_ms, g->level, g->smoothed);
        g->learned = true;
    }
    if (g->went_up && g->frames_here >= GOVERNOR_SETTLE_FRAMES) {
        g->up_wait[g->level] = GOVERNOR_UP_FRAMES; /* the ascent held */
        g->went_up = false;
    }
    if (!governor_try_down(g))
        governor_try_up(g);
}

int governor_level(const governor *g) { return g->level; }
double governor_smoothed_ms(const governor *g) { return g->samples > 0 ? g->smoothed : g->from_ms; }
int governor_frames_over(const governor *g) { return g->frames_over; }
int governor_changes(const governor *g) { return g->changes; }
