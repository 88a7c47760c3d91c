/* The top (src/rooms.txt): the module's lifetime and its public entry points, in the order of the
 * data flow of docs/design.md §1 and the seed's figure 9; every room below does its part:
 *   sbfx_create    plan (scene/: the desc with its defaults and the scene's settings, checked;
 *                  budget/: the levels it declares) -> load (the scene adopted and its timeline
 *                  scheduled, the pool (sim/), the tables (scene/), and on the GPU (gl/, render/)
 *                  only what the plan uses, inside one save and restore of the host's state)
 *   sbfx_trigger   an effect instance spawned into the fixed pool (sim/timeline.c)
 *   sbfx_update    fixed steps of the live particles, the triggers due fired (sim/)
 *   sbfx_render    the particles in view space (sim/view.c) -> the budget's level (budget/) ->
 *                  opaque depth, particles front to back, composite, post chain (render/)
 * Replacing a live module's scene: set_scene.c. The module's block: module.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "module.h"

/* ---- the module: the handle and every room's state in one block ---------------------------- */

void sbfx_module_point(sbfx *fx)
{
    sbfx_module *m = (sbfx_module *)fx;
    fx->scene = &m->scene;
    fx->tables = &m->tables;
    fx->sim = &m->sim;
    fx->gl = &m->gl;
    fx->render = &m->render;
    fx->budget = &m->budget;
}

sbfx *sbfx_module_new(void)
{
    sbfx_module *m = calloc(1, sizeof(*m));
    if (!m) return NULL;
    sbfx_module_point(&m->fx);
    return &m->fx;
}

/* ---- load -------------------------------------------------------------------------------------- */

/* Everything made on the GPU at load, inside one save and restore of what it changes: the
 * program, vertex array and buffer bindings, the unpack state, and unit 0 (active texture,
 * 2D, 3D and 2D-array bindings, sampler). Targets follow the first frame's size. */
static sbfx_result load_gl(sbfx *fx)
{
    const sbfx_gl_units unit0 = {1u, 1u, 1u};
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_OBJECTS | SBFX_GL_SAVE_UNPACK, &unit0);
    sbfx_result r = sbfx_samplers_create(fx);
    if (r == SBFX_OK) r = sbfx_scene_tables_create(fx);
    if (r == SBFX_OK) r = sbfx_luts_create(fx);
    if (r == SBFX_OK) r = sbfx_programs_create(fx);
    if (r == SBFX_OK) r = sbfx_quality_load(fx);
    if (r == SBFX_OK) r = sbfx_post_programs_create(fx);
    if (r == SBFX_OK) sbfx_budget_gl_init(fx);
    if (r == SBFX_OK) r = sbfx_shadow_create(fx);
    if (r == SBFX_OK) r = sbfx_tiles_create(fx);
    sbfx_gl_state_restore(&saved);
    return r;
}

/* Deleting sbfx's own objects changes no binding a host can hold. */
static void destroy_gl(sbfx *fx)
{
    sbfx_budget_gl_destroy(fx);
    sbfx_shadow_destroy(fx);
    sbfx_tiles_destroy(fx);
    sbfx_targets_destroy(fx);
    sbfx_post_destroy(fx);
    sbfx_programs_destroy(fx);
    sbfx_probe_destroy(fx);
    sbfx_luts_destroy(fx);
    sbfx_scene_tables_destroy(fx);
    sbfx_samplers_destroy(fx);
}

/* The GL objects and everything made with them are made again; the context, what was read
 * about it at create and the clock stay. */
sbfx_result sbfx_reload(sbfx *fx)
{
    destroy_gl(fx);
    sbfx_gl *gl = fx->gl;
    sbfx_gl_context context = gl->context;
    int ring_next = gl->detail_ring_next;
    sbfx *donor = gl->donor;
    memset(gl, 0, sizeof(*gl));
    gl->context = context, gl->detail_ring_next = ring_next, gl->donor = donor;
    memset(&fx->render->post, 0, sizeof(fx->render->post));
    memset(&fx->render->probe, 0, sizeof(fx->render->probe));
    fx->counters.programs = fx->counters.textures = fx->counters.framebuffers = 0;
    fx->counters.gpu_bytes = 0;
    return load_gl(fx);
}

/* The scene's timeline, from now: a reload's timeline starts again. */
static void schedule_timeline(sbfx *fx, const sbfx_scene *scene)
{
    if (fx->scene->desc.ignore_timeline) return;
    for (int i = 0; i < scene->timeline_count; i++) {
        const sbfx_timeline_entry *t = &scene->timeline[i];
        sbfx_timeline_add(fx, t->effect, fx->sim->time + t->time, t->position, SBFX_TRIGGER_TIMELINE);
    }
}

static sbfx_result load(sbfx *fx)
{
    sbfx_result r;
    sbfx_scene *builtin = NULL;
    const sbfx_scene *scene = fx->scene->desc.scene;
    if (!scene) {
        if (!(builtin = sbfx_calloc(fx, 1, sizeof(*builtin))))
            return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "out of memory");
        sbfx_scene_builtin(builtin);
        scene = builtin;
    }
    sbfx_scene_adopt(fx, scene);
    schedule_timeline(fx, scene);
    sbfx_free(fx, builtin);
    sbfx_orbit_lights(fx); /* where orbiting lights are at t = 0 */
    fx->scene->tone_curve = sbfx_tone_curve_for(fx->scene->desc.tone_map);
    if ((r = sbfx_context_check(fx)) != SBFX_OK) return r;
    if ((r = sbfx_pool_create(fx, fx->scene->desc.max_particles)) != SBFX_OK) return r;
    if ((r = sbfx_fire_lights_create(fx)) != SBFX_OK) return r;
    sbfx_gl_enter(fx);
    r = load_gl(fx);
    sbfx_gl_leave(fx, "sbfx_create");
    return r;
}

/* Plan: the desc with its defaults and the scene's render settings, checked, and the levels it
 * declares. */
static sbfx_result plan(sbfx *fx, const sbfx_desc *desc)
{
    sbfx_desc *d = &fx->scene->desc;
    *d = sbfx_desc_with_defaults(desc);
    fx->log = d->log;
    fx->log_user = d->log_user;
    sbfx_result r = sbfx_desc_validate(fx, d);
    if (r == SBFX_OK) r = sbfx_budget_init(fx);
    d->ladder = NULL; /* parsed: the scene's names may go away */
    d->ladder_count = 0;
    return r;
}

sbfx_result sbfx_module_build(sbfx *fx, const sbfx_desc *desc)
{
    sbfx_result r = plan(fx, desc);
    return r == SBFX_OK ? load(fx) : r;
}

void sbfx_module_release(sbfx *fx)
{
    destroy_gl(fx);
    sbfx_fire_lights_destroy(fx);
    sbfx_pool_destroy(fx);
}

sbfx_result sbfx_create(const sbfx_desc *desc, sbfx **out)
{
    if (!out) return SBFX_ERR_INVALID_ARGUMENT;
    *out = NULL;
    sbfx *fx = sbfx_module_new();
    if (!fx) return SBFX_ERR_OUT_OF_MEMORY;
    fx->log = desc ? desc->log : NULL; /* for sbfx_keep_host_desc's message */
    fx->log_user = desc ? desc->log_user : NULL;
    sbfx_result r = sbfx_keep_host_desc(fx, desc);
    if (r == SBFX_OK) r = sbfx_precision_from_env(fx); /* once: a reload keeps what create read */
    if (r == SBFX_OK) r = sbfx_module_build(fx, desc);
    if (r != SBFX_OK) {
        /* Hand the message to the caller's log before the handle goes away. */
        sbfx_destroy(fx);
        return r;
    }
    fx->loaded = true;
    *out = fx;
    return SBFX_OK;
}

void sbfx_destroy(sbfx *fx)
{
    if (!fx) return;
    sbfx_module_release(fx);
    free(fx); /* the block (module.h) */
}

/* ---- triggers: effect instances into the pool ------------------------------------------------- */

bool sbfx_has_effect(const sbfx *fx, const char *effect)
{
    return fx && effect && sbfx_effect_index(fx, effect) >= 0;
}

const char *sbfx_effect_name(const sbfx *fx, int index)
{
    return fx && index >= 0 && index < fx->scene->effect_count ? fx->scene->effects[index].name : NULL;
}

static bool position_valid(const float p[3])
{
    return p && isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

sbfx_result sbfx_trigger(sbfx *fx, const char *effect, const float position[3])
{
    if (!fx || !effect || !position) return SBFX_ERR_INVALID_ARGUMENT;
    if (!position_valid(position))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "trigger \"%s\": position is not finite", effect);
    int index = sbfx_effect_index(fx, effect);
    if (index < 0) return sbfx_fail(fx, SBFX_ERR_UNKNOWN_EFFECT, "trigger: no effect named \"%s\"", effect);
    return sbfx_fire(fx, index, position, SBFX_TRIGGER_CALL);
}

sbfx_result sbfx_trigger_identified(sbfx *fx, const sbfx_trigger_desc *t)
{
    if (!fx || !t) return SBFX_ERR_INVALID_ARGUMENT;
    if (t->version != SBFX_TRIGGER_DESC_VERSION)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "sbfx_trigger_identified: version %u, this library knows %d",
                         (unsigned)t->version, SBFX_TRIGGER_DESC_VERSION);
    const char *effect = t->effect ? t->effect : "(null)";
    if (!t->effect || !position_valid(t->position) || !isfinite(t->start_time))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "trigger \"%s\": no effect, or a position or start time "
                         "that is not finite", effect);
    if (t->identity == 0 || t->identity >= (UINT64_C(1) << 63))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "trigger \"%s\": identity %llu is outside 1..2^63-1",
                         effect, (unsigned long long)t->identity);
    int index = sbfx_effect_index(fx, t->effect);
    if (index < 0) return sbfx_fail(fx, SBFX_ERR_UNKNOWN_EFFECT, "trigger: no effect named \"%s\"", effect);
    return sbfx_fire_identified(fx, index, t->position, t->identity, t->start_time);
}

int sbfx_stop_identified(sbfx *fx, uint64_t identity)
{
    if (!fx || !identity) return SBFX_ERR_INVALID_ARGUMENT;
    return sbfx_stop_instance(fx, identity);
}

void sbfx_set_trigger_listener(sbfx *fx, sbfx_trigger_fn fn, void *user)
{
    if (!fx) return;
    fx->sim->trigger_listener = fn;
    fx->sim->trigger_listener_user = user;
}

sbfx_result sbfx_schedule(sbfx *fx, const char *effect, double seconds, const float position[3])
{
    if (!fx || !effect) return SBFX_ERR_INVALID_ARGUMENT;
    if (!position_valid(position) || !isfinite(seconds) || seconds < 0)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "schedule \"%s\": time or position is not finite", effect);
    int index = sbfx_effect_index(fx, effect);
    if (index < 0) return sbfx_fail(fx, SBFX_ERR_UNKNOWN_EFFECT, "schedule: no effect named \"%s\"", effect);
    return sbfx_timeline_add(fx, index, seconds, position, SBFX_TRIGGER_SCHEDULE);
}

double sbfx_time(const sbfx *fx) { return fx ? fx->scene->desc.start_time + fx->sim->time : 0.0; }

double sbfx_elapsed(const sbfx *fx) { return fx ? fx->sim->time : 0.0; }

/* ---- update: the simulation ------------------------------------------------------------------- */

sbfx_result sbfx_update(sbfx *fx, double dt)
{
    if (!fx) return SBFX_ERR_INVALID_ARGUMENT;
    if (!(dt >= 0.0) || !isfinite(dt))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "sbfx_update: dt %g is not a finite time >= 0", dt);
    sbfx_timeline_advance(fx, dt);
    sbfx_orbit_lights(fx);
    return SBFX_OK;
}

/* ---- render: one frame -------------------------------------------------------------------------- */

/* Collect the live particles in view space (bad ones skipped), then, inside the frame budget's
 * level and GPU timer, the frame's passes (render/frame.c: sort, depth, particles, composite,
 * post). With no live particle and no post effect there is no pass at all, no GL call: the
 * host's state is untouched. */
sbfx_result sbfx_render(sbfx *fx, const sbfx_frame *frame)
{
    if (!fx || !frame) return SBFX_ERR_INVALID_ARGUMENT;
    sbfx_frame_counters_reset(fx);
    sbfx_depth_model depth;
    if (!sbfx_frame_check(fx, frame, &depth)) return SBFX_ERR_INVALID_ARGUMENT;
    int count = sbfx_collect_view_particles(fx, frame->view);
    sbfx_result r = SBFX_OK;
    if (count > 0 || fx->scene->plan.owns_scene) {
        sbfx_gl_enter(fx);
        r = sbfx_budget_begin_frame(fx); /* the budget's level, and its GPU timer */
        if (r == SBFX_OK) r = sbfx_render_frame(fx, frame, &depth, count);
        sbfx_budget_end_frame(fx);
        sbfx_gl_leave(fx, "sbfx_render");
    }
    sbfx_view_rendered(fx, frame->view);
    return r;
}

void sbfx_stats(const sbfx *fx, sbfx_counters *out)
{
    if (!fx || !out) return;
    *out = fx->counters;
    out->particles_simulated = fx->sim->particles_simulated;
    out->particles_alive = fx->sim->pool.alive;
    out->heap_allocs_after_load = fx->heap_allocs_after_load;
}

int sbfx_triggers_expired(const sbfx *fx)
{
    return fx ? fx->triggers_expired : 0;
}
