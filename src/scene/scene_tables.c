/* The black-body and phase tables of the loaded scene (docs/design.md §2.3, §4): ranges from what the
 * scene can produce, the tables built in double (blackbody.c, phase.c) and stored as float,
 * checked against their functions at load, and uploaded. A medium whose table would miss the
 * tolerance (SBFX_TABLE_TOLERANCE, less what the shader's float arithmetic may add) evaluates
 * its function per fragment instead; the log says so once. */
#include <math.h>
#include <string.h>
#include "module.h"

static const char *const medium_names[SBFX_MEDIUM_COUNT] = {"dust", "smoke", "fire", "heat"};

static GLuint make_table_texture(sbfx *fx, GLenum internal, GLenum format, int w, int h, const float *texels)
{
    /* texelFetch only: NEAREST keeps the texture complete (float is not filterable in ES 3.0) */
    GLuint tex = sbfx_texture_create(fx, GL_TEXTURE_2D, GL_NEAREST, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, format, GL_FLOAT, texels);
    fx->counters.gpu_bytes += (size_t)w * h * (format == GL_RGBA ? 16 : 4);
    return tex;
}

/* ---- black body ----------------------------------------------------------------------------- */

/* The temperatures the scene's fire can reach: T = (t0 + t1 d)(1 - cooling (1 - I)) with the
 * detail d in [0, 1] and the intensity I anywhere between its emitters' ends (0 while an
 * emitter fades in). Light flashes are lights of a given colour: they add no temperature. */
static void fire_temperatures(const sbfx *fx, double *coolest, double *hottest)
{
    const sbfx_medium_params *m = &fx->media[SBFX_FIRE];
    *coolest = INFINITY, *hottest = 0.0;
    for (int e = 0; e < fx->effect_count; e++)
        for (int i = 0; i < fx->effects[e].emitter_count; i++) {
            const sbfx_emitter *em = &fx->effects[e].emitters[i];
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
    sbfx_tables *t = &fx->tables;
    t->blackbody = sbfx_calloc(fx, SBFX_BLACKBODY_SIZE * 4, sizeof(float));
    if (!t->blackbody) return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "out of memory");
    blackbody_range(fx, &t->blackbody_lo, &t->blackbody_hi);
    t->blackbody_norm = sbfx_blackbody_norm(cmf, fx->desc.blackbody_max_kelvin);
    sbfx_blackbody_table(cmf, t->blackbody_norm, t->blackbody_lo, t->blackbody_hi, SBFX_BLACKBODY_SIZE, t->blackbody);
    t->blackbody_error = sbfx_blackbody_table_error(cmf, t->blackbody_norm, t->blackbody, SBFX_BLACKBODY_SIZE,
                                                    t->blackbody_lo, t->blackbody_hi);
    t->blackbody_missed = !(t->blackbody_error <= SBFX_TABLE_TOLERANCE - SBFX_TABLE_GPU_ALLOWANCE);
    t->blackbody_analytic = fx->desc.analytic_blackbody || t->blackbody_missed;
    if (t->blackbody_missed) {
        sbfx_log(fx, SBFX_LOG_WARN, "media.fire: the black-body table over %.0f..%.0f K would be %.2g off "
                 "Planck x CIE (a table may be %.0e off: %.0e less what the shader's float arithmetic adds): "
                 "fire evaluates it per fragment instead", t->blackbody_lo, t->blackbody_hi, t->blackbody_error,
                 SBFX_TABLE_TOLERANCE - SBFX_TABLE_GPU_ALLOWANCE, SBFX_TABLE_TOLERANCE);
    }
    return sbfx_declared_any(fx, sbfx_quality_uses_blackbody_table) ? sbfx_tables_upload_blackbody(fx) : SBFX_OK;
}

sbfx_result sbfx_tables_upload_blackbody(sbfx *fx)
{
    fx->gl.blackbody_texture = make_table_texture(fx, GL_RGBA32F, GL_RGBA, SBFX_BLACKBODY_SIZE, 1, fx->tables.blackbody);
    return sbfx_gl_check(fx, "uploading the black-body table") ? SBFX_OK : SBFX_ERR_GL;
}

/* ---- phase function ------------------------------------------------------------------------- */

/* Scatters light through the phase function: uses the medium, has albedo, is not lit the
 * lit-smoke way (heat neither absorbs nor scatters). */
bool sbfx_medium_uses_phase(const sbfx *fx, sbfx_medium m)
{
    const sbfx_medium_params *p = &fx->media[m];
    return fx->uses_medium[m] && m != SBFX_HEAT && p->albedo > 0 && !p->lit;
}

static void decide_phase(sbfx *fx, sbfx_medium m)
{
    sbfx_tables *t = &fx->tables;
    float *row = t->phase + (size_t)m * SBFX_PHASE_SIZE;
    double g = fx->media[m].phase_g;
    sbfx_phase_table(g, SBFX_PHASE_SIZE, row);
    t->phase_error[m] = sbfx_phase_table_error(row, SBFX_PHASE_SIZE, g);
    t->phase_missed[m] = !(t->phase_error[m] <= SBFX_TABLE_TOLERANCE - SBFX_TABLE_GPU_ALLOWANCE);
    t->phase_analytic[m] = fx->desc.analytic_phase || t->phase_missed[m];
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
    sbfx_tables *t = &fx->tables;
    t->phase = sbfx_calloc(fx, (size_t)SBFX_MEDIUM_COUNT * SBFX_PHASE_SIZE, sizeof(float));
    if (!t->phase) return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "out of memory");
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (sbfx_medium_uses_phase(fx, (sbfx_medium)m)) decide_phase(fx, (sbfx_medium)m);
    return sbfx_declared_any(fx, sbfx_quality_uses_phase_table) ? sbfx_tables_upload_phase(fx) : SBFX_OK;
}

sbfx_result sbfx_tables_upload_phase(sbfx *fx)
{
    fx->gl.phase_texture = make_table_texture(fx, GL_R32F, GL_RED, SBFX_PHASE_SIZE, SBFX_MEDIUM_COUNT, fx->tables.phase);
    return sbfx_gl_check(fx, "uploading the phase-function table") ? SBFX_OK : SBFX_ERR_GL;
}

/* ---- lifetime and binding ------------------------------------------------------------------- */

sbfx_result sbfx_tables_create(sbfx *fx, const sbfx_cmf *cmf)
{
    sbfx_result r = SBFX_OK;
    memset(&fx->tables, 0, sizeof(fx->tables));
    if (cmf && (r = make_blackbody(fx, cmf)) != SBFX_OK) return r;
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (sbfx_medium_uses_phase(fx, (sbfx_medium)m)) return make_phase(fx);
    return SBFX_OK;
}

void sbfx_tables_destroy(sbfx *fx)
{
    GLuint textures[] = {fx->gl.blackbody_texture, fx->gl.phase_texture};
    glDeleteTextures((GLsizei)ARRAY_SIZE(textures), textures);
    fx->gl.blackbody_texture = fx->gl.phase_texture = 0;
    sbfx_free(fx, fx->tables.blackbody);
    sbfx_free(fx, fx->tables.phase);
    memset(&fx->tables, 0, sizeof(fx->tables));
}

const sbfx_tables *sbfx_get_tables(const sbfx *fx) { return &fx->tables; }

/* The shader's mappings (particle.frag's blackbody() and phase()): position in entries of
 * 1/T, and the coordinate of sbfx_phase_coordinate() folded into scale and offset. */
void sbfx_tables_bind(const sbfx *fx, const sbfx_program *p, sbfx_medium m)
{
    const sbfx_tables *t = &fx->tables;
    /* only the tables that exist: their units are the ones the frame saves (passes.c) */
    if (fx->gl.phase_texture) sbfx_bind_texture(SBFX_UNIT_PHASE, GL_TEXTURE_2D, fx->gl.phase_texture, 0);
    if (fx->gl.blackbody_texture)
        sbfx_bind_texture(SBFX_UNIT_BLACKBODY, GL_TEXTURE_2D, fx->gl.blackbody_texture, 0);
    glUniform1i(p->phase_lut, SBFX_UNIT_PHASE);
    glUniform1i(p->blackbody, SBFX_UNIT_BLACKBODY);
    double lo = t->blackbody_lo > 0 ? t->blackbody_lo : 1.0, hi = t->blackbody_hi > lo ? t->blackbody_hi : 2.0 * lo;
    glUniform3f(p->blackbody_map, (float)(1.0 / hi), (float)((SBFX_BLACKBODY_SIZE - 1) / (1.0 / lo - 1.0 / hi)),
                (float)(SBFX_BLACKBODY_SIZE - 2));
    double g = fx->media[m].phase_g, a = fmin(fabs(g), SBFX_PHASE_G_MAX);
    double back = (1.0 + a) * (1.0 + a), peak = (1.0 - a) * (1.0 - a);
    bool warp = a >= SBFX_PHASE_WARP_MIN_G;
    double k = warp ? 1.0 / log(peak / back) : 0.0;
    glUniform4f(p->phase_warp, g < 0.0 ? -1.0f : 1.0f, (float)peak, warp ? (float)(2.0 * a) : 0.0f, (float)k);
    glUniform2f(p->phase_shift, (float)(-log(back) * k), (float)(SBFX_PHASE_SIZE - 1));
    glUniform1i(p->phase_row, (GLint)m);
    glUniform1f(p->g, (float)g);
}
