/* The ground floor of src/ (src/rooms.txt; docs/hacking.md has the map): what every room may
 * use and which uses nothing of theirs, the way libcamera's base/ does.
 *
 * Exports to the rooms above:
 *   - errors and logging (log.c): sbfx_fail keeps a message as the module's last error and sends
 *     it to the host's log callback, sbfx_log logs; no room calls back into sbfx.c to report;
 *   - allocation counting (alloc.c): every heap allocation of the module, so that "nothing
 *     allocated per frame" is a number a test asserts (sbfx_counters.heap_allocs_after_load);
 *   - the deterministic RNG (rng.h), the FNV-1a hash (hash.h), a 3-vector's normalisation;
 *   - struct sbfx, the module's handle: the ground floor's own state (the last error, the log
 *     callback, the allocation count, sbfx_counters) and a pointer to each room's state;
 *   - ARRAY_SIZE. */
#ifndef SBFX_BASE_H
#define SBFX_BASE_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "sbfx.h"

#define ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))

/* The module's handle (sbfx.h's opaque struct sbfx), what every room is given. The ground
 * floor's own state is here. Each room above keeps its state in a struct its own header
 * declares, reached through the pointer below: an incomplete type to a file that does not
 * include that header, which only the room itself and the rooms above it may (src/rooms.txt,
 * tools/layers.sh). The top allocates the rooms' states with the handle, in one block
 * (module.h), and points these at them. */
struct sbfx {
    sbfx_log_fn log;                  /* the host's log callback and its pointer (desc.log, */
    void *log_user;                   /* desc.log_user), set with the desc */
    char last_error[512];
    bool loaded;                      /* sbfx_create finished: heap allocations now count */
    uint64_t heap_allocs_after_load;
    sbfx_counters counters;           /* sbfx_stats: what each room counts */
    int triggers_expired;             /* sbfx_triggers_expired (not in sbfx_counters: its size is ABI) */
    struct sbfx_scene_state *scene;   /* scene/plan.h: the scene as the module keeps it, the plan */
    struct sbfx_tables *tables;       /* tables/scene_tables.h: the loaded scene's tables */
    struct sbfx_sim *sim;             /* sim/sim.h: particles, clock, timeline, the fire's light */
    struct sbfx_gl *gl;               /* gl/gl.h: context, programs, targets, textures, objects */
    struct sbfx_render_state *render; /* render/render.h: post chain, shadow map, read-back probe */
    struct sbfx_budget *budget;       /* budget/budget.h: ladder, governor, GPU timer */
};

/* ---- allocation accounting (alloc.c): every heap allocation of the module goes here ---- */
void *sbfx_calloc(sbfx *fx, size_t count, size_t size);
void sbfx_free(sbfx *fx, void *p);

/* ---- errors and logging (log.c) ---- */
/* Records the message as last error, sends it to the log callback, returns `result`. */
sbfx_result sbfx_fail(sbfx *fx, sbfx_result result, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
void sbfx_log(sbfx *fx, sbfx_log_level level, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* ---- vec3.c ---- */
void sbfx_normalize3(float v[3]);

#endif
