/* Replacing the scene of a live module (sbfx_set_scene): load planned again and built into a
 * second module that borrows from the live one every GL object it would make the same way
 * (gl/objects.h), then, if that succeeded, takes the live module's place: its handle, its clock,
 * what it had learnt about the host. If it failed, the borrowed objects go back and the live
 * module goes on as it was. */
#include <stdlib.h>
#include <string.h>
#include "module.h"

/* The targets the live module renders into, made (or taken over) now at its output size, so the
 * first frame of the new scene creates none it could have borrowed. Targets bind the draw
 * framebuffer and unit 0's 2D texture: saved and put back. */
static sbfx_result build_targets(sbfx *next, const sbfx *live)
{
    int w = live->gl->out_width, h = live->gl->out_height;
    int pw = live->render->post.width, ph = live->render->post.height;
    if (!(w > 0) && !(pw > 0)) return SBFX_OK;
    const sbfx_gl_units unit0 = {.tex_2d = 1u};
    sbfx_gl_state saved;
    sbfx_gl_enter(next);
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_PASS | next->gl->context.parts, &unit0);
    sbfx_result r = w > 0 ? sbfx_targets_ensure(next, w, h) : SBFX_OK;
    if (r == SBFX_OK && pw > 0) r = sbfx_post_targets_ensure(next, pw, ph);
    sbfx_gl_state_restore(&saved);
    if (r == SBFX_OK && !sbfx_gl_check(next, "creating the new scene's targets")) r = SBFX_ERR_GL;
    sbfx_gl_leave(next, "sbfx_set_scene");
    return r;
}

/* The host's desc as sbfx_create was given it, with this scene. */
static sbfx_desc host_desc(const sbfx *fx, const sbfx_scene *scene, const char *ladder[SBFX_LADDER_MAX])
{
    sbfx_desc d = fx->scene->host_desc;
    d.scene = scene;
    for (int i = 0; i < d.ladder_count; i++) ladder[i] = fx->scene->host_ladder[i];
    d.ladder = d.ladder_count ? ladder : NULL;
    return d;
}

/* What goes on across the reload: the clock, what the module learnt about the host, the host's
 * trigger listener, counts since create. */
static void carry_over(sbfx *next, const sbfx *live)
{
    next->scene->host_desc = live->scene->host_desc;
    memcpy(next->scene->host_ladder, live->scene->host_ladder, sizeof(next->scene->host_ladder));
    next->heap_allocs_after_load = live->heap_allocs_after_load;
    next->gl->context.warned_format = next->gl->context.warned_format || live->gl->context.warned_format;
    next->render->warned_polygon_mode = next->render->warned_polygon_mode || live->render->warned_polygon_mode;
    memcpy(next->sim->previous_view, live->sim->previous_view, sizeof(next->sim->previous_view));
    next->sim->previous_render_time = live->sim->previous_render_time;
    next->sim->have_previous_view = live->sim->have_previous_view;
    next->sim->trigger_listener = live->sim->trigger_listener;
    next->sim->trigger_listener_user = live->sim->trigger_listener_user;
    next->counters.programs_compiled += live->counters.programs_compiled;
    next->counters.targets_created += live->counters.targets_created;
    next->counters.scene_reloads = live->counters.scene_reloads + 1;
}

static sbfx_result fail_back(sbfx *fx, sbfx *next, sbfx_result r)
{
    memcpy(fx->last_error, next->last_error, sizeof(fx->last_error)); /* logged by next already */
    next->gl->donor = NULL;
    sbfx_module_release(next); /* its borrowed objects stay with fx */
    free(next);
    sbfx_objects_settle(fx, SBFX_OBJECT_LENT, SBFX_OBJECT_OWN);
    return r;
}

sbfx_result sbfx_set_scene(sbfx *fx, const sbfx_scene *scene)
{
    if (!fx) return SBFX_ERR_INVALID_ARGUMENT;
    sbfx *next = sbfx_module_new();
    if (!next) return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "sbfx_set_scene: out of memory");
    /* the clock first: the new timeline is scheduled from now */
    next->sim->time = fx->sim->time;
    next->sim->step_index = fx->sim->step_index;
    next->sim->accumulator = fx->sim->accumulator;
    /* SBFX_MEDIUMP, SBFX_FILTER_BITS: read once, at create */
    next->gl->context.mediump_native = fx->gl->context.mediump_native;
    next->gl->context.filter_bits = fx->gl->context.filter_bits;
    next->gl->context.host_errors.logged = fx->gl->context.host_errors.logged; /* what the host left pending: said once */
    next->gl->donor = fx;
    const char *ladder[SBFX_LADDER_MAX];
    sbfx_desc desc = host_desc(fx, scene, ladder);
    sbfx_result r = sbfx_module_build(next, &desc);
    if (r == SBFX_OK) r = build_targets(next, fx);
    if (r != SBFX_OK) return fail_back(fx, next, r);
    carry_over(next, fx);
    sbfx_module_release(fx); /* deletes what next did not take over */
    next->gl->donor = NULL;
    sbfx_objects_settle(next, SBFX_OBJECT_BORROWED, SBFX_OBJECT_OWN);
    next->loaded = true;
    /* the host's handle stays valid: the whole block moves into it, and nothing points into a
     * block but its own handle, pointed again at its own rooms */
    memcpy(fx, next, sizeof(sbfx_module));
    sbfx_module_point(fx);
    free(next);
    return SBFX_OK;
}
