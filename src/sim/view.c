/* One frame, as the seed's figure 9 draws it:
 *   collect live particles (view space, bad ones skipped) -> sort back to front
 *   pass 1: opaque depth -> particle-target resolution
 *   pass 2: particles -> low-res target (premultiplied light, transmittance)
 *   pass 3: composite over the host's framebuffer (depth-aware upsample)
 * With no live particle there is no pass at all. */
#include <math.h>
#include <string.h>
#include "module.h"


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
    if (!fx->plan.particle_velocity || !fx->have_previous_view) {
        memcpy(v->previous_center, v->center, sizeof(v->center));
        return;
    }
    float dt = (float)(fx->time - fx->previous_render_time), before[3];
    for (int k = 0; k < 3; k++) before[k] = pos[k] - vel[k] * dt;
    transform_point(fx->previous_view, before, v->previous_center);
    (void)view;
}

/* Live particles whose delay has passed, in view space, into fx->view. */
int sbfx_collect_view_particles(sbfx *fx, const float view[16])
{
    const sbfx_pool *p = &fx->pool;
    int n = 0;
    fx->counters.particles_skipped = 0;
    for (int i = 0; i < p->alive; i++) {
        if (p->age[i] < 0.0f) continue;
        sbfx_view_particle *v = &fx->view[n];
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

static bool frame_valid(sbfx *fx, const sbfx_frame *f, sbfx_depth_model *depth)
{
    if (f->width <= 0 || f->height <= 0 || f->width > 16384 || f->height > 16384) {
        sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "frame size %dx%d is out of range", f->width, f->height);
        return false;
    }
    if (!f->scene_depth_texture) {
        sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "frame has no scene_depth_texture: sbfx needs "
                  "the opaque scene's depth as a texture");
        return false;
    }
    if (fx->plan.owns_scene && !f->scene_color_texture) {
        sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "this scene's post effects (heat shimmer, motion blur or "
                  "depth of field) need frame.scene_color_texture");
        return false;
    }
    return sbfx_depth_model_from(fx, f, depth);
}

sbfx_result sbfx_render(sbfx *fx, const sbfx_frame *frame)
{
    if (!fx || !frame) return SBFX_ERR_INVALID_ARGUMENT;
    fx->counters.passes = 0;
    fx->counters.draw_calls = 0;
    fx->counters.gl_state_queries = 0;
    fx->counters.fire_lit_particles = 0;
    sbfx_depth_model depth;
    if (!frame_valid(fx, frame, &depth)) return SBFX_ERR_INVALID_ARGUMENT;
    int count = sbfx_collect_view_particles(fx, frame->view);
    sbfx_result r = SBFX_OK;
    /* Idle without post effects: no pass at all, no GL call: the host's state is untouched. */
    if (count > 0 || fx->plan.owns_scene) {
        sbfx_gl_enter(fx);
        r = sbfx_budget_begin_frame(fx); /* the budget's level, and its GPU timer */
        if (r == SBFX_OK) r = sbfx_render_frame(fx, frame, &depth, count);
        sbfx_budget_end_frame(fx);
        sbfx_gl_leave(fx, "sbfx_render");
    }
    memcpy(fx->previous_view, frame->view, sizeof(fx->previous_view));
    fx->previous_render_time = fx->time;
    fx->have_previous_view = true;
    return r;
}

sbfx_result sbfx_render_view_particles(sbfx *fx, const sbfx_frame *frame,
                                       const sbfx_view_particle *particles, int count)
{
    if (!fx || !frame || (count > 0 && !particles) || count < 0) return SBFX_ERR_INVALID_ARGUMENT;
    fx->counters.passes = 0;
    fx->counters.draw_calls = 0;
    fx->counters.particles_skipped = 0;
    fx->counters.gl_state_queries = 0;
    fx->counters.fire_lit_particles = 0;
    sbfx_depth_model depth;
    if (!frame_valid(fx, frame, &depth)) return SBFX_ERR_INVALID_ARGUMENT;
    if (count > fx->pool.capacity)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "%d particles exceed the pool of %d",
                         count, fx->pool.capacity);
    int n = 0;
    for (int i = 0; i < count; i++) {
        if (sbfx_view_particle_valid(&particles[i]) && fx->uses_medium[particles[i].medium]) {
            fx->view[n] = particles[i];
            memcpy(fx->view[n++].previous_center, particles[i].center, sizeof(particles[i].center));
        }
        else
            fx->counters.particles_skipped++;
    }
    if (n == 0 && !fx->plan.owns_scene) return SBFX_OK;
    sbfx_gl_enter(fx);
    sbfx_result r = sbfx_render_frame(fx, frame, &depth, n);
    sbfx_gl_leave(fx, "sbfx_render_view_particles");
    return r;
}

int sbfx_frame_particles(sbfx *fx, const float view[16], const sbfx_view_particle **out)
{
    int n = sbfx_collect_view_particles(fx, view);
    *out = fx->view;
    return n;
}
