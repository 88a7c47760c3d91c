/* The black-body and phase tables of the loaded scene (scene_tables.h; docs/design.md §2.3, §4):
 * ranges from what the scene can produce, the tables built in double (tables/blackbody.c,
 * tables/phase.c) and stored as float, checked against their functions at load. A medium whose
 * table would miss the tolerance (SBFX_TABLE_TOLERANCE, less what the shader's float arithmetic
 * may add) evaluates its function per fragment instead; the log says so once. The GPU's copies
 * are uploaded by the gl room (gl/luts.c). */
#include <math.h>
#include <string.h>
#include "scene/scene_tables.h"

static const char *const medium_names[SBFX_MEDIUM_COUNT] = {"dust", "smoke", "fire", "heat"};

/* ---- black body ----------------------------------------------------------------------------- */

/* The temperatures the scene's fire can reach: T = (t0 + t1 d)(1 - cooling (1 - I)) with the
 * detail d in [0, 1] and the intensity I anywhere between its emitters' ends (0 while an
 * emitter fades in). Light flashes are lights of a given colour: they add no temperature. */
static void fire_temperatures(const sbfx *fx, double *coolest, double *hottest)
{
    const sbfx_medium_params *m = &fx->scene->media[SBFX_FIRE];
    *coolest = INFINITY, *hottest = 0.0;
    for (int e = 0; e < fx->scene->effect_count; e++)
        for (int i = 0; i < fx->scene->effects[e].emitter_count; i++) {
            const sbfx_emitter *em = &fx->scene->effects[e].emitters[i];
            if (em->medium != SBFX_FIRE) continue;
            double low = fmin(em->intensity_start, em->intensity_end), high = fmax(em->intensity_start, em->intensity_end);
            if (em->fade_in > 0.0f) low = 0.0;
            *coolest = fmin(*coolest, m->t0 * (1.0 - m->cooling * (1.0 - low)));
            *hottest = fmax(*hottest, (m->t0 + m->t1) * (1.0 - m->cooling * (1.0 - high)));
        }
    if (*coolest > *hottest) *coolest = *hottest = 0.0; /* fire drawn by hand (tests): no emitter */
}

/* [lo, hi] with a margin beyond what the scene reaches; nothing below 500 K (there the light is
 * under 1e-19 of the unit's, and the lookup's Wien extrapolation carries on to 0 at T = 0). */
static void blackbody_range(const sbfx *fx, double *lo, double *hi)
{
    double coolest, hottest;
    fire_temperatures(fx, &coolest, &hottest);
    *lo = fmax(SBFX_BLACKBODY_MIN_KELVIN, coolest / SBFX_BLACKBODY_MARGIN);
    *hi = fmax(hottest * SBFX_BLACKBODY_MARGIN, 2.0 * *lo);
}

static sbfx_result make_blackbody(sbfx *fx, const sbfx_cmf *cmf)
{
    sbfx_tables *t = fx->tables;
    t->blackbody = sbfx_calloc(fx, SBFX_BLACKBODY_SIZE * 4, sizeof(float));
    if (!t->blackbody) return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "out of memory");
    blackbody_range(fx, &t->blackbody_lo, &t->blackbody_hi);
    t->blackbody_norm = sbfx_blackbody_norm(cmf, fx->scene->desc.blackbody_max_kelvin);
    sbfx_blackbody_table(cmf, t->blackbody_norm, t->blackbody_lo, t->blackbody_hi, SBFX_BLACKBODY_SIZE, t->blackbody);
    t->blackbody_error = sbfx_blackbody_table_error(cmf, t->blackbody_norm, t->blackbody, SBFX_BLACKBODY_SIZE,
                                                    t->blackbody_lo, t->blackbody_hi);
    t->blackbody_missed = !(t->blackbody_error <= SBFX_TABLE_TOLERANCE - SBFX_TABLE_GPU_ALLOWANCE);
    t->blackbody_analytic = fx->scene->desc.analytic_blackbody || t->blackbody_missed;
    if (t->blackbody_missed) {
        sbfx_log(fx, SBFX_LOG_WARN, "media.fire: the black-body table over %.0f..%.0f K would be %.2g off "
                 "Planck x CIE (a table may be %.0e off: %.0e less what the shader's float arithmetic adds): "
                 "fire evaluates it per fragment instead", t->blackbody_lo, t->blackbody_hi, t->blackbody_error,
                 SBFX_TABLE_TOLERANCE - SBFX_TABLE_GPU_ALLOWANCE, SBFX_TABLE_TOLERANCE);
    }
    return SBFX_OK;
}

/* ---- phase function ------------------------------------------------------------------------- */

/* Scatters light through the phase function: uses the medium, has albedo, is not lit the
 * lit-smoke way (heat neither absorbs nor scatters). */
bool sbfx_medium_uses_phase(const sbfx *fx, sbfx_medium m)
{
    const sbfx_medium_params *p = &fx->scene->media[m];
    return fx->scene->uses_medium[m] && m != SBFX_HEAT && p->albedo > 0 && !p->lit;
}

static void decide_phase(sbfx *fx, sbfx_medium m)
{
    sbfx_tables *t = fx->tables;
    float *row = t->phase + (size_t)m * SBFX_PHASE_SIZE;
    double g = fx->scene->media[m].phase_g;
    sbfx_phase_table(g, SBFX_PHASE_SIZE, row);
    t->phase_error[m] = sbfx_phase_table_error(row, SBFX_PHASE_SIZE, g);
    t->phase_missed[m] = !(t->phase_error[m] <= SBFX_TABLE_TOLERANCE - SBFX_TABLE_GPU_ALLOWANCE);
    t->phase_analytic[m] = fx->scene->desc.analytic_phase || t->phase_missed[m];
    if (t->phase_missed[m]) {
        sbfx_log(fx, SBFX_LOG_WARN, "media.%s: its %d-entry phase table for phase_g = %g would be %.2g off the "
                 "function (a table may be %.0e off: %.0e less what the shader's float arithmetic adds): %s "
                 "evaluates the phase function per fragment instead", medium_names[m], SBFX_PHASE_SIZE, g,
                 t->phase_error[m], SBFX_TABLE_TOLERANCE - SBFX_TABLE_GPU_ALLOWANCE, SBFX_TABLE_TOLERANCE,
                 medium_names[m]);
    }
    t->phase_table[m] = !t->phase_analytic[m];
}

static sbfx_result make_phase(sbfx *fx)
{
    sbfx_tables *t = fx->tables;
    t->phase = sbfx_calloc(fx, (size_t)SBFX_MEDIUM_COUNT * SBFX_PHASE_SIZE, sizeof(float));
    if (!t->phase) return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "out of memory");
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (sbfx_medium_uses_phase(fx, (sbfx_medium)m)) decide_phase(fx, (sbfx_medium)m);
    return SBFX_OK;
}

/* ---- lifetime ------------------------------------------------------------------------------- */

static sbfx_result tables_create(sbfx *fx, const sbfx_cmf *cmf)
{
    sbfx_result r = SBFX_OK;
    memset(fx->tables, 0, sizeof(*fx->tables));
    if (cmf && (r = make_blackbody(fx, cmf)) != SBFX_OK) return r;
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (sbfx_medium_uses_phase(fx, (sbfx_medium)m)) return make_phase(fx);
    return SBFX_OK;
}

const sbfx_tables *sbfx_get_tables(const sbfx *fx) { return fx->tables; }

/* ---- the analytic black body, fire's photometry ------------------------------------------- */

/* The analytic black body sums Planck x CMF per fragment; the per-band constants fold the
 * XYZ -> sRGB matrix, the trapezoid weight, 2hc² (with λ in µm) and the table's normalisation,
 * so the shader's sum equals the table's value at every temperature. */
#define PLANCK_C1L_UM (2.0 * 6.62607015e-34 * 299792458.0 * 299792458.0 * 1e30)

static sbfx_result prepare_analytic_blackbody(sbfx *fx, const sbfx_cmf *cmf)
{
    fx->tables->cmf_rgb = sbfx_calloc(fx, (size_t)cmf->bands * 3, sizeof(float));
    fx->tables->cmf_band = sbfx_calloc(fx, (size_t)cmf->bands, sizeof(float));
    if (!fx->tables->cmf_rgb || !fx->tables->cmf_band) return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "out of memory");
    double norm = fx->tables->blackbody_norm, step_m = cmf->step_nm * 1e-9;
    for (int i = 0; i < cmf->bands; i++) {
        double weight = (i == 0 || i == cmf->bands - 1) ? 0.5 * step_m : step_m;
        double xyz[3] = {cmf->xyz[0][i], cmf->xyz[1][i], cmf->xyz[2][i]}, rgb[3];
        sbfx_xyz_to_linear_srgb(xyz, rgb);
        for (int k = 0; k < 3; k++) fx->tables->cmf_rgb[3 * i + k] = (float)(rgb[k] * weight * PLANCK_C1L_UM * norm);
        fx->tables->cmf_band[i] = (float)((cmf->start_nm + cmf->step_nm * i) * 1e-3);
    }
    fx->tables->cmf_bands = cmf->bands;
    return SBFX_OK;
}

/* Fire given an emissivity emits black-body luminance in the scene's unit (docs/look-fire.md). */
static void set_photometric_emission(sbfx *fx)
{
    sbfx_medium_params *m = &fx->scene->media[SBFX_FIRE];
    if (m->emissivity > 0.0f)
        m->emission_scale = (float)sbfx_emission_scale_photometric(fx->tables->blackbody_norm, m->emissivity,
                                                                   fx->scene->desc.white_luminance);
}

/* The compiled-in CIE tables feed the black-body table, or the analytic black body's per-band
 * constants (whose shader array, MAX_BANDS in particle.frag, must hold every band). */
static sbfx_result make_fire_tables(sbfx *fx)
{
    sbfx_result r = tables_create(fx, &sbfx_cie1931_2deg);
    if (r == SBFX_OK && !fx->loaded) set_photometric_emission(fx); /* once: sbfx_reload keeps what was set */
    if (r == SBFX_OK && sbfx_declared_any(fx, sbfx_quality_uses_blackbody_analytic))
        r = prepare_analytic_blackbody(fx, &sbfx_cie1931_2deg);
    return r;
}

sbfx_result sbfx_scene_tables_create(sbfx *fx)
{
    return fx->scene->uses_medium[SBFX_FIRE] ? make_fire_tables(fx) : tables_create(fx, NULL);
}

void sbfx_scene_tables_destroy(sbfx *fx)
{
    sbfx_free(fx, fx->tables->blackbody);
    sbfx_free(fx, fx->tables->phase);
    sbfx_free(fx, fx->tables->cmf_rgb);
    sbfx_free(fx, fx->tables->cmf_band);
    memset(fx->tables, 0, sizeof(*fx->tables));
}

sbfx_result sbfx_blackbody_constants_load(sbfx *fx)
{
    return prepare_analytic_blackbody(fx, &sbfx_cie1931_2deg);
}

/* ---- what a quality level uses of them ---------------------------------------------------- */

bool sbfx_quality_uses_blackbody_table(const sbfx *fx, const sbfx_quality *q)
{
    return fx->scene->uses_medium[SBFX_FIRE] && !q->analytic_blackbody && !fx->tables->blackbody_missed;
}

bool sbfx_quality_uses_blackbody_analytic(const sbfx *fx, const sbfx_quality *q)
{
    return fx->scene->uses_medium[SBFX_FIRE] && (q->analytic_blackbody || fx->tables->blackbody_missed);
}

bool sbfx_quality_uses_phase_table(const sbfx *fx, const sbfx_quality *q)
{
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (sbfx_medium_uses_phase(fx, (sbfx_medium)m) && !q->analytic_phase && !fx->tables->phase_missed[m])
            return true;
    return false;
}
