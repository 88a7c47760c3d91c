/* The GL objects a module made, known by how they were made (gl/objects.h): a module built to
 * replace another (sbfx_set_scene, set_scene.c) takes over from its donor those it would make
 * the same way instead of making them again. */
#include <stdlib.h>
#include <string.h>
#include "gl/gl.h"

void sbfx_object_note(sbfx *fx, sbfx_object_kind kind, GLuint id, uint64_t key, const sbfx_rt *rt)
{
    /* a full table only means the object cannot be lent: it is deleted the ordinary way */
    if (fx->gl->object_count == SBFX_OBJECTS) return;
    sbfx_object *o = &fx->gl->objects[fx->gl->object_count++];
    *o = (sbfx_object){.kind = (uint8_t)kind, .state = SBFX_OBJECT_OWN, .id = id, .key = key};
    if (rt) o->rt = *rt;
}

bool sbfx_object_borrow(sbfx *fx, sbfx_object_kind kind, uint64_t key, GLuint *id, sbfx_rt *rt)
{
    sbfx *donor = fx->gl->donor;
    if (!donor || fx->gl->object_count == SBFX_OBJECTS) return false;
    for (int i = 0; i < donor->gl->object_count; i++) {
        sbfx_object *o = &donor->gl->objects[i];
        if (o->kind != kind || o->key != key || o->state != SBFX_OBJECT_OWN) continue;
        o->state = SBFX_OBJECT_LENT;
        sbfx_object_note(fx, kind, o->id, key, &o->rt);
        fx->gl->objects[fx->gl->object_count - 1].state = SBFX_OBJECT_BORROWED;
        if (id) *id = o->id;
        if (rt) *rt = o->rt;
        return true;
    }
    return false;
}

bool sbfx_object_release(sbfx *fx, sbfx_object_kind kind, GLuint id)
{
    for (int i = 0; i < fx->gl->object_count; i++) {
        sbfx_object *o = &fx->gl->objects[i];
        if (o->kind != kind || o->id != id) continue;
        bool own = o->state == SBFX_OBJECT_OWN;
        *o = fx->gl->objects[--fx->gl->object_count];
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
    for (int i = 0; i < fx->gl->object_count; i++)
        if (fx->gl->objects[i].kind == kind && fx->gl->objects[i].id == id) fx->gl->objects[i].key = 0;
}

void sbfx_texture_delete(sbfx *fx, GLuint *texture)
{
    if (*texture && sbfx_object_release(fx, SBFX_OBJECT_TEXTURE, *texture)) glDeleteTextures(1, texture);
    *texture = 0;
}

/* Every object of `from` state in fx becomes `to`. */
void sbfx_objects_settle(sbfx *fx, sbfx_object_state from, sbfx_object_state to)
{
    for (int i = 0; i < fx->gl->object_count; i++)
        if (fx->gl->objects[i].state == from) fx->gl->objects[i].state = (uint8_t)to;
}
