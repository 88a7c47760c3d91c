/* Quality levels as values and names (docs/design.md §6): defaults, validation, and the level name
 * grammar <opacity>/<divisor>/<upsample>[/<flag>...] (docs/quality-and-budgets.md, "Level
 * names"). No GL: the scene parser (and its fuzzer) reads ladders with it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "scene/scene.h"

#define LOD_MAX (1 << 20)

static const char *const opacity_tokens[SBFX_OPACITY_COUNT] = {
    [SBFX_OPACITY_PLANAR] = "planar", [SBFX_OPACITY_SOFT] = "soft", [SBFX_OPACITY_SPHERICAL] = "spherical",
    [SBFX_OPACITY_EXACT] = "exact",   [SBFX_OPACITY_FLOOR] = "floor", /* named, not parsed: bench only */
};
static const char *const upsample_tokens[SBFX_UPSAMPLE_COUNT] = {
    [SBFX_UPSAMPLE_BILINEAR] = "bl", [SBFX_UPSAMPLE_NEAREST_DEPTH] = "nd", [SBFX_UPSAMPLE_MIXED] = "mx"};
static const char *const format_tokens[SBFX_FORMAT_COUNT] = {
    [SBFX_FORMAT_RGBA8] = "rgba8", [SBFX_FORMAT_RGBA16F] = "rgba16f", [SBFX_FORMAT_RGBA32F] = "rgba32f"};

/* The phase function is analytic unless the table is asked for and the analytic form is not
 * (issue 43: the table bought no accuracy and cost cycles on every GPU; docs/quality-and-budgets.md).
 * Resolved, exactly one of the two is set, so every reader of analytic_phase sees the choice. */
void sbfx_phase_resolve(bool *analytic, bool *table)
{
    *table = *table && !*analytic;
    *analytic = !*table;
}

sbfx_quality sbfx_quality_from_desc(const sbfx_desc *d)
{
    return (sbfx_quality){d->opacity, d->target_divisor, d->upsample, d->target_format, d->light_per_particle,
                          d->analytic_blackbody, d->analytic_phase, d->table_phase, d->lod_particles};
}

bool sbfx_quality_resolve(sbfx_quality *q, char *err, size_t size)
{
    if (!q->opacity) q->opacity = SBFX_OPACITY_EXACT;
    if (!q->target_divisor) q->target_divisor = 4;
    if (!q->upsample) q->upsample = SBFX_UPSAMPLE_NEAREST_DEPTH;
    sbfx_phase_resolve(&q->analytic_phase, &q->table_phase);
    int d = q->target_divisor;
    const char *why = (unsigned)q->opacity >= SBFX_OPACITY_COUNT ? "unknown opacity mode"
                      : d != 1 && d != 2 && d != 4 && d != 8 ? "target_divisor is not 1, 2, 4 or 8"
                      : (unsigned)q->upsample >= SBFX_UPSAMPLE_COUNT ? "unknown upsample"
                      : (unsigned)q->target_format >= SBFX_FORMAT_COUNT ? "unknown target format"
                      : q->lod_particles < 0 || q->lod_particles > LOD_MAX ? "lod_particles is not 0 .. 1048576"
                      : NULL;
    if (why && err) snprintf(err, size, "quality: %s", why);
    return !why;
}

bool sbfx_quality_equal(const sbfx_quality *a, const sbfx_quality *b)
{
    return a->opacity == b->opacity && a->target_divisor == b->target_divisor && a->upsample == b->upsample &&
           a->target_format == b->target_format && a->light_per_particle == b->light_per_particle &&
           a->analytic_blackbody == b->analytic_blackbody &&
           (a->table_phase && !a->analytic_phase) == (b->table_phase && !b->analytic_phase) &&
           a->lod_particles == b->lod_particles;
}

/* ---- names ---------------------------------------------------------------------------------- */

static int token_index(const char *const *tokens, int count, const char *t)
{
    for (int i = 1; i < count; i++)
        if (tokens[i] && strcmp(tokens[i], t) == 0) return i;
    return 0;
}

/* A flag token (the fourth and later): 0, or -1 with err written. */
static int parse_flag(const char *t, sbfx_quality *q, char *err, size_t size)
{
    bool *flag = strcmp(t, "lpp") == 0 ? &q->light_per_particle : strcmp(t, "abb") == 0 ? &q->analytic_blackbody
                 : strcmp(t, "aph") == 0 ? &q->analytic_phase : strcmp(t, "tph") == 0 ? &q->table_phase : NULL;
    int format = token_index(format_tokens, SBFX_FORMAT_COUNT, t);
    if (flag || format) {
        if (flag ? *flag : q->target_format != 0) {
            snprintf(err, size, flag ? "'%s' given twice" : "'%s': a second target format", t);
            return -1;
        }
        if (flag) *flag = true;
        else q->target_format = (sbfx_target_format)format;
        if (q->analytic_phase && q->table_phase) {
            snprintf(err, size, "'aph' and 'tph': the phase function is either analytic or its table");
            return -1;
        }
        return 0;
    }
    if (strncmp(t, "lod", 3) == 0 && t[3] >= '1' && t[3] <= '9' && strspn(t + 3, "0123456789") == strlen(t + 3) &&
        strlen(t + 3) <= 7 && atoi(t + 3) <= LOD_MAX) {
        if (q->lod_particles) {
            snprintf(err, size, "'%s': a second lod", t);
            return -1;
        }
        q->lod_particles = atoi(t + 3);
        return 0;
    }
    snprintf(err, size, "unknown flag '%.40s' (rgba8, rgba16f, rgba32f, lpp, abb, tph, aph, lodN with N in 1..%d)", t, LOD_MAX);
    return -1;
}

/* Token i of a name: 0, or -1 with err written. */
static int parse_token(int i, const char *t, sbfx_quality *q, char *err, size_t size)
{
    if (i == 0) {
        q->opacity = (sbfx_opacity_mode)token_index(opacity_tokens, SBFX_OPACITY_FLOOR, t);
        if (!q->opacity) snprintf(err, size, "unknown opacity '%s' (planar, soft, spherical, exact)", t);
        return q->opacity ? 0 : -1;
    }
    if (i == 1) {
        q->target_divisor = strlen(t) == 1 && strchr("1248", t[0]) ? t[0] - '0' : 0;
        if (!q->target_divisor) snprintf(err, size, "unknown divisor '%s' (1, 2, 4, 8)", t);
        return q->target_divisor ? 0 : -1;
    }
    if (i == 2) {
        q->upsample = (sbfx_upsample)token_index(upsample_tokens, SBFX_UPSAMPLE_COUNT, t);
        if (!q->upsample) snprintf(err, size, "unknown upsample '%s' (nd, bl, mx)", t);
        return q->upsample ? 0 : -1;
    }
    return parse_flag(t, q, err, size);
}

sbfx_result sbfx_quality_parse(const char *name, sbfx_quality *out, char *err, size_t err_size)
{
    char why[256] = "", text[128];
    sbfx_quality q = {0};
    int count = 0;
    if (!name || !out) snprintf(why, sizeof(why), "NULL name or output");
    else if (strlen(name) >= sizeof(text)) snprintf(why, sizeof(why), "longer than %zu characters", sizeof(text) - 1);
    else {
        snprintf(text, sizeof(text), "%s", name);
        for (char *t = text; t && !why[0]; count++) {
            char *slash = strchr(t, '/');
            if (slash) *slash = '\0';
            parse_token(count, t, &q, why, sizeof(why));
            t = slash ? slash + 1 : NULL;
        }
        if (!why[0] && count < 3) snprintf(why, sizeof(why), "use <opacity>/<divisor>/<upsample>[/<flag>...]");
    }
    if (why[0]) {
        if (err && err_size) snprintf(err, err_size, "quality \"%s\": %s", name ? name : "(null)", why);
        return SBFX_ERR_INVALID_ARGUMENT;
    }
    sbfx_phase_resolve(&q.analytic_phase, &q.table_phase);
    *out = q;
    return SBFX_OK;
}

const char *sbfx_quality_name(const sbfx_quality *q, char *buf, size_t size)
{
    if (!buf || !size) return buf;
    sbfx_quality r = q ? *q : (sbfx_quality){0};
    if (!q || !sbfx_quality_resolve(&r, NULL, 0)) {
        snprintf(buf, size, "invalid");
        return buf;
    }
    char lod[16] = "";
    if (r.lod_particles) snprintf(lod, sizeof(lod), "/lod%d", r.lod_particles);
    snprintf(buf, size, "%s/%d/%s%s%s%s%s%s%s", opacity_tokens[r.opacity], r.target_divisor,
             upsample_tokens[r.upsample], r.target_format ? "/" : "", r.target_format ? format_tokens[r.target_format] : "",
             r.light_per_particle ? "/lpp" : "", r.analytic_blackbody ? "/abb" : "", r.table_phase ? "/tph" : "", lod);
    return buf;
}
