/* The plan (scene/scene.h says what the room is for): the scene as the module keeps it, and
 * what the module builds for it — only what the scene uses (docs/design.md §1). Made at load by
 * the top (sbfx.c: plan, then load) from the desc and the scene; read by every room above. */
#ifndef SBFX_SCENE_PLAN_H
#define SBFX_SCENE_PLAN_H

#include "base/base.h"
#include "scene/scene.h"
#include "tables/tables.h"

#define SBFX_SHADER_LIGHTS 8 /* scene lights (<= 4) + live flashes share these slots */
#define SBFX_MAX_START_TIME 1e10 /* desc.start_time, seconds */

/* What the scene's plan needs beyond the particle passes. */
typedef struct sbfx_plan {
    bool distortion;           /* heat medium: shimmer offsets */
    bool particle_velocity;    /* velocity blur: particles write their screen motion */
    bool motion_target;        /* velocity blur or depth of field: particles write premultiplied
                                  velocity and depth into attachment 2 */
    bool owns_scene;           /* any post effect: sbfx reads the scene colour and writes out */
    bool fire_light;           /* emitting fire and dust or smoke of the phase model: the fire's
                                  light in-scatters there (FIRE_LIGHT, sim/fire_lights.c) */
} sbfx_plan;

/* The scene room's state (fx->scene). */
typedef struct sbfx_scene_state {
    sbfx_desc desc;                      /* with its defaults; quality fields: the current level's */
    sbfx_desc host_desc;                 /* the desc as the host gave it, scene and ladder pointers */
    char host_ladder[SBFX_LADDER_MAX][64]; /* cleared (the names are here): each reload's plan */
    /* quality levels (budget/budget.c declares them at plan time, gl/levels.c makes them) */
    sbfx_quality top;                    /* the quality of the desc (and scene) at create */
    sbfx_quality current;
    sbfx_quality declared[SBFX_LADDER_MAX + 1]; /* made at load: the top and the ladders */
    int declared_count;
    /* the scene as the module keeps it */
    sbfx_medium_params media[SBFX_MEDIUM_COUNT];
    bool uses_medium[SBFX_MEDIUM_COUNT];
    sbfx_post_params post;
    int light_count;
    int light_slots;  /* lights the phase shaders loop over: scene lights + one effect's flashes */
    sbfx_scene_light lights[SBFX_SHADER_LIGHTS];
    float ambient[3];
    sbfx_effect effects[SBFX_MAX_EFFECTS];
    int effect_count;
    sbfx_plan plan;
    /* early termination of the particles (render/terminate.c): the scene's render key, then
     * sbfx_set_early_termination */
    bool early_termination;
    sbfx_tone_curve tone_curve;  /* the composite's (tables/tonemap.c), made at load */
    /* a particle's instance data (render/particles.c writes it, gl/programs.c lays out its buffer) */
    int instance_floats;         /* 8, + 4 previous centre (velocity blur), + 4 light, + 8 fire */
    int instance_previous;       /* float offset of the previous centre, 0 = none */
    int instance_light;          /* float offset of the per-particle light, 0 = none */
    int instance_fire;           /* float offset of the fire light (8 floats), 0 = none */
} sbfx_scene_state;

/* plan.c */
/* Zero means "default": the desc with every default filled in, the scene's settings where the
 * desc leaves them. */
sbfx_desc sbfx_desc_with_defaults(const sbfx_desc *in);
sbfx_result sbfx_desc_validate(sbfx *fx, const sbfx_desc *d);
/* The desc as given (ladder names copied: the host's may go away), for sbfx_set_scene. */
sbfx_result sbfx_keep_host_desc(sbfx *fx, const sbfx_desc *desc);
/* Copies what the module keeps of a scene (media, lights, effects, post chain) and plans the
 * passes and the instance layout. The timeline is the top's to schedule. */
void sbfx_scene_adopt(sbfx *fx, const sbfx_scene *scene);
/* The effect of that name, or -1. */
int sbfx_effect_index(const sbfx *fx, const char *name);
/* The phase shaders' light loop: the scene's lights and the flashes of one effect instance. */
int sbfx_light_slots_of_scene(const sbfx *fx);
/* Whether the scene's fire lights its dust and smoke (the plan's fire_light). */
bool sbfx_fire_lights_media(const sbfx *fx);
/* True when one of the levels made at load (declared) does. */
bool sbfx_declared_any(const sbfx *fx, bool (*uses)(const sbfx *, const sbfx_quality *));
bool sbfx_quality_uses_light_slot(const sbfx *fx, const sbfx_quality *q);
/* Whether the loaded effects use the fire medium / fire lights its dust and smoke (tests). */
bool sbfx_fire_lit(const sbfx *fx);
/* Mutable media parameters (index by sbfx_medium; tests and tools, before sbfx_reload). */
sbfx_medium_params *sbfx_media(sbfx *fx);
/* The desc the module runs with, defaults filled in (tests, bench, CPU reference). */
const sbfx_desc *sbfx_get_desc(const sbfx *fx);

#endif
