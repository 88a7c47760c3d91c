/* The frame's particles in view space: the live particles whose delay has passed, shaped at
 * their age (radius, intensity), where they were at the previous render (velocity blur), bad
 * ones skipped and counted. The first step of a frame (sbfx.c, sbfx_render). */
#include <math.h>
#include <string.h>
#include "sim/sim.h"

bool sbfx_view_particle_valid(const sbfx_view_particle *p)
{
    const float *f[] = {p->center, p->detail};
    for (int a = 0; a < 2; a++)
        for (int i = 0; i < 3; i++)
            if (!isfinite(f[a][i])) return false;
    return isfinite(p->radius) && p->radius > 0.0f && isfinite(p->intensity) &&
           (unsigned)p->medium < SBFX_MEDIUM_COUNT;
}

static void transform_point(const float m[16], const float p[3], float out[3])
{
    for (int r = 0; r < 3; r++) out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

static float lifetime_curve(float x) { return 1.0f - (1.0f - x) * (1.0f - x); }

void sbfx_pool_particle_shape(const sbfx_pool *p, int i, float *radius, float *intensity)
{
    float x = p->age[i] / p->life[i];
    float fade = p->fade_in[i] > 0.0f ? fminf(1.0f, x / p->fade_in[i]) : 1.0f;
    *radius = p->radius0[i] + (p->radius1[i] - p->radius0[i]) * lifetime_curve(x);
    *intensity = (p->intensity0[i] + (p->intensity1[i] - p->intensity0[i]) * x) * fade;
}

/* Where the particle was at the previous render, seen by the previous camera (velocity blur
 * only; otherwise the current centre, which means no motion). */
static void previous_center(const sbfx *fx, const float pos[3], const float vel[3], const float view[16],
                            sbfx_view_particle *v)
{
    if (!fx->scene->plan.particle_velocity || !fx->sim->have_previous_view) {
        memcpy(v->previous_center, v->center, sizeof(v->center));
        return;
    }
    float dt = (float)(fx->sim->time - fx->sim->previous_render_time), before[3];
    for (int k = 0; k < 3; k++) before[k] = pos[k] - vel[k] * dt;
    transform_point(fx->sim->previous_view, before, v->previous_center);
    (void)view;
}

/* Live particles whose delay has passed, in view space, into fx->sim->view. */
int sbfx_collect_view_particles(sbfx *fx, const float view[16])
{
    const sbfx_pool *p = &fx->sim->pool;
    int n = 0;
    fx->counters.particles_skipped = 0;
    fx->sim->view_identified = false;
    for (int i = 0; i < p->alive; i++) {
        if (p->age[i] < 0.0f) continue;
        fx->sim->view_identified |= !isnan(p->start[i]);
        sbfx_view_particle *v = &fx->sim->view[n];
        transform_point(view, &p->pos[3 * i], v->center);
        sbfx_pool_particle_shape(p, i, &v->radius, &v->intensity);
        memcpy(v->detail, &p->detail[3 * i], sizeof(v->detail));
        v->medium = (sbfx_medium)p->medium[i];
        previous_center(fx, &p->pos[3 * i], &p->vel[3 * i], view, v);
        if (sbfx_view_particle_valid(v)) n++;
        else fx->counters.particles_skipped++;
    }
    return n;
}

int sbfx_frame_particles(sbfx *fx, const float view[16], const sbfx_view_particle **out)
{
    int n = sbfx_collect_view_particles(fx, view);
    *out = fx->sim->view;
    return n;
}

/* The view and the clock of the frame just rendered: where particles were then (velocity blur). */
void sbfx_view_rendered(sbfx *fx, const float view[16])
{
    memcpy(fx->sim->previous_view, view, 16 * sizeof(float));
    fx->sim->previous_render_time = fx->sim->time;
    fx->sim->have_previous_view = true;
}
