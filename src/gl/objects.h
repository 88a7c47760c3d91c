/* The GL objects a module made (gl/gl.h says what the room is for; objects.c), known by how they
 * were made: a 64-bit key (sbfx_hash64 of the shader names and defines, or of a target's size,
 * formats and filter). A module built to replace another (sbfx_set_scene, set_scene.c) takes
 * over those it would make the same way instead of making them again. The donor lends them; if
 * the new module fails, they go back to it. Deleting an object that is lent or borrowed leaves
 * it to the module that keeps it. */
#ifndef SBFX_GL_OBJECTS_H
#define SBFX_GL_OBJECTS_H

#include <GLES3/gl3.h>
#include <stdbool.h>
#include <stdint.h>
#include "base/hash.h"
#include "gl/target.h"

typedef enum sbfx_object_kind { SBFX_OBJECT_PROGRAM = 1, SBFX_OBJECT_TARGET, SBFX_OBJECT_TEXTURE } sbfx_object_kind;
typedef enum sbfx_object_state { SBFX_OBJECT_OWN, SBFX_OBJECT_LENT, SBFX_OBJECT_BORROWED } sbfx_object_state;
typedef struct sbfx_object {
    uint8_t kind, state;
    GLuint id;          /* the program, the target's framebuffer, the texture */
    uint64_t key;
    sbfx_rt rt;         /* targets: the whole of it */
} sbfx_object;
#define SBFX_OBJECTS 256

/* The object table (fx->gl->objects): what the module made (lendable). */
void sbfx_object_note(sbfx *fx, sbfx_object_kind kind, GLuint id, uint64_t key, const sbfx_rt *rt);
/* Takes over the donor's object of that kind and key (true), or finds none (false). */
bool sbfx_object_borrow(sbfx *fx, sbfx_object_kind kind, uint64_t key, GLuint *id, sbfx_rt *rt);
/* Forgets an object; true when the caller is to delete it (the module's own, or unknown). */
bool sbfx_object_release(sbfx *fx, sbfx_object_kind kind, GLuint id);
/* The object no longer holds what its recipe makes (detail pushed into the procedural volume):
 * no reload takes it over. */
void sbfx_object_forget_recipe(sbfx *fx, sbfx_object_kind kind, GLuint id);
void sbfx_program_delete(sbfx *fx, GLuint program);
void sbfx_texture_delete(sbfx *fx, GLuint *texture);
/* Every object of state `from` in fx's table becomes `to` (a reload settled). */
void sbfx_objects_settle(sbfx *fx, sbfx_object_state from, sbfx_object_state to);

#endif
