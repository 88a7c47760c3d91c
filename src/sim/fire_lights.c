/* Fire as light (issue 27; sim/fire_light.h has the model): the live fire particles gathered into a
 * few point lights — for the host (sbfx_emitted_lights), once per update when asked, and for the
 * frame's dust and smoke (render/particles.c), from the frame's view-space fire. */
#include <math.h>
#include <string.h>
#include "sim/sim.h"

/* The module's black body: its table (made at load with the fire), as the shader samples it. */
static void table_blackbody(const void *ctx, double kelvin, double rgb[3])
{
    const sbfx_tables *t = ctx;
    sbfx_blackbody_table_lookup(t->blackbody, SBFX_BLACKBODY_SIZE, t->blackbody_lo, t->blackbody_hi, kelvin, rgb);
}

sbfx_fire_model sbfx_fire_model_of(const sbfx *fx)
{
    const sbfx_medium_params *m = &fx->scene->media[SBFX_FIRE];
    sbfx_fire_model model = {.tau = m->tau, .t0 = m->t0, .t1 = m->t1, .cooling = m->cooling,
                             .soot = m->soot, .detail_strength = m->detail_strength,
                             .emission_scale = (double)m->emission_scale * (1.0 - m->albedo),
                             .ceiling = SBFX_RADIANCE_CEILING / fx->scene->desc.exposure,
                             .blackbody = table_blackbody, .blackbody_ctx = fx->tables};
    memcpy(model.detail, fx->sim->fire_detail, sizeof(model.detail));
    return model;
}

sbfx_result sbfx_fire_lights_create(sbfx *fx)
{
    if (!fx->scene->uses_medium[SBFX_FIRE]) return SBFX_OK; /* nothing to gather: no memory */
    size_t n = (size_t)fx->sim->pool.capacity;
    fx->sim->fire_particles = sbfx_calloc(fx, n, sizeof(*fx->sim->fire_particles));
    fx->sim->fire_work = sbfx_calloc(fx, n, sizeof(*fx->sim->fire_work));
    if (!fx->sim->fire_particles || !fx->sim->fire_work)
        return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "cannot allocate the fire lights' work memory");
    return SBFX_OK;
}

void sbfx_fire_lights_destroy(sbfx *fx)
{
    sbfx_free(fx, fx->sim->fire_particles);
    sbfx_free(fx, fx->sim->fire_work);
    fx->sim->fire_particles = NULL;
    fx->sim->fire_work = NULL;
}

/* The live fire of the pool (world space, whose delay has passed) gathered into fx->sim->emitted. */
static void gather_pool(sbfx *fx)
{
    const sbfx_pool *p = &fx->sim->pool;
    int n = 0;
    for (int i = 0; i < p->alive; i++) {
        if (p->medium[i] != SBFX_FIRE || p->age[i] < 0.0f) continue;
        float radius, intensity;
        sbfx_pool_particle_shape(p, i, &radius, &intensity);
        sbfx_fire_particle *f = &fx->sim->fire_particles[n++];
        for (int k = 0; k < 3; k++) f->position[k] = p->pos[3 * i + k];
        f->radius = radius;
        f->intensity = intensity;
    }
    sbfx_fire_model model = sbfx_fire_model_of(fx);
    fx->sim->emitted_count = sbfx_fire_gather(&model, fx->sim->fire_particles, n, fx->sim->fire_work, fx->sim->emitted,
                                         SBFX_MAX_POINT_LIGHTS);
    fx->sim->emitted_current = true;
    fx->counters.emitted_lights = fx->sim->emitted_count;
}

int sbfx_emitted_lights(sbfx *fx, sbfx_point_light *out, int max)
{
    if (!fx) return SBFX_ERR_INVALID_ARGUMENT;
    if (!out || max < 1 || max > SBFX_MAX_POINT_LIGHTS)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "sbfx_emitted_lights: %s (max %d): give an array of 1 .. %d "
                         "lights", out ? "max out of range" : "out is NULL", max, SBFX_MAX_POINT_LIGHTS);
    if (!fx->sim->fire_work) return 0;   /* the scene has no fire */
    if (!fx->sim->emitted_current) gather_pool(fx);
    int n = fx->sim->emitted_count < max ? fx->sim->emitted_count : max;
    for (int i = 0; i < n; i++) {
        const sbfx_fire_gathered *g = &fx->sim->emitted[i];
        for (int k = 0; k < 3; k++) {
            out[i].position[k] = (float)g->position[k];
            out[i].color[k] = (float)(g->intensity[k] / M_PI);
        }
        out[i].radius = (float)sbfx_fire_gathered_radius(g, fx->scene->desc.exposure);
    }
    return n;
}

void sbfx_fire_lights_of_frame(sbfx *fx, int count)
{
    int n = 0;
    for (int i = 0; i < count; i++) {
        const sbfx_view_particle *v = &fx->sim->view[i];
        if (v->medium != SBFX_FIRE) continue;
        sbfx_fire_particle *f = &fx->sim->fire_particles[n++];
        for (int k = 0; k < 3; k++) f->position[k] = v->center[k];
        f->radius = v->radius;
        f->intensity = v->intensity;
    }
    sbfx_fire_model model = sbfx_fire_model_of(fx);
    fx->sim->frame_fire_count = sbfx_fire_gather(&model, fx->sim->fire_particles, n, fx->sim->fire_work, fx->sim->frame_fire,
                                            SBFX_MAX_POINT_LIGHTS);
}
