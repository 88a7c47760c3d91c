/* The scene room (src/rooms.txt; docs/hacking.md): what the module is asked to show, and the
 * plan of what it builds for it. Above the ground floor and the tables' math (its parser
 * checks the smoke textures' and the lit shader's limits, tables/tables.h).
 *
 * Exports to the rooms above:
 *   - the parsed scene file (this header; scene.c parses, sbfx_scene_* in sbfx.h) and the
 *     host's view of it (scene_host.c);
 *   - what a scene is made of (model.h): media, effects, flashes, lights, post parameters, and
 *     the seed's defaults and built-in explosion (effects.c);
 *   - quality level names (quality_name.c: sbfx_quality_parse/name, resolve, equal);
 *   - the plan (plan.h, plan.c): the desc with its defaults, checked; the scene as the module
 *     keeps it (sbfx_scene_state: media, effects, lights, post chain, the levels declared at
 *     load, the plan's passes and instance layout); the tables the plan decides (scene_tables.h:
 *     black body and phase tables built in double, table or analytic per medium).
 * The module copies what it needs of a parsed scene at sbfx_create (sbfx_scene_adopt). */
#ifndef SBFX_SCENE_H
#define SBFX_SCENE_H

#include "scene/model.h"

#define SBFX_MAX_LIGHTS 4
#define SBFX_MAX_TIMELINE 64
#define SBFX_MAX_GPIO 16
#define SBFX_MAX_EMITTER_COUNT 100000 /* particles of one emitter step */
#define SBFX_SCENE_FILES 16           /* the file and the files it includes, as reported */

typedef enum sbfx_light_type { SBFX_LIGHT_DIRECTIONAL, SBFX_LIGHT_POINT } sbfx_light_type;

typedef struct sbfx_light {
    sbfx_light_type type;
    float vector[3]; /* direction the light travels in (directional) or position (point) */
    float color[3];  /* irradiance; point lights at 1 m */
    sbfx_orbit orbit; /* point lights: circles instead of standing at vector */
} sbfx_light;

typedef struct sbfx_timeline_entry {
    int effect;
    double time;
    float position[3];
} sbfx_timeline_entry;

struct sbfx_scene {
    char name[128];
    sbfx_desc render;   /* render settings given by the file (zero = not given); its ladder
                           points at ladder_names below */
    char ladder_names[SBFX_LADDER_MAX][64];
    const char *ladder_ptrs[SBFX_LADDER_MAX];
    int light_count;
    sbfx_light lights[SBFX_MAX_LIGHTS];
    float ambient[3];
    bool has_medium[SBFX_MEDIUM_COUNT];
    sbfx_medium_params media[SBFX_MEDIUM_COUNT];
    int effect_count;
    sbfx_effect effects[SBFX_MAX_EFFECTS];
    int timeline_count;
    sbfx_timeline_entry timeline[SBFX_MAX_TIMELINE];
    int gpio_count;
    sbfx_gpio_trigger gpio[SBFX_MAX_GPIO];
    sbfx_post_params post;
    bool host_lights, host_shadows; /* render.host_lights, render.host_shadows (sbfx_scene_host) */
    bool early_termination; /* render.early_termination (render/terminate.c); off by default */
    bool has_sky;
    float sky[3];       /* the host's sky colour, linear RGB (sbfx_scene_host) */
    bool has_camera;
    sbfx_scene_camera camera; /* sbfx-play's view; the module does not use it */
    int file_count;           /* the file loaded, then the files it @included (sbfx_scene_file) */
    char files[SBFX_SCENE_FILES][1024];
};

/* The scene sbfx uses when the desc names none: the seed's explosion, fired at t = 0. */
void sbfx_scene_builtin(sbfx_scene *scene);

/* quality_name.c: quality levels (sbfx_quality; their names: sbfx_quality_parse, _name) */
sbfx_quality sbfx_quality_from_desc(const sbfx_desc *d);
/* Fills zero fields with the defaults; false (err says why) for values out of range. */
bool sbfx_quality_resolve(sbfx_quality *q, char *err, size_t size);
bool sbfx_quality_equal(const sbfx_quality *a, const sbfx_quality *b);
/* analytic_phase, table_phase resolved: the table where it is asked for and analytic is not */
void sbfx_phase_resolve(bool *analytic, bool *table);

#endif
