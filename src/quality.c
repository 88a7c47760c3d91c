/* Run-time quality (DESIGN §6): level names, what a level needs on the GPU, and switching
 * between levels without re-creating the module. The current level's choices live in
 * fx->desc (its quality fields) and in the current copies of fx->gl (particle programs,
 * composite, targets), so the passes read them as they always did. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "module.h"

#define LOD_MAX (1 << 20)

static const char *const opacity_tokens[SBFX_OPACITY_COUNT] = {
    [SBFX_OPACITY_PLANAR] = "planar", [SBFX_OPACITY_SOFT] = "soft", [SBFX_OPACITY_SPHERICAL] = "spherical",
    [SBFX_OPACITY_EXACT] = "exact",   [SBFX_OPACITY_FLOOR] = "floor", /* named, not parsed: bench only */
};
static const char *const upsample_tokens[SBFX_UPSAMPLE_COUNT] = {
    [SBFX_UPSAMPLE_BILINEAR] = "bl", [SBFX_UPSAMPLE_NEAREST_DEPTH] = "nd"};
static const char *const format_tokens[SBFX_FORMAT_COUNT] = {
    [SBFX_FORMAT_RGBA8] = "rgba8", [SBFX_FORMAT_RGBA16F] = "rgba16f", [SBFX_FORMAT_RGBA32F] = "rgba32f"};

sbfx_quality sbfx_quality_from_desc(const sbfx_desc *d)
{
    return (sbfx_quality){d->opacity, d->target_divisor, d->upsample, d->target_format, d->light_per_particle,
                          d->analytic_blackbody, d->analytic_phase, d->lod_particles};
}

bool sbfx_quality_resolve(sbfx_quality *q, char *err, size_t size)
{
    if (!q->opacity) q->opacity = SBFX_OPACITY_EXACT;
    if (!q->target_divisor) q->target_divisor = 4;
    if (!q->upsample) q->upsample = SBFX_UPSAMPLE_NEAREST_DEPTH;
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
           a->analytic_blackbody == b->analytic_blackbody && a->analytic_phase == b->analytic_phase &&
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
                 : strcmp(t, "aph") == 0 ? &q->analytic_phase : NULL;
    int format = token_index(format_tokens, SBFX_FORMAT_COUNT, t);
    if (flag || format) {
        if (flag ? *flag : q->target_format != 0) {
            snprintf(err, size, flag ? "'%s' given twice" : "'%s': a second target format", t);
            return -1;
        }
        if (flag) *flag = true;
        else q->target_format = (sbfx_target_format)format;
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
    snprintf(err, size, "unknown flag '%.40s' (rgba8, rgba16f, rgba32f, lpp, abb, aph, lodN with N in 1..%d)", t, LOD_MAX);
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
        if (!q->upsample) snprintf(err, size, "unknown upsample '%s' (nd, bl)", t);
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
             r.light_per_particle ? "/lpp" : "", r.analytic_blackbody ? "/abb" : "", r.analytic_phase ? "/aph" : "", lod);
    return buf;
}

/* ---- what a level needs --------------------------------------------------------------------- */

static bool any_phase_medium(const sbfx *fx)
{
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (sbfx_medium_uses_phase(fx, (sbfx_medium)m)) return true;
    return false;
}

/* Only what a loaded medium is affected by: levels that differ elsewhere share programs. */
sbfx_variant_key sbfx_variant_key_of(const sbfx *fx, const sbfx_quality *q)
{
    bool phase = any_phase_medium(fx);
    return (sbfx_variant_key){
        .opacity = q->opacity,
        .lpp = q->light_per_particle && phase,
        .abb = fx->uses_medium[SBFX_FIRE] && (q->analytic_blackbody || fx->tables.blackbody_missed),
        .aph = q->analytic_phase && phase,
    };
}

int sbfx_variant_index(const sbfx_variant_key *k)
{
    return (int)k->opacity * 8 + (k->lpp ? 4 : 0) + (k->abb ? 2 : 0) + (k->aph ? 1 : 0);
}

/* The default format asks for RGBA16F: both share a target. */
int sbfx_target_index(int divisor, sbfx_target_format format)
{
    int log2 = divisor == 1 ? 0 : divisor == 2 ? 1 : divisor == 4 ? 2 : 3;
    return log2 * SBFX_FORMAT_COUNT + (int)(format ? format : SBFX_FORMAT_RGBA16F);
}

bool sbfx_quality_uses_blackbody_table(const sbfx *fx, const sbfx_quality *q)
{
    return fx->uses_medium[SBFX_FIRE] && !q->analytic_blackbody && !fx->tables.blackbody_missed;
}

bool sbfx_quality_uses_blackbody_analytic(const sbfx *fx, const sbfx_quality *q)
{
    return fx->uses_medium[SBFX_FIRE] && (q->analytic_blackbody || fx->tables.blackbody_missed);
}

bool sbfx_quality_uses_phase_table(const sbfx *fx, const sbfx_quality *q)
{
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (sbfx_medium_uses_phase(fx, (sbfx_medium)m) && !q->analytic_phase && !fx->tables.phase_missed[m])
            return true;
    return false;
}

bool sbfx_declared_any(const sbfx *fx, bool (*uses)(const sbfx *, const sbfx_quality *))
{
    for (int i = 0; i < fx->declared_count; i++)
        if (uses(fx, &fx->declared[i])) return true;
    return false;
}

bool sbfx_quality_uses_light_slot(const sbfx *fx, const sbfx_quality *q) { return q->light_per_particle; }

/* ---- building and switching ----------------------------------------------------------------- */

static bool missing(const sbfx *fx, const sbfx_quality *q)
{
    sbfx_variant_key key = sbfx_variant_key_of(fx, q);
    return !fx->gl.variants[sbfx_variant_index(&key)].built || !fx->gl.composites[q->upsample] ||
           (sbfx_quality_uses_blackbody_table(fx, q) && !fx->gl.blackbody_texture) ||
           (sbfx_quality_uses_blackbody_analytic(fx, q) && !fx->cmf_rgb) ||
           (sbfx_quality_uses_phase_table(fx, q) && !fx->gl.phase_texture) ||
           (q->light_per_particle && !fx->instance_light) || (q->lod_particles && !fx->lod_work);
}

/* What q's first use needs; called inside a saved state (load_gl's, or build_first_use's). */
static sbfx_result build(sbfx *fx, const sbfx_quality *q)
{
    sbfx_result r = SBFX_OK;
    sbfx_variant_key key = sbfx_variant_key_of(fx, q);
    if (sbfx_quality_uses_blackbody_table(fx, q) && !fx->gl.blackbody_texture) r = sbfx_tables_upload_blackbody(fx);
    if (r == SBFX_OK && sbfx_quality_uses_blackbody_analytic(fx, q) && !fx->cmf_rgb) r = sbfx_blackbody_constants_load(fx);
    if (r == SBFX_OK && sbfx_quality_uses_phase_table(fx, q) && !fx->gl.phase_texture) r = sbfx_tables_upload_phase(fx);
    if (r == SBFX_OK && q->light_per_particle && !fx->instance_light) r = sbfx_instances_reserve_light(fx);
    if (r == SBFX_OK && q->lod_particles && !fx->lod_work) r = sbfx_lod_create(fx);
    if (r == SBFX_OK) r = sbfx_variant_build(fx, &key);
    if (r == SBFX_OK) r = sbfx_composite_build(fx, q->upsample);
    return r;
}

/* A level's first use after load: the GL objects it needs, inside a save and restore of what
 * making them changes (as at load). */
static sbfx_result build_first_use(sbfx *fx, const sbfx_quality *q)
{
    const sbfx_gl_units unit0 = {1u, 1u, 1u};
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_OBJECTS | SBFX_GL_SAVE_UNPACK, &unit0);
    sbfx_result r = build(fx, q);
    sbfx_gl_state_restore(&saved);
    return r;
}

/* Points the module's current state at q (everything exists). */
static void point(sbfx *fx, const sbfx_quality *q)
{
    sbfx_gl *gl = &fx->gl;
    sbfx_variant_key key = sbfx_variant_key_of(fx, q);
    memcpy(gl->particle, gl->variants[sbfx_variant_index(&key)].particle, sizeof(gl->particle));
    gl->composite_program = gl->composites[q->upsample];
    gl->composite_u = gl->composite_us[q->upsample];
    sbfx_desc *d = &fx->desc;
    d->opacity = q->opacity, d->target_divisor = q->target_divisor, d->upsample = q->upsample;
    d->target_format = q->target_format, d->light_per_particle = q->light_per_particle;
    d->analytic_blackbody = q->analytic_blackbody, d->analytic_phase = q->analytic_phase;
    d->lod_particles = q->lod_particles;
    sbfx_tables *t = &fx->tables;
    t->blackbody_analytic = q->analytic_blackbody || t->blackbody_missed;
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) {
        if (!sbfx_medium_uses_phase(fx, (sbfx_medium)m)) continue;
        t->phase_analytic[m] = q->analytic_phase || t->phase_missed[m];
        t->phase_table[m] = !t->phase_analytic[m];
    }
    fx->current = *q;
    sbfx_quality_name(q, fx->counters.quality, sizeof(fx->counters.quality));
}

sbfx_result sbfx_quality_load(sbfx *fx)
{
    for (int i = 0; i < fx->declared_count; i++) {
        sbfx_result r = build(fx, &fx->declared[i]);
        if (r != SBFX_OK) return r;
    }
    point(fx, &fx->top);
    return SBFX_OK;
}

sbfx_result sbfx_quality_apply(sbfx *fx, const sbfx_quality *q)
{
    if (missing(fx, q)) {
        sbfx_result r = build_first_use(fx, q);
        if (r != SBFX_OK) return r;
    }
    point(fx, q);
    return SBFX_OK;
}

/* ---- public entry points -------------------------------------------------------------------- */

sbfx_result sbfx_set_quality(sbfx *fx, const sbfx_quality *q)
{
    if (!fx || !q) return SBFX_ERR_INVALID_ARGUMENT;
    sbfx_quality r = *q;
    char why[128];
    if (!sbfx_quality_resolve(&r, why, sizeof(why))) return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "sbfx_set_quality: %s", why);
    if (r.opacity == SBFX_OPACITY_FLOOR)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "sbfx_set_quality: the floor opacity is for benchmarks only");
    if (sbfx_budget_active(fx))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "sbfx_set_quality: the frame budget chooses the level "
                         "(create the module without frame_budget_ms to choose it yourself)");
    if (sbfx_quality_equal(&r, &fx->current)) return SBFX_OK;
    return sbfx_quality_apply(fx, &r);
}

sbfx_result sbfx_get_quality(const sbfx *fx, sbfx_quality *out)
{
    if (!fx || !out) return SBFX_ERR_INVALID_ARGUMENT;
    *out = fx->current;
    return SBFX_OK;
}
