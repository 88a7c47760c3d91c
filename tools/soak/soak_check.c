/* sbfx-soak's CSV records and flatness check (soak_check.h). */
#include "soak_check.h"

#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <string.h>

enum metric_kind { METRIC_EXACT, METRIC_RSS, METRIC_HEAP, METRIC_INFO };

struct metric {
    const char *name;
    size_t offset;
    enum metric_kind kind;
};

#define METRIC(field, kind) {#field, offsetof(struct soak_sample, field), kind}
static const struct metric metrics[] = {
    METRIC(programs, METRIC_EXACT),   METRIC(textures, METRIC_EXACT),  METRIC(framebuffers, METRIC_EXACT),
    METRIC(gpu_bytes, METRIC_EXACT),  METRIC(heap_allocs, METRIC_EXACT),
    METRIC(gl_textures, METRIC_EXACT), METRIC(gl_framebuffers, METRIC_EXACT), METRIC(gl_buffers, METRIC_EXACT),
    METRIC(rss_anon_kib, METRIC_RSS), METRIC(heap_bytes, METRIC_HEAP),
    METRIC(rss_kib, METRIC_INFO),     METRIC(rss_file_kib, METRIC_INFO),
};
#define METRIC_COUNT (sizeof(metrics) / sizeof(metrics[0]))

void soak_limits_default(struct soak_limits *lim)
{
    *lim = (struct soak_limits){.warmup = 0.25, .rss_kib = 4096, .heap_bytes = 2 << 20, .dt = 0.0, .step = 0.0};
}

void soak_write_header(FILE *f)
{
    fputs("sim_hours,frames,wall_seconds,rss_kib,rss_anon_kib,rss_file_kib,heap_bytes,programs,textures,framebuffers,gpu_bytes,"
          "heap_allocs_after_load,gl_textures,gl_framebuffers,gl_buffers,particles_alive,triggers_fired,triggers_refused\n", f);
}

void soak_write_sample(FILE *f, const struct soak_sample *s)
{
    fprintf(f, "%.6f,%lld,%.3f,%lld,%lld,%lld,%lld,%lld,%lld,%lld,%lld,%lld,%lld,%lld,%lld,%lld,%lld,%lld\n",
            s->sim_seconds / 3600.0, (long long)s->frames, s->wall_seconds, (long long)s->rss_kib,
            (long long)s->rss_anon_kib, (long long)s->rss_file_kib, (long long)s->heap_bytes,
            (long long)s->programs, (long long)s->textures, (long long)s->framebuffers, (long long)s->gpu_bytes,
            (long long)s->heap_allocs, (long long)s->gl_textures, (long long)s->gl_framebuffers,
            (long long)s->gl_buffers, (long long)s->particles_alive,
            (long long)s->triggers_fired, (long long)s->triggers_refused);
}

static int64_t value(const struct soak_sample *s, const struct metric *m)
{
    int64_t v;
    memcpy(&v, (const char *)s + m->offset, sizeof(v));
    return v;
}

/* Appends one line to the report. */
static void say(char *report, size_t n, const char *fmt, ...)
{
    size_t used = strlen(report);
    if (used + 1 >= n) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(report + used, n - used, fmt, ap);
    va_end(ap);
    used = strlen(report);
    if (used + 1 < n) strcat(report, "\n");
}

static double mean(const struct soak_sample *s, int from, int to, const struct metric *m)
{
    double sum = 0.0;
    for (int i = from; i < to; i++) sum += (double)value(&s[i], m);
    return to > from ? sum / (to - from) : 0.0;
}

/* Least-squares slope of a metric against simulated hours over [from, to). */
static double slope_per_hour(const struct soak_sample *s, int from, int to, const struct metric *m)
{
    double n = to - from, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = from; i < to; i++) {
        double x = s[i].sim_seconds / 3600.0, y = (double)value(&s[i], m);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    double d = n * sxx - sx * sx;
    return n >= 2 && d > 0 ? (n * sxy - sx * sy) / d : 0.0;
}

static int check_exact(const struct soak_sample *s, int from, int count, const struct metric *m, char *r, size_t n)
{
    int64_t first = value(&s[from], m), hi = first, lo = first;
    int at = from;
    for (int i = from; i < count; i++) {
        int64_t v = value(&s[i], m);
        if (v > hi) hi = v, at = i;
        if (v < lo) lo = v;
    }
    if (hi == first && lo == first) return 0;
    if (hi > first)
        say(r, n, "%s grew from %lld to %lld (+%lld) after warm-up (by %.2f simulated hours, frame %lld)", m->name,
            (long long)first, (long long)hi, (long long)(hi - first), s[at].sim_seconds / 3600.0,
            (long long)s[at].frames);
    else
        say(r, n, "%s fell from %lld to %lld after warm-up: it must stay flat", m->name, (long long)first,
            (long long)lo);
    return 1;
}

/* Resident memory and heap bytes: the last quarter's mean against the first quarter's after
 * warm-up, within the tolerance. */
static int check_drift(const struct soak_sample *s, int from, int count, const struct metric *m, int64_t tolerance,
                       const char *unit, double scale, char *r, size_t n)
{
    int quarter = (count - from) / 4 > 0 ? (count - from) / 4 : 1;
    double before = mean(s, from, from + quarter, m), after = mean(s, count - quarter, count, m);
    double slope = slope_per_hour(s, from, count, m);
    say(r, n, "# %s: %.0f %s after warm-up, %.0f %s at the end (%+.0f), slope %+.1f %s per simulated hour",
        m->name, before / scale, unit, after / scale, unit, (after - before) / scale, slope / scale, unit);
    if (after - before <= (double)tolerance) return 0;
    say(r, n, "%s grew by %.0f %s (tolerance %.0f) from %.0f to %.0f after warm-up, slope %+.1f %s per "
        "simulated hour", m->name, (after - before) / scale, unit, (double)tolerance / scale, before / scale,
        after / scale, slope / scale, unit);
    return 1;
}

/* The run did what a soak is for: effects fired and lived, and no simulated time was lost. */
static int check_activity(const struct soak_sample *s, int count, const struct soak_limits *lim, char *r, size_t n)
{
    int problems = 0;
    const struct soak_sample *last = &s[count - 1];
    int64_t alive = 0;
    for (int i = 0; i < count; i++) alive = s[i].particles_alive > alive ? s[i].particles_alive : alive;
    if (last->triggers_fired <= s[0].triggers_fired || alive == 0) {
        say(r, n, "nothing happened: %lld triggers fired, at most %lld particles alive",
            (long long)(last->triggers_fired - s[0].triggers_fired), (long long)alive);
        problems++;
    }
    double want = (double)last->frames * lim->dt;
    if (lim->dt > 0 && fabs(last->sim_seconds - want) > lim->step + 1e-6 * want) {
        say(r, n, "simulated time %.6f s after %lld frames of %g s: %.6f s lost", last->sim_seconds,
            (long long)last->frames, lim->dt, want - last->sim_seconds);
        problems++;
    }
    return problems;
}

int soak_check(const struct soak_sample *s, int count, const struct soak_limits *lim, char *report, size_t n)
{
    if (n) report[0] = '\0';
    if (count < 8) {
        say(report, n, "only %d samples: run longer or sample more often", count);
        return 1;
    }
    int from = (int)(count * lim->warmup);
    if (from > count - 4) from = count - 4;
    int problems = check_activity(s, count, lim, report, n);
    for (size_t i = 0; i < METRIC_COUNT; i++) {
        const struct metric *m = &metrics[i];
        if (m->kind == METRIC_EXACT) problems += check_exact(s, from, count, m, report, n);
        else if (m->kind == METRIC_RSS)
            problems += check_drift(s, from, count, m, lim->rss_kib, "KiB", 1.0, report, n);
        else if (m->kind == METRIC_INFO) /* reported, not checked */
            check_drift(s, from, count, m, INT64_MAX, "KiB", 1.0, report, n);
        else
            problems += check_drift(s, from, count, m, lim->heap_bytes, "KiB", 1024.0, report, n);
    }
    return problems;
}
