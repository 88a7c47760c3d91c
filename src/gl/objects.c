/* Replacing the scene of a live module (sbfx_set_scene): load planned again and built into a
 * second module that borrows from the live one every GL object it would make the same way
 * (module.h, sbfx_object), then, if that succeeded, takes the live module's place: its handle,
 * its clock, what it had learnt about the host. If it failed, the borrowed objects go back and
 * the live module goes on as it was. */
#include <stdlib.h>
#include <string.h>
#include "module.h"

void sbfx_object_note(sbfx *fx, sbfx_object_kind kind, GLuint id, uint64_t key, const sbfx_rt *rt)
{
    /* a full table only means the object cannot be lent: it is deleted the ordinary way */
    if (fx->object_count == SBFX_OBJECTS) return;
    sbfx_object *o = &fx->objects[fx->object_count++];
    *o = (sbfx_object){.kind = (uint8_t)kind, .state = SBFX_OBJECT_OWN, .id = id, .key = key};
    if (rt) o->rt = *rt;
}

bool sbfx_object_borrow(sbfx *fx, sbfx_object_kind kind, uint64_t key, GLuint *id, sbfx_rt *rt)
{
    sbfx *donor = fx->donor;
    if (!donor || fx->object_count == SBFX_OBJECTS) return false;
    for (int i = 0; i < donor->object_count; i++) {
        sbfx_object *o = &donor->objects[i];
        if (o->kind != kind || o->key != key || o->state != SBFX_OBJECT_OWN) continue;
        o->state = SBFX_OBJECT_LENT;
        sbfx_object_note(fx, kind, o->id, key, &o->rt);
        fx->objects[fx->object_count - 1].state = SBFX_OBJECT_BORROWED;
        if (id) *id = o->id;
        if (rt) *rt = o->rt;
        return true;
    }
    return false;
}

bool sbfx_object_release(sbfx *fx, sbfx_object_kind kind, GLuint id)
{
    for (int i = 0; i < fx->object_count; i++) {
        sbfx_object *o = &fx->objects[i];
        if (o->kind != kind || o->id != id) continue;
        bool own = o->state == SBFX_OBJECT_OWN;
        *o = fx->objects[--fx->object_count];
        return own;
    }
    return true;
}

void sbfx_program_delete(sbfx *fx, GLuint program)
{
    if (program && sbfx_object_release(fx, SBFX_OBJECT_PROGRAM, program)) glDeleteProgram(program);
}

void sbfx_object_forget_recipe(sbfx *fx, sbfx_object_kind kind, GLuint id)
{
    for (int i = 0; i < fx->object_count; i++)
        if (fx->objects[i].kind == kind && fx->objects[i].id == id) fx->objects[i].key = 0;
}

void sbfx_texture_delete(sbfx *fx, GLuint *texture)
{
    if (*texture && sbfx_object_release(fx, SBFX_OBJECT_TEXTURE, *texture)) glDeleteTextures(1, texture);
    *texture = 0;
}

/* Every object of `from` state in fx becomes `to`. */
static void settle(sbfx *fx, sbfx_object_state from, sbfx_object_state to)
{
    for (int i = 0; i < fx->object_count; i++)
        if (fx->objects[i].state == from) fx->objects[i].state = (uint8_t)to;
}

/* The targets the live module renders into, made (or taken over) now at its output size, so the
 * first frame of the new scene creates none it could have borrowed. Targets bind the draw
 * framebuffer and unit 0's 2D texture: saved and put back. */
static sbfx_result build_targets(sbfx *next, const sbfx *live)
{
    int w = live->gl.out_width, h = live->gl.out_height;
    int pw = live->gl.post.width, ph = live->gl.post.height;
    if (!(w > 0) && !(pw > 0)) return SBFX_OK;
    const sbfx_gl_units unit0 = {.tex_2d = 1u};
    sbfx_gl_state saved;
    sbfx_gl_enter(next);
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_PASS | next->context_parts, &unit0);
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
    sbfx_desc d = fx->host_desc;
    d.scene = scene;
    for (int i = 0; i < d.ladder_count; i++) ladder[i] = fx->host_ladder[i];
    d.ladder = d.ladder_count ? ladder : NULL;
    return d;
}

/* What goes on across the reload: the clock, what the module learnt about the host, counts
 * since create. */
static void carry_over(sbfx *next, const sbfx *live)
{
    next->host_desc = live->host_desc;
    memcpy(next->host_ladder, live->host_ladder, sizeof(next->host_ladder));
    next->heap_allocs_after_load = live->heap_allocs_after_load;
    next->warned_format = next->warned_format || live->warned_format;
    next->warned_polygon_mode = next->warned_polygon_mode || live->warned_polygon_mode;
    memcpy(next->previous_view, live->previous_view, sizeof(next->previous_view));
    next->previous_render_time = live->previous_render_time;
    next->have_previous_view = live->have_previous_view;
    next->counters.programs_compiled += live->counters.programs_compiled;
    next->counters.targets_created += live->counters.targets_created;
    next->counters.scene_reloads = live->counters.scene_reloads + 1;
}

static sbfx_result fail_back(sbfx *fx, sbfx *next, sbfx_result r)
{
    memcpy(fx->last_error, next->last_error, sizeof(fx->last_error)); /* logged by next already */
    next->donor = NULL;
    sbfx_module_release(next); /* its borrowed objects stay with fx */
    free(next);
    settle(fx, SBFX_OBJECT_LENT, SBFX_OBJECT_OWN);
    return r;
}

sbfx_result sbfx_set_scene(sbfx *fx, const sbfx_scene *scene)
{
    if (!fx) return SBFX_ERR_INVALID_ARGUMENT;
    sbfx *next = calloc(1, sizeof(*next));
    if (!next) return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "sbfx_set_scene: out of memory");
    /* the clock first: the new timeline is scheduled from now */
    next->time = fx->time;
    next->step_index = fx->step_index;
    next->accumulator = fx->accumulator;
    next->mediump_native = fx->mediump_native; /* SBFX_MEDIUMP, SBFX_FILTER_BITS: read once, at create */
    next->filter_bits = fx->filter_bits;
    next->host_errors.logged = fx->host_errors.logged; /* what the host left pending: said once */
    next->donor = fx;
    const char *ladder[SBFX_LADDER_MAX];
    sbfx_desc desc = host_desc(fx, scene, ladder);
    sbfx_result r = sbfx_module_build(next, &desc);
    if (r == SBFX_OK) r = build_targets(next, fx);
    if (r != SBFX_OK) return fail_back(fx, next, r);
    carry_over(next, fx);
    sbfx_module_release(fx); /* deletes what next did not take over */
    next->donor = NULL;
    settle(next, SBFX_OBJECT_BORROWED, SBFX_OBJECT_OWN);
    next->loaded = true;
    memcpy(fx, next, sizeof(*fx)); /* the host's handle stays valid: nothing points into it */
    free(next);
    return SBFX_OK;
}
