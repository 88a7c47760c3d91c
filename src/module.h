/* The top's private header (src/rooms.txt): the module's block — the handle and every room's
 * state, allocated together (sbfx_module_new) — its load and release (sbfx.c), and the top's
 * entry points for tests and tools. It includes every room's header: the top composes them.
 * Tests, tools and the bench include it (or internal.h) to look inside the module; a room's own
 * files include their room's headers and those of the rooms below it, never this one. */
#ifndef SBFX_MODULE_H
#define SBFX_MODULE_H

#include "base/base.h"
#include "base/hash.h"
#include "base/rng.h"
#include "tables/tables.h"
#include "scene/scene.h"
#include "scene/plan.h"
#include "scene/scene_tables.h"
#include "sim/sim.h"
#include "gl/gl.h"
#include "render/render.h"
#include "budget/budget.h"

/* struct sbfx composes the rooms' states by reference (base/base.h); they live here, in one
 * allocation with it. */
typedef struct sbfx_module {
    struct sbfx fx;              /* first: the host's handle is the block's address */
    sbfx_scene_state scene;
    sbfx_tables tables;
    sbfx_sim sim;
    sbfx_gl gl;
    sbfx_render_state render;
    sbfx_budget budget;
} sbfx_module;

/* A zeroed module with its rooms' pointers set (free() releases the block). */
sbfx *sbfx_module_new(void);
/* Sets the handle's pointers to the rooms of its own block (after the block was copied). */
void sbfx_module_point(sbfx *fx);
/* Load in two steps, shared by sbfx_create and sbfx_set_scene: plan (the desc with its defaults
 * and the scene's settings, checked; the declared levels) and build (the scene adopted, the pool,
 * the GL objects: borrowed from fx->gl->donor where it has them). */
sbfx_result sbfx_module_build(sbfx *fx, const sbfx_desc *desc);
/* Everything a module holds but its own allocation (GL objects it lent are left alone). */
void sbfx_module_release(sbfx *fx);
/* Remakes the tables, shader programs and targets from the current media (sbfx_media): for
 * tests and tools that change media after sbfx_create. Allocates; not for the frame loop. */
sbfx_result sbfx_reload(sbfx *fx);

#endif
