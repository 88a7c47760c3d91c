/* Run-time quality (docs/design.md §6) on the GPU: what a level needs (its particle programs, its
 * composite, the tables it samples), made at load for every declared level or at its first use,
 * and switching between levels without re-creating the module (level names:
 * scene/quality_name.c; the frame budget that switches: budget/). The current level's choices
 * live in fx->scene->desc (its quality fields) and in the current copies of fx->gl (particle programs,
 * composite, targets), so the passes read them as they always did. */
#include <stdio.h>
#include <string.h>
#include "gl/gl.h"

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
        .abb = fx->scene->uses_medium[SBFX_FIRE] && (q->analytic_blackbody || fx->tables->blackbody_missed),
        .aph = q->analytic_phase && phase,
    };
}

/* ---- building and switching ----------------------------------------------------------------- */

static bool missing(const sbfx *fx, const sbfx_quality *q)
{
    sbfx_variant_key key = sbfx_variant_key_of(fx, q);
    return !fx->gl->variants[sbfx_variant_index(&key)].built || !fx->gl->composites[q->upsample] ||
           (sbfx_quality_uses_blackbody_table(fx, q) && !fx->gl->blackbody_texture) ||
           (sbfx_quality_uses_blackbody_analytic(fx, q) && !fx->tables->cmf_rgb) ||
           (sbfx_quality_uses_phase_table(fx, q) && !fx->gl->phase_texture) ||
           (q->light_per_particle && !fx->scene->instance_light) || (q->lod_particles && !fx->sim->lod_work);
}

/* What q's first use needs; called inside a saved state (load_gl's, or build_first_use's). */
static sbfx_result build(sbfx *fx, const sbfx_quality *q)
{
    sbfx_result r = SBFX_OK;
    sbfx_variant_key key = sbfx_variant_key_of(fx, q);
    if (sbfx_quality_uses_blackbody_table(fx, q) && !fx->gl->blackbody_texture) r = sbfx_tables_upload_blackbody(fx);
    if (r == SBFX_OK && sbfx_quality_uses_blackbody_analytic(fx, q) && !fx->tables->cmf_rgb) r = sbfx_blackbody_constants_load(fx);
    if (r == SBFX_OK && sbfx_quality_uses_phase_table(fx, q) && !fx->gl->phase_texture) r = sbfx_tables_upload_phase(fx);
    if (r == SBFX_OK && q->light_per_particle && !fx->scene->instance_light) r = sbfx_instances_reserve_light(fx);
    if (r == SBFX_OK && q->lod_particles && !fx->sim->lod_work) r = sbfx_lod_create(fx);
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
    sbfx_gl *gl = fx->gl;
    sbfx_variant_key key = sbfx_variant_key_of(fx, q);
    memcpy(gl->particle, gl->variants[sbfx_variant_index(&key)].particle, sizeof(gl->particle));
    gl->composite_program = gl->composites[q->upsample];
    gl->composite_u = gl->composite_us[q->upsample];
    sbfx_desc *d = &fx->scene->desc;
    d->opacity = q->opacity, d->target_divisor = q->target_divisor, d->upsample = q->upsample;
    d->target_format = q->target_format, d->light_per_particle = q->light_per_particle;
    d->analytic_blackbody = q->analytic_blackbody, d->analytic_phase = q->analytic_phase, d->table_phase = q->table_phase;
    d->lod_particles = q->lod_particles;
    sbfx_tables *t = fx->tables;
    t->blackbody_analytic = q->analytic_blackbody || t->blackbody_missed;
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) {
        if (!sbfx_medium_uses_phase(fx, (sbfx_medium)m)) continue;
        t->phase_analytic[m] = q->analytic_phase || t->phase_missed[m];
        t->phase_table[m] = !t->phase_analytic[m];
    }
    fx->scene->current = *q;
    sbfx_quality_name(q, fx->counters.quality, sizeof(fx->counters.quality));
}

sbfx_result sbfx_quality_load(sbfx *fx)
{
    for (int i = 0; i < fx->scene->declared_count; i++) {
        sbfx_result r = build(fx, &fx->scene->declared[i]);
        if (r != SBFX_OK) return r;
    }
    point(fx, &fx->scene->top);
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

/* Test and tool entry points may set more lights than the scene has: the particle programs
 * are made again, with the larger loop, the next time the current level is applied. */
void sbfx_light_slots_reserve(sbfx *fx, int count)
{
    if (count <= fx->scene->light_slots) return;
    fx->scene->light_slots = count;
    bool built = false;
    for (int v = 0; v < SBFX_VARIANTS; v++) {
        sbfx_variant *var = &fx->gl->variants[v];
        for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) {
            if (!var->particle[m].id) continue;
            sbfx_program_delete(fx, var->particle[m].id);
            var->particle[m].id = 0;
            fx->counters.programs--;
        }
        built = built || var->built;
        var->built = false;
    }
    if (!built) return;   /* before load: the programs are made with the new size */
    sbfx_result r = sbfx_quality_apply(fx, &fx->scene->current);
    if (r != SBFX_OK) sbfx_log(fx, SBFX_LOG_ERROR, "rebuilding the particle programs for %d lights failed", count);
}
