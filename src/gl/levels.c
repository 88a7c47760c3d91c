/* Run-time quality (docs/design.md §6): what a level needs on the GPU, and switching between levels
 * without re-creating the module (level names: quality_name.c). The current level's choices live in
 * fx->desc (its quality fields) and in the current copies of fx->gl (particle programs,
 * composite, targets), so the passes read them as they always did. */
#include <stdio.h>
#include <string.h>
#include "module.h"

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
    sbfx_gl_enter(fx);
    sbfx_result result = sbfx_quality_apply(fx, &r);
    sbfx_gl_leave(fx, "sbfx_set_quality");
    return result;
}

sbfx_result sbfx_get_quality(const sbfx *fx, sbfx_quality *out)
{
    if (!fx || !out) return SBFX_ERR_INVALID_ARGUMENT;
    *out = fx->current;
    return SBFX_OK;
}
