/* What a host that plays a stream needs (issue 34, the GStreamer element): the module put back
 * where sbfx_create left it when the stream seeks (sbfx_restart), and whether a frame needs
 * sbfx at all, so that an idle frame can go on unchanged (sbfx_idle). Public entry points: the
 * top (src/rooms.txt), beside sbfx_set_scene (set_scene.c), which the restart is made of. */
#include "module.h"

sbfx_result sbfx_restart(sbfx *fx, const sbfx_scene *scene)
{
    if (!fx) return SBFX_ERR_INVALID_ARGUMENT;
    /* sbfx_set_scene carries the clock over and schedules the timeline from it: at zero, the
     * new module starts where a module just created starts */
    sbfx_sim *sim = fx->sim;
    double time = sim->time, accumulator = sim->accumulator;
    uint64_t step_index = sim->step_index;
    sim->time = sim->accumulator = 0.0;
    sim->step_index = 0;
    sbfx_result r = sbfx_set_scene(fx, scene);
    sim = fx->sim; /* the new module's block, moved into the handle */
    if (r != SBFX_OK) {
        sim->time = time, sim->accumulator = accumulator, sim->step_index = step_index;
        return r;
    }
    /* what the last frames left for the next (the velocity blur's previous camera) */
    sim->have_previous_view = false;
    sim->previous_render_time = 0.0;
    return SBFX_OK;
}

bool sbfx_idle(const sbfx *fx)
{
    if (!fx) return true;
    if (fx->scene->plan.owns_scene) return false;
    const sbfx_pool *pool = &fx->sim->pool;
    for (int i = 0; i < pool->alive; i++)
        if (pool->age[i] >= 0.0f) return false; /* sbfx_collect_view_particles' test (sim/view.c) */
    return true;
}
