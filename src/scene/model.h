/* What a scene is made of, the scene room's vocabulary (scene/scene.h says what the room is
 * for): media, emitters and effects, light flashes, scene lights, the post chain's parameters,
 * and the seed's defaults (effects.c). */
#ifndef SBFX_SCENE_MODEL_H
#define SBFX_SCENE_MODEL_H

#include <stdbool.h>
#include "sbfx.h"

#define SBFX_MAX_EFFECTS 16
#define SBFX_MAX_EMITTERS 8
#define SBFX_NAME_MAX 32
#define SBFX_LADDER_MAX 16 /* quality levels a ladder names */

/* Soot that wraps the glowing soot (particle.frag, media.fire.soot; docs/look-fire.md "Pink
 * edges"): the share of a column too cool to glow (1 - glow share) carries `soot` times the
 * column's optical depth on top of it (sbfx_fire_cool_soot, sim/fire_light.h). 0: none. */
#define SBFX_FIRE_SOOT_DEFAULT 2.0

/* Per-medium rendering parameters (the seed's values by default). */
typedef struct sbfx_medium_params {
    float albedo;          /* a in equation (1) */
    float tau;             /* extinction at the particle centre */
    float phase_g;         /* phase-function asymmetry (positive = forward) */
    float color[3];        /* tint of the scattering albedo */
    float detail_strength; /* 0 = no perturbation by the detail volume, 1 = full */
    float detail_window;   /* size of a particle's detail window, in volume widths */
    float t0, t1;          /* fire: T = (t0 + t1 * detail) * (1 - cooling * (1 - intensity)) */
    float cooling;         /* fire: fraction of the temperature lost as intensity reaches 0 */
    float soot;            /* fire: optical depth of a column's soot too cool to glow, per unit of
                              its own, in the cool share (1 - glow share): what wraps the glowing
                              soot and absorbs the background (docs/look-fire.md); 0: none */
    bool live_detail;      /* detail source "v4l2": slices come from sbfx_detail_push_slice */
    char detail_clip[256]; /* detail source a video clip (path resolved against the scene file's
                              folder; "" none): the host decodes it and pushes its slices
                              (sbfx_detail_clip, docs/detail-clips.md) */
    float heat_strength;   /* heat: largest screen offset of the shimmer, in UV units */
    float emission_scale;  /* fire: radiance multiplier on the normalised black-body table */
    float emissivity;      /* fire: > 0 sets emission_scale once, in sbfx_create, from photometry
                              (emissivity * L_blackbody / white_luminance; sbfx_reload keeps
                              emission_scale as it is); <= 0: emission_scale as given */
    /* lit-smoke seed (lighting = "lit"; ref/lit_ref.h): per-pixel lit instead of the phase model */
    bool lit;
    float wrap;            /* wrap-around coefficient w (0.6 in the seed) */
    float translucency;    /* strength of the back-lighting term */
    float dampening;       /* fraction of the lights' direct term removed (dense groups) */
    int steps_min, steps_max;          /* ray-march steps nMin, nMax; nMax = 0: no self-shadow */
    int texture_size, texture_variants; /* procedural smoke texture array */
} sbfx_medium_params;

/* One emitter step of an effect: a burst of `count` particles of one medium. */
typedef struct sbfx_emitter {
    sbfx_medium medium;
    int count;
    float delay;                        /* seconds after the trigger */
    float spawn_radius;                 /* particles start inside this ball */
    float speed_min, speed_max;         /* initial outward speed */
    float upward;                       /* 0: isotropic directions, 1: straight up */
    float life_min, life_max;           /* seconds */
    float radius_start, radius_end;     /* radius grows over the lifetime */
    float radius_jitter;                /* relative random spread of radius */
    float drag;                         /* 1/s */
    float buoyancy;                     /* m/s^2 upward */
    float intensity_start, intensity_end; /* density (dust, smoke) / temperature scale (fire) */
    float fade_in;                      /* fraction of life spent fading in */
} sbfx_emitter;

/* Post effects a scene asks for (each exists in the plan only if asked for). */
typedef enum sbfx_blur_mode { SBFX_BLUR_NONE, SBFX_BLUR_HISTORY, SBFX_BLUR_VELOCITY } sbfx_blur_mode;

typedef struct sbfx_post_params {
    sbfx_blur_mode blur;
    float persistence;     /* history: seconds for the old image to fade to 1/e */
    int tile;              /* velocity: tile size = largest blur radius, pixels */
    int samples;           /* velocity: gather samples */
    float shutter;         /* velocity: fraction of the frame interval the shutter is open */
    bool dof;
    float dof_near[2];     /* full near blur at [0], sharp from [1] (view distances) */
    float dof_far[2];      /* sharp until [0], full far blur at [1] */
    float dof_max_radius;  /* full-resolution pixels */
    int dof_scale;         /* blur resolution divisor */
} sbfx_post_params;

/* A light-flash step: a point light at the effect's position (+ offset) that rises at once
 * and decays linearly over `duration`. */
typedef struct sbfx_flash {
    float delay, duration;
    float color[3];
    float offset[3];
} sbfx_flash;

#define SBFX_MAX_FLASHES 4

typedef struct sbfx_effect {
    char name[SBFX_NAME_MAX];
    int emitter_count;
    sbfx_emitter emitters[SBFX_MAX_EMITTERS];
    int flash_count;
    sbfx_flash flashes[SBFX_MAX_FLASHES];
} sbfx_effect;

/* A point light circling `center` in the world's horizontal plane, counter-clockwise seen from
 * above (+y) for period > 0: position = center + radius (cos a, 0, -sin a),
 * a = 2 pi t / period + phase (radians), t = simulation time. */
typedef struct sbfx_orbit {
    bool on;
    float center[3], radius, period, phase;
} sbfx_orbit;

typedef struct sbfx_scene_light { /* scene light, as the module keeps it */
    bool point;
    float vector[3], color[3];
    sbfx_orbit orbit;  /* point lights: vector follows it (sbfx_orbit_lights) */
} sbfx_scene_light;

/* effects.c: the seed's media, the built-in explosion, the post chain's values when asked */
void sbfx_default_media(sbfx_medium_params media[SBFX_MEDIUM_COUNT]);
void sbfx_builtin_explosion(sbfx_effect *out);
void sbfx_default_post(sbfx_post_params *post);

#endif
