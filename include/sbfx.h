/* sbfx — volumetric particle effects (spherical billboards) on OpenGL ES 3.0.
 *
 * The one public header. The module is created on the caller's *current* GLES 3.0 context; it
 * never owns a window, display or context. Every call that can fail returns an sbfx_result and
 * leaves a message readable with sbfx_last_error(); the library never exits the process.
 *
 * Conventions: matrices are column-major float[16] (OpenGL order); view space has the camera at
 * the origin looking down -z; depths are reported as positive distances along -z.
 */
#ifndef SBFX_H
#define SBFX_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Marks what libsbfx.so exports: the library is built with -fvisibility=hidden, so a function
 * of this header without SBFX_API would be missing from it (tests/exports.sh checks both ways). */
#ifndef SBFX_API
#if defined(__GNUC__) && __GNUC__ >= 4
#define SBFX_API __attribute__((visibility("default")))
#else
#define SBFX_API
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sbfx_result {
    SBFX_OK = 0,
    SBFX_ERR_INVALID_ARGUMENT = -1, /* a NULL pointer, a value out of range */
    SBFX_ERR_NO_GLES3 = -2,         /* no current context, or it is not OpenGL ES 3.0+ */
    SBFX_ERR_GL = -3,               /* a GL call or framebuffer failed */
    SBFX_ERR_SHADER = -4,           /* a shader failed to compile or link */
    SBFX_ERR_MISSING_DATA = -5,     /* no longer returned: the module reads no data file */
    SBFX_ERR_OUT_OF_MEMORY = -6,
    SBFX_ERR_POOL_FULL = -7,        /* a trigger found no room in the particle pool */
    SBFX_ERR_UNKNOWN_EFFECT = -8,
} sbfx_result;

SBFX_API const char *sbfx_result_string(sbfx_result result);

typedef enum sbfx_log_level { SBFX_LOG_ERROR, SBFX_LOG_WARN, SBFX_LOG_INFO } sbfx_log_level;
typedef void (*sbfx_log_fn)(sbfx_log_level level, const char *message, void *user);

/* Accuracy knobs. Zero in a desc always means "the default" (marked). */
typedef enum sbfx_opacity_mode {
    SBFX_OPACITY_DEFAULT = 0, /* = EXACT: as cheap as SPHERICAL and ten times closer to the
                                 reference (docs/accuracy-and-benchmarks.md, the defaults) */
    SBFX_OPACITY_PLANAR,      /* classic billboard: radial profile, emulated depth test */
    SBFX_OPACITY_SOFT,        /* planar faded by an S-curve of the depth difference (RTR) */
    SBFX_OPACITY_SPHERICAL,   /* the seed: parallel rays, (1 - d/r) * clipped chord; twice the
                                 exact model's optical depth through the centre */
    SBFX_OPACITY_EXACT,       /* perspective ray, exact integral of the linear density */
    SBFX_OPACITY_FLOOR,       /* benchmark only: the same quads with a trivial shader */
    SBFX_OPACITY_COUNT
} sbfx_opacity_mode;

typedef enum sbfx_target_format {
    SBFX_FORMAT_DEFAULT = 0, /* RGBA16F when colour-renderable, else RGBA8 (logged once) */
    SBFX_FORMAT_RGBA8,
    SBFX_FORMAT_RGBA16F,
    SBFX_FORMAT_RGBA32F,
    SBFX_FORMAT_COUNT
} sbfx_target_format;

typedef enum sbfx_upsample {
    SBFX_UPSAMPLE_DEFAULT = 0, /* = NEAREST_DEPTH */
    SBFX_UPSAMPLE_BILINEAR,
    SBFX_UPSAMPLE_NEAREST_DEPTH,
    SBFX_UPSAMPLE_MIXED,       /* nearest-depth, and the particles shaded again at full
                                  resolution where the coarse target fails: opaque depth edges
                                  inside a coarse texel, strong gradients of the coarse image
                                  (docs/quality-and-budgets.md, "Mixed resolution") */
    SBFX_UPSAMPLE_COUNT
} sbfx_upsample;

typedef enum sbfx_detail_format {
    SBFX_DETAIL_DEFAULT = 0, /* = R16F: half float, filterable in core ES 3.0 */
    SBFX_DETAIL_R16F,
    SBFX_DETAIL_R32F,        /* not filterable in ES 3.0: sampled NEAREST (shows the cost) */
    SBFX_DETAIL_COUNT
} sbfx_detail_format;

/* How the particles' light (already times desc.exposure) meets the host's framebuffer. Over a
 * host pixel dst seen through the particles' transmittance T, the light C is brought within the
 * room the picture leaves, room_k = 1 - T dst_k, so dst * T + C never clips where the host's
 * picture does not. dst is read from frame.scene_color_texture (black when there is none, or when
 * it is the texture out_framebuffer draws into). The curve is the identity up to 0.6 and a
 * logarithmic shoulder above that reaches 1 at 16384, the particles' radiance ceiling (filmic:
 * white with slope 0 at 1024); docs/colour.md, docs/look-fire.md. */
typedef enum sbfx_tone_map {
    SBFX_TONE_MAP_DEFAULT = 0,     /* = FILMIC */
    SBFX_TONE_MAP_NONE,            /* light added as computed: each channel clips on its own */
    SBFX_TONE_MAP_HUE_PRESERVING,  /* C scaled by curve(r) / r, r = max C_k / room_k: hue kept */
    SBFX_TONE_MAP_PER_CHANNEL,     /* C_k = room_k curve(C_k / room_k): bright colours turn white */
    SBFX_TONE_MAP_FILMIC,          /* a path to white for emitters: the curve per channel between
                                      a small cross-talk and its inverse; hue kept below 0.6 */
    SBFX_TONE_MAP_COUNT
} sbfx_tone_map;

/* Media of the particle family. Heat neither absorbs nor emits: it displaces the scene behind
 * it (heat shimmer). */
typedef enum sbfx_medium { SBFX_DUST, SBFX_SMOKE, SBFX_FIRE, SBFX_HEAT, SBFX_MEDIUM_COUNT } sbfx_medium;

/* A parsed scene file (libconfig syntax; docs/scene-format.md): render settings, lights,
 * media, effects made of steps, and triggers. Loading either succeeds whole or leaves nothing
 * behind; errors name the file and line. */
typedef struct sbfx_scene sbfx_scene;

SBFX_API sbfx_result sbfx_scene_load(const char *path, sbfx_scene **out, char *err,
                                     size_t err_size);
/* The same from text in memory; `name` stands for the file name in messages. */
SBFX_API sbfx_result sbfx_scene_parse(const char *text, const char *name, sbfx_scene **out,
                                      char *err, size_t err_size);
SBFX_API void sbfx_scene_free(sbfx_scene *scene);

typedef enum sbfx_edge { SBFX_EDGE_RISING = 1, SBFX_EDGE_FALLING = 2, SBFX_EDGE_BOTH = 3 } sbfx_edge;

/* A GPIO line that fires an effect: read by the platform layer, which calls sbfx_trigger. */
typedef struct sbfx_gpio_trigger {
    char chip[64];        /* "gpiochip0" or a path */
    int line;
    sbfx_edge edge;
    int debounce_ms;
    char effect[32];
    float position[3];
} sbfx_gpio_trigger;

/* The scene's GPIO triggers; returns their count and sets *out to an array owned by the scene. */
SBFX_API int sbfx_scene_gpio_triggers(const sbfx_scene *scene, const sbfx_gpio_trigger **out);

/* One trigger of a scene's timeline (since 1.5.0): a host that runs the timeline on a clock of
 * its own (sbfx-play's --world-time: at world times, as identified triggers) reads it here and
 * creates the module with desc.ignore_timeline. */
typedef struct sbfx_timeline_trigger {
    const char *effect;  /* owned by the scene */
    double time;         /* seconds from the timeline's start */
    float position[3];
} sbfx_timeline_trigger;
/* Fills *out with the scene's timeline trigger number index (0, 1, ...) and returns true; false
 * past the last. scene NULL: the built-in timeline (one "explosion" at 0 at the origin). */
SBFX_API bool sbfx_scene_timeline_get(const sbfx_scene *scene, int index, sbfx_timeline_trigger *out);

/* Where a viewer's camera looks at the scene: its `camera` group, read by sbfx-play (the module
 * itself draws from whatever view the host gives it). The eye circles the target. */
typedef struct sbfx_scene_camera {
    float target[3];   /* the point looked at (world) */
    float distance;    /* of the eye from the target, horizontally (m) */
    float height;      /* of the eye (world y, m) */
    float azimuth;     /* degrees around +y at t = 0; 0: the eye on the target's +z side,
                          90: on its +x side */
    float orbit;       /* degrees per second the eye moves on (0: a fixed camera) */
    float fov;         /* vertical field of view, degrees */
} sbfx_scene_camera;

/* Fills *out with the scene's camera, keys it leaves out taken from the default orbit; with no
 * camera group (or scene NULL) with the default orbit, and returns false. */
SBFX_API bool sbfx_scene_camera_get(const sbfx_scene *scene, sbfx_scene_camera *out);

typedef struct sbfx_desc {
    int target_divisor;              /* particle target = output / divisor per axis: 1,2,4,8 (4) */
    sbfx_target_format target_format;
    sbfx_upsample upsample;
    sbfx_opacity_mode opacity;
    uint32_t seed;                   /* random seed of spawns and detail windows (1) */
    int max_particles;               /* particle pool size (2048) */
    const char *cmf_path;            /* ignored: the CIE 1931 2° CMFs are compiled in (kept for the layout) */
    float blackbody_max_kelvin;      /* the black body's unit: luminance 1 at this temperature,
                                        before the fire's emission scale (6000 K). The table's
                                        range follows what the scene's fire can reach. */
    int detail_size;                 /* detail volume width = height (128) */
    int detail_frames;               /* detail volume depth = animation frames (32) */
    sbfx_detail_format detail_format;
    bool analytic_blackbody;         /* Planck x CIE evaluated per fragment, not the table */
    bool analytic_phase;             /* phase function evaluated per fragment: the default
                                        since issue 43; set, it wins over table_phase */
    bool light_per_particle;         /* phase-model in-scattering evaluated once per particle
                                        (on the CPU, at its centre) instead of per fragment */
    bool table_phase;                /* the phase function sampled from its table (scene
                                        render.phase = "table", level flag tph) instead */
    sbfx_tone_map tone_map;          /* the particles' light on the display (hue-preserving) */
    float exposure;                  /* scale of the particles' light (1), applied where it is
                                        made (pre-exposed in the particle target) */
    float sim_step;                  /* fixed simulation step in seconds (1/120) */
    double start_time;               /* seconds: where the simulation clock starts (0). A kiosk
                                        that keeps its clock across restarts passes the last
                                        sbfx_time() here. Everything periodic (detail
                                        animation, orbiting lights) follows the clock, reduced
                                        in double precision, so it renders the same after a
                                        year as at 0; timelines and sbfx_schedule count from
                                        the start (sbfx_elapsed). 0 .. 1e10 (about 317 years). */
    const sbfx_scene *scene;         /* NULL: the built-in explosion. Non-zero fields of this
                                        desc override the scene's render settings. The scene
                                        may be freed once sbfx_create returns. */
    bool ignore_timeline;            /* do not fire the scene's timeline triggers */
    sbfx_log_fn log;                 /* NULL: messages go nowhere, sbfx_last_error() still works */
    void *log_user;
    /* Frame budget (docs/quality-and-budgets.md): with frame_budget_ms > 0 sbfx measures its own
     * GPU time per frame and walks a quality ladder to stay within it. The quality this desc (and
     * the scene) gives is the ladder's top: the budget never raises it. 0 = no budget. */
    int lod_particles;               /* at most this many particles drawn, the least visible
                                        merged (level of detail); 0 = all */
    float frame_budget_ms;
    /* Quality levels (sbfx_quality_parse names), most accurate first: the ladder the budget
     * walks below the top (NULL: the scene's render.ladder, else the default ladder). Their
     * shader variants are built at load, so sbfx_set_quality to any of them never compiles. */
    const char *const *ladder;
    int ladder_count;
    /* Photometric unit (docs/look-fire.md): the luminance in cd/m^2 that a linear 1.0 stands
     * for, in the host's picture and in the lights' colours (10000: a daylight sky of linear
     * luminance 0.69 is about 7000 cd/m^2). Fire given an emissivity emits
     * emissivity * L_blackbody(T) / white_luminance. 0: the scene's, else 10000. */
    float white_luminance;
    /* Transmittance shadow map for the host (sbfx_render_shadow_map): texels per side, 16 .. the
     * context's largest renderable size. 0: the scene's (render.shadow_map_size, or 256 with
     * render.host_shadows = true), else none: no texture, framebuffer or program is made. */
    int shadow_map_size;
} sbfx_desc;

/* How the host's clip-space depth became the window depth its depth texture holds (with the
 * default glDepthRangef(0, 1)). Zero is OpenGL's default; a host that calls
 * glClipControlEXT(GL_LOWER_LEFT, GL_ZERO_TO_ONE) says so here. Together with the projection
 * matrix this fixes how depth reads back as distance (docs/embedding.md "Projections and depth"). */
typedef enum sbfx_clip_depth_mode {
    SBFX_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE = 0, /* window depth = (ndc_z + 1) / 2 */
    SBFX_CLIP_DEPTH_ZERO_TO_ONE,             /* window depth = ndc_z (GL_EXT_clip_control) */
    SBFX_CLIP_DEPTH_COUNT
} sbfx_clip_depth_mode;

/* One frame to render. The opaque scene has been drawn by the host into colour and depth
 * textures of width x height; sbfx composites into out_framebuffer (0 = default).
 * The projection is any OpenGL perspective (column-major, clip w = -z_view): finite far,
 * infinite far (projection[10] = -1, [14] = -2 near), off-axis ([8], [9] != 0) or reversed-Z
 * (projection[14] > 0: near -> depth 1, far -> 0, usually with SBFX_CLIP_DEPTH_ZERO_TO_ONE and
 * a 32-bit float depth buffer cleared to 0). The depth texture's clear value (1, or 0
 * reversed) means "no surface": nothing is clipped there, not even by a finite far plane.
 * Anything else (orthographic, skewed, oblique, NaN, far before near) is refused with
 * SBFX_ERR_INVALID_ARGUMENT and a message naming what is wrong.
 * sbfx reads both textures through its own sampler objects (depth: NEAREST, no comparison;
 * colour: LINEAR, clamped): their own parameters are never changed, and they need no
 * particular filter or compare mode. Clip origin: GL_LOWER_LEFT (the default). */
typedef struct sbfx_frame {
    float view[16];          /* world -> view */
    float projection[16];    /* a perspective projection (above) */
    uint32_t scene_color_texture; /* 0: none (post effects need it; the tone map reads it) */
    uint32_t scene_depth_texture;
    uint32_t out_framebuffer;
    int width, height;
    sbfx_clip_depth_mode clip_depth_mode;
} sbfx_frame;

typedef struct sbfx_counters {
    int programs;             /* GL programs linked */
    int textures;             /* GL textures created by sbfx */
    int framebuffers;
    size_t gpu_bytes;         /* texture + buffer storage held */
    int passes;               /* render passes of the last sbfx_render */
    int draw_calls;           /* draw calls of the last sbfx_render */
    int particles_simulated;  /* particles advanced by the last sbfx_update */
    int particles_alive;
    int particles_skipped;    /* bad particles (NaN/Inf/negative radius) skipped last render */
    int triggers_fired;       /* effect instances started since load */
    int triggers_refused;     /* triggers refused because the pool was full */
    uint64_t heap_allocs_after_load; /* sbfx heap allocations since sbfx_create returned */
    sbfx_target_format target_format; /* the format actually in use */
    int gl_state_queries;     /* glGet* / glIs* calls the last sbfx_render made to save and
                                 restore the host's GL state (0 when it ran no pass);
                                 docs/embedding.md "What sbfx does to your GL state" */
    char quality[64];         /* the current quality level's name (sbfx_quality_name) */
    float budget_ms;          /* desc.frame_budget_ms (0: none) */
    float gpu_ms;             /* smoothed GPU time of sbfx's work per frame (budget only) */
    int frames_over_budget;   /* measured frames whose GPU time exceeded the budget */
    int quality_changes;      /* level changes the budget made */
    int emitted_lights;       /* point lights sbfx_emitted_lights gathered from the fire after the
                                 last update (0: none, or not asked) */
    int fire_lit_particles;   /* dust and smoke particles the fire lit in the last render (0
                                 without emitting fire, or without dust or smoke to light) */
    int shadow_passes;        /* passes of the last sbfx_render_shadow_map (0: no particle cast
                                 a shadow, or the map was not asked for) */
    /* since sbfx_create, reloads (sbfx_set_scene) included: what was made, not what was
     * taken over from the scene before */
    int programs_compiled;    /* GL programs compiled and linked */
    int targets_created;      /* framebuffers created (particle, depth and post targets) */
    int scene_reloads;        /* scenes taken over by sbfx_set_scene */
    /* since 1.4.0 (at the end: the members before keep their offsets) */
    int composite_tiles;      /* screen tiles the last sbfx_render composited: those its particles
                                 can change (0: it drew no particle); docs/gpus.md "Tiles" */
    int composite_pixels;     /* output pixels those tiles cover: the composite's and the depth
                                 downsample's share of the screen */
} sbfx_counters;

typedef struct sbfx sbfx;

/* GL errors the host left pending. GL keeps an error until someone calls glGetError, so an
 * error a host (or its toolkit: Qt 6.4 leaves GL_INVALID_OPERATION after glPolygonMode on ES
 * contexts) leaves behind is not sbfx's failure. Each entry point that makes GL calls and checks
 * them (sbfx_create, sbfx_set_scene, sbfx_render when it draws, sbfx_set_quality,
 * sbfx_detail_push_slice) first reads the pending errors off (up to 8 distinct codes), so its
 * checks see only its own, and before it returns posts them again for the host, in the order
 * they were read, by a call that fails with that error and has no other effect:
 * GL_INVALID_ENUM by glEnable(GL_NONE), GL_INVALID_VALUE by glLineWidth(0),
 * GL_INVALID_OPERATION by glBeginQuery(GL_ANY_SAMPLES_PASSED, 0).
 * GL_INVALID_FRAMEBUFFER_OPERATION, GL_OUT_OF_MEMORY and GL_CONTEXT_LOST cannot be posted
 * that way: they are dropped. Either way the log says so once per module and kind (INFO when
 * posted again, WARN when dropped). sbfx_render with nothing to draw, sbfx_update,
 * sbfx_trigger and the other calls make no GL call and leave pending errors alone; sbfx_destroy
 * deletes its objects without reading errors, so pending ones stay pending. */

SBFX_API sbfx_result sbfx_create(const sbfx_desc *desc, sbfx **out);
SBFX_API void sbfx_destroy(sbfx *fx);

/* Replaces the scene of a live module (an authoring loop that reloads a file as it is edited, a
 * kiosk's `systemctl reload`); scene NULL is the built-in explosion. The module is planned again
 * from the desc given to sbfx_create with this scene in place of its scene, and built: what the
 * new scene needs the same way as the old one — shader programs with the same defines, targets of
 * the same size and formats — is taken over, so a change of numbers only (a temperature, a count,
 * a colour) compiles no shader and creates no target (sbfx_counters.programs_compiled and
 * targets_created say so); what it needs anew is made, and what it no longer needs is deleted.
 * The new scene takes over at once (call it between frames): the clock (sbfx_time,
 * sbfx_elapsed) goes on; the scene's timeline starts again from now; live particles, pending
 * sbfx_schedule triggers and live light flashes are dropped, and the quality is the new plan's
 * top. Detail pushed with sbfx_detail_push_slice is not kept (the new volume is procedural):
 * push it again.
 * A reload is a load: it may allocate; frames after it allocate nothing. It saves and restores
 * the GL state it changes, like sbfx_create. On failure (a shader that does not build, a GL
 * error, a render setting out of range) the module goes on with its old scene, unchanged, and
 * the error is returned with a message (sbfx_last_error, the log). The scene may be freed once
 * the call returns. */
SBFX_API sbfx_result sbfx_set_scene(sbfx *fx, const sbfx_scene *scene);
/* The files a loaded scene was read from: index 0 is the file sbfx_scene_load was given, then
 * every file its @include directives brought in (a watcher reloads when one of them changes);
 * NULL past the last, and for scenes parsed from memory. */
SBFX_API const char *sbfx_scene_file(const sbfx_scene *scene, int index);
SBFX_API const char *sbfx_last_error(const sbfx *fx);

/* Starts an instance of a named effect at a world position now (at the next simulation step).
 * Without a scene the one effect is "explosion". When the pool cannot hold the whole instance
 * the trigger is refused (SBFX_ERR_POOL_FULL, counted in triggers_refused); live instances
 * are never cut short. */
SBFX_API sbfx_result sbfx_trigger(sbfx *fx, const char *effect, const float position[3]);
/* Schedules a trigger at `seconds` since sbfx_create (the sbfx_elapsed() clock, not
 * sbfx_time(): a scene's timeline means the same whatever desc.start_time is); it fires at the
 * first simulation step at or after that time, so results do not depend on frame times. */
SBFX_API sbfx_result sbfx_schedule(sbfx *fx, const char *effect, double seconds,
                                   const float position[3]);
/* Effects as functions of identity and time (since 1.5.0; docs/embedding.md "Channels: identity
 * and time"). Several processes that draw slices of one world (a simulator's channels) start the
 * same effect with the same identity and start time, and draw the same particles at the same
 * world time: an identified instance's particles are seeded from its identity alone (not from
 * desc.seed, nor from how many triggers came before), and simulated with the fixed step from its
 * start time (step j at start_time + j * sim_step), whatever the order the triggers arrive in,
 * the frame rate, or when the module was made. A module that hears of it after it started (a
 * channel restarted late) catches up at once in fixed steps, at most the effect's longest
 * delay + life, and shows it at its age; one whose every particle and flash has already ended is
 * not started (counted by sbfx_triggers_expired). Frames of different modules agree when their clocks
 * (sbfx_time) agree at the frame: give them the same desc.sim_step and start times on its grid. */
#define SBFX_TRIGGER_DESC_VERSION 1
typedef struct sbfx_trigger_desc {
    uint32_t version;        /* SBFX_TRIGGER_DESC_VERSION: the layout the caller was built with */
    const char *effect;      /* the effect's name (sbfx_has_effect) */
    float position[3];       /* world */
    uint64_t identity;       /* 1 .. 2^63-1: what names this instance in every process (DIS: site,
                                application and event number; CIGI: entity ID and generation) */
    double start_time;       /* on the module's clock (sbfx_time): the world time it started at;
                                may be in the past (drawn at its age) or ahead (waits) */
} sbfx_trigger_desc;
/* Starts an identified instance (above). SBFX_ERR_INVALID_ARGUMENT for a version this library
 * does not know, an identity of 0 or >= 2^63, a position or start time that is not finite;
 * SBFX_ERR_UNKNOWN_EFFECT, SBFX_ERR_POOL_FULL as sbfx_trigger. The trigger listener is told with
 * `time` = start_time. Allocates nothing. */
SBFX_API sbfx_result sbfx_trigger_identified(sbfx *fx, const sbfx_trigger_desc *trigger);
/* Ends the identified instance now (since 1.5.0): its particles are gone from the next render
 * and its light flashes go out (CIGI: the entity was Destroyed, or its animation stopped).
 * Returns the number of particles removed (0: none was live, e.g. it had ended, or another
 * channel's trigger never came), or a negative sbfx_result for a NULL module or identity 0.
 * Allocates nothing. */
SBFX_API int sbfx_stop_identified(sbfx *fx, uint64_t identity);
/* Identified triggers not started since the module was made (since 1.5.0): every particle and
 * flash of theirs had ended by the module's clock when they came. A call of its own rather than a
 * field of sbfx_counters: hosts built against 1.4 pass sbfx_stats a counters struct of 1.4's
 * size, which the library must not write past (the ABI check, tests/abi.sh). 0 for NULL. */
SBFX_API int sbfx_triggers_expired(const sbfx *fx);
/* Where an effect instance the module started came from (sbfx_set_trigger_listener). */
typedef enum sbfx_trigger_origin {
    SBFX_TRIGGER_CALL,     /* sbfx_trigger */
    SBFX_TRIGGER_SCHEDULE, /* sbfx_schedule */
    SBFX_TRIGGER_TIMELINE  /* the scene's timeline */
} sbfx_trigger_origin;
/* Told of every effect instance the module starts, as it starts: inside sbfx_trigger, or inside
 * sbfx_update at the step a scheduled or timeline trigger fires at. `time` is the clock
 * (sbfx_time) at the instance's first step; refused triggers (pool full) are not told. The
 * listener must not call the module back (sbfx_time and sbfx_elapsed excepted). */
typedef void (*sbfx_trigger_fn)(const char *effect, const float position[3], double time,
                                sbfx_trigger_origin origin, void *user);
/* Sets the listener (NULL: none); it stays across sbfx_set_scene. A host that logs what fired
 * learns here of the scene's timeline, which it does not see otherwise. */
SBFX_API void sbfx_set_trigger_listener(sbfx *fx, sbfx_trigger_fn fn, void *user);
/* True when the module has an effect of that name (the scene's, or the built-in "explosion"):
 * lets a host check at start the names it will trigger later (GPIO lines, remote commands). */
SBFX_API bool sbfx_has_effect(const sbfx *fx, const char *effect);
/* The name of the module's effect number index (0, 1, ...), NULL past the last: lets a host name
 * the effects there are when it is given one that is not (an error message). */
SBFX_API const char *sbfx_effect_name(const sbfx *fx, int index);
/* The simulation clock in seconds: desc.start_time + sbfx_elapsed(). Absolute, so a kiosk can
 * persist it and restart where it was (desc.start_time); hosts that animate from it should reduce
 * periodic values in double precision (fmod) before making floats of them. */
SBFX_API double sbfx_time(const sbfx *fx);
/* Simulation time in seconds since sbfx_create, counted in whole fixed steps: the clock of
 * sbfx_schedule and of the scene's timeline. */
SBFX_API double sbfx_elapsed(const sbfx *fx);
/* Advances the simulation by dt seconds in fixed steps (an accumulator keeps the remainder). At
 * most 0.25 s (+ one step) is owed at a time: a longer dt (a stall, a suspended board) is cut
 * there, so the simulation never spins to catch up; hosts that want more call it again. */
SBFX_API sbfx_result sbfx_update(sbfx *fx, double dt);
SBFX_API sbfx_result sbfx_render(sbfx *fx, const sbfx_frame *frame);
/* For hosts that play a stream (a video filter: docs/hosts/gstreamer.md). Since 1.3.0.
 * sbfx_restart puts the module back where sbfx_create left it, with this scene (NULL: the
 * built-in explosion) planned from the desc given to sbfx_create: the clock at zero
 * (sbfx_elapsed() = 0, sbfx_time() = desc.start_time), the scene's timeline scheduled from
 * there, no particle, flash or pending trigger, the same random streams; what a stream's seek
 * needs, so that the frames after a seek back to the start are those of the first pass. It is
 * sbfx_set_scene otherwise: GL objects made the same way are taken over (a restart with the
 * same scene compiles nothing), it may allocate, it saves and restores the GL state it
 * changes, detail pushed with sbfx_detail_push_slice is not kept, and on failure the module
 * goes on unchanged, clock included. */
SBFX_API sbfx_result sbfx_restart(sbfx *fx, const sbfx_scene *scene);
/* True when an sbfx_render now would draw nothing and make no GL call: no particle is live
 * past its emitter's delay and the scene has no post effect (those pass every frame). Asked
 * after sbfx_update, it lets a host pass its picture on unchanged, without a copy. No GL call. */
SBFX_API bool sbfx_idle(const sbfx *fx);
SBFX_API void sbfx_stats(const sbfx *fx, sbfx_counters *out);

/* Fire lights the host (docs/embedding.md "Fire lights your scene"). Each frame the live fire
 * particles' black-body light is gathered into a few point lights: the fire within 2 m of its
 * brightest particle makes one light at the luminance-weighted centre of its particles.
 * A host shades its own scene with them, with this falloff at distance d (m) from `position`:
 *     falloff(d) = window(d / radius) / max(d^2, 0.25),  window(x) = clamp(1 - x^4, 0, 1)^2
 * so that a white Lambertian surface facing the light has radiance color * falloff(d) (times the
 * host's exposure, as for its other lights). In GLSL:
 *     float x = d / radius, window = clamp(1.0 - x * x * x * x, 0.0, 1.0);
 *     vec3 lit = albedo * color * (window * window / max(d * d, 0.25)) * max(dot(n, l), 0.0);
 * Units: the scene's linear light units (a linear 1.0 stands for desc.white_luminance cd/m^2; the
 * same units as the scene's light colours, before desc.exposure). The fire's radiance is what the
 * particles emit (emissivity x L_blackbody(T) / white_luminance); a light's radiant intensity I
 * is that radiance integrated over each particle's disc, less what the fire particles in front of
 * it absorb (averaged over directions), and color = I / pi, which is what makes the
 * Lambertian radiance above right: the flux that leaves the fire is 4 pi I = 4 pi^2 color. */
#define SBFX_MAX_POINT_LIGHTS 16
typedef struct sbfx_point_light {
    float position[3]; /* world space */
    float color[3];    /* radiant intensity / pi in the scene's linear units (through
                          white_luminance), normalised to the flux that leaves the fire (above) */
    float radius;      /* distance beyond which the light is negligible (influence radius): where
                          color x exposure / d^2 falls below 1/2048, at least the fire's extent
                          + 0.5 m; falloff(d) is 0 from there on */
} sbfx_point_light;
/* Writes up to max lights emitted this frame (after the last sbfx_update) into out, brightest
 * first; returns the number written (>= 0: 0 with no live fire, or a scene without fire) or a
 * negative sbfx_result on bad arguments (max out of 1..SBFX_MAX_POINT_LIGHTS, out NULL); on error
 * nothing is written and sbfx_last_error says why. No GL call, no allocation; the gathering runs
 * once per update, on the first call. */
SBFX_API int sbfx_emitted_lights(sbfx *fx, sbfx_point_light *out, int max);

/* Run-time quality (docs/quality-and-budgets.md): what sbfx_desc's accuracy knobs choose at
 * create, changeable between frames without losing the simulation. Zero fields mean the
 * default, as in sbfx_desc. */
typedef struct sbfx_quality {
    sbfx_opacity_mode opacity;
    int target_divisor;              /* 1, 2, 4 or 8 */
    sbfx_upsample upsample;
    sbfx_target_format target_format;
    bool light_per_particle;
    bool analytic_blackbody;
    bool analytic_phase;             /* the default: resolved, exactly one of these two is set */
    bool table_phase;                /* level flag tph: the phase function's table */
    int lod_particles;               /* at most this many particles drawn (level of detail);
                                        0 = all */
} sbfx_quality;

/* Effective at the next sbfx_render. A frame rendered after switching to q is bit-identical to
 * the same frame of a module created with q. The first use of a level the load did not declare
 * (desc.ladder, render.ladder, the budget's ladder) builds its shader variants and targets;
 * after that, switching to it allocates nothing. With a frame budget the governor goes on
 * choosing: q becomes the ladder's top only when created so (set_quality picks a level). */
SBFX_API sbfx_result sbfx_set_quality(sbfx *fx, const sbfx_quality *q);
SBFX_API sbfx_result sbfx_get_quality(const sbfx *fx, sbfx_quality *out);
/* Early termination of the particles (since 1.5.0; docs/gpus.md "Front to back, and early
 * termination"): drawn nearest first, a texel stops taking particles once what it lets through
 * is below a bound derived so that what it loses stays under a quarter of an 8-bit level on the
 * display. Off by default (a scene's render.early_termination = true turns it on at load;
 * sbfx-play --early-termination on): in an RGBA16F target the nearest-first order carries each
 * stored transmittance's rounding into the light behind it, about twice the error of back to
 * front against RGBA32F. Effective at the next sbfx_render; turning it on in a module loaded
 * without it makes its mark program now and its targets again at that render. */
SBFX_API sbfx_result sbfx_set_early_termination(sbfx *fx, bool on);
/* Level names: <opacity>/<divisor>/<upsample>[/<flag>...] with opacity planar | soft |
 * spherical | exact, divisor 1 | 2 | 4 | 8, upsample nd (nearest-depth) | bl (bilinear) | mx
 * (mixed resolution: nearest-depth, refined at full resolution where the coarse target fails), flags
 * rgba8 | rgba16f | rgba32f (target format), lpp (light per particle), abb (analytic black
 * body), tph (the phase function's table; the analytic phase is the default, and aph, which
 * named it, is still accepted), lodN (at most N particles). "exact/4/nd", "spherical/8/bl/lod256".
 * Parse fills *out (defaults resolved) or names the bad token in err. */
SBFX_API sbfx_result sbfx_quality_parse(const char *name, sbfx_quality *out, char *err, size_t err_size);
/* The canonical name of q (parse(name(q)) == q); returns buf. */
SBFX_API const char *sbfx_quality_name(const sbfx_quality *q, char *buf, size_t size);
/* The frame-budget fallback where GL_EXT_disjoint_timer_query is missing: the host passes the
 * time sbfx's work took in the frame just rendered (e.g. glFinish before and after sbfx_render,
 * or a timer of its own). Ignored when the module measures itself or has no budget. */
SBFX_API void sbfx_report_frame_time(sbfx *fx, double ms);

/* Live detail images (e.g. from a V4L2 camera). The detail volume is size x size x frames
 * half floats in [0,1] whose third axis is a time ring; each call writes the next slice
 * (size * size IEEE half-float bit patterns, row 0 first) and advances the ring. */
SBFX_API void sbfx_detail_dimensions(const sbfx *fx, int *size, int *frames);
/* True when a medium of the loaded scene asks for detail source "v4l2". */
SBFX_API bool sbfx_wants_live_detail(const sbfx *fx);
SBFX_API sbfx_result sbfx_detail_push_slice(sbfx *fx, const uint16_t *half_texels, int size);
/* The video clip a medium of the loaded scene names as its detail source (detail.source = a
 * file's path; relative paths are resolved against the scene file's folder), or NULL. The module
 * opens no file: the host decodes the clip and pushes its frames (one full turn of the ring).
 * platform/video/clip_detail.c does this with FFmpeg's libraries for sbfx-play and can be
 * compiled into any host (docs/detail-clips.md). Until then the volume holds procedural detail. */
SBFX_API const char *sbfx_detail_clip(const sbfx *fx);
/* The procedural volume the module made at load (size * size * frames values in [0,1], x
 * fastest, then y, then the time ring) written into the caller's `out` of `count` floats: a host
 * whose live source went away pushes it back, slice by slice, to return to procedural detail.
 * Allocates nothing. SBFX_ERR_INVALID_ARGUMENT when count is not size * size * frames. */
SBFX_API sbfx_result sbfx_detail_procedural(const sbfx *fx, float *out, size_t count);

/* Smoke shades the host (RTR 13.8.1; docs/embedding.md "Smoke that shades the host"). sbfx
 * renders the live particles' transmittance, seen from one directional light, into a texture
 * of its own (desc.shadow_map_size texels per side, made at load); the host multiplies the
 * value it makes of it into that light's visibility. The map holds, in .r, the transmittance
 * along the light's ray through every particle (the exact model's optical depth of each
 * particle's mean density, detail not sampled): 1 where no particle is, and on the map's
 * border, so a CLAMP_TO_EDGE lookup outside the particles reads 1. And where along the light
 * it absorbs, in the map's depth z = (view_projection * p).z * 0.5 + 0.5 (0 where the particles
 * begin, 1 where they end): .a the nearest z where any particle begins, .g the product of
 * exp(-optical depth x the particle centre's z), .b of exp(-optical depth x (z^2 + the chord's
 * variance)), so log g / log r is the optical-depth-weighted mean depth and log b / log r its
 * mean square. docs/embedding.md's smoke_visibility() makes of them 1 above the smoke, .r
 * under it and the share in front of a surface inside it; .r alone shades a surface above the
 * cloud like one below it. The texture is LINEAR filtered, RGBA16F where half floats are
 * renderable, else RGBA8; the host only samples it and leaves its parameters alone. It is
 * fitted to the particles each call: a world point p looks up uv = (view_projection * p).xy *
 * 0.5 + 0.5. */
typedef struct sbfx_shadow_map {
    uint32_t texture;            /* sbfx's GL texture (valid until sbfx_destroy) */
    int size;                    /* texels per side */
    float view_projection[16];   /* world -> the map's clip space (orthographic, column-major) */
    int particles;               /* particles drawn into it (0: the map is all 1) */
} sbfx_shadow_map;

/* Renders the map for light travelling along `direction` (world space, any length above 0)
 * from the particles as they are now (call it after sbfx_update, before the host draws what
 * it shades). One pass; none when no particle casts a shadow (the map is then cleared to 1
 * once). The host's GL state is left as it was. SBFX_ERR_INVALID_ARGUMENT, with nothing
 * changed and *out untouched, for a NULL pointer, a zero-length or non-finite direction, or a
 * module made without a map. */
SBFX_API sbfx_result sbfx_render_shadow_map(sbfx *fx, const float direction[3], sbfx_shadow_map *out);

/* What a scene file says to its host (sbfx-play's test scene): render.host_lights and
 * render.host_shadows, and the daylight of the ground it stands on: the first directional
 * light (the sun or moon), `ambient` and the `sky` colour, all linear RGB in the scene's units. */
typedef struct sbfx_scene_host {
    bool host_lights;            /* light the host's scene with the fire's emitted lights */
    bool host_shadows;           /* shadow it by sbfx_render_shadow_map from the sun below */
    bool has_sky;                /* the file gives `sky`: the fields below describe the host's
                                    daylight; false: the host keeps its own */
    float sky[3];                /* sky and fog colour */
    float ambient[3];            /* the scene's ambient */
    bool has_sun;                /* the scene has a directional light */
    float sun_direction[3];      /* the direction its light travels (unit) */
    float sun_color[3];
    float exposure;              /* render.exposure (1 when not given): the host's light is
                                    scaled as the particles' is */
} sbfx_scene_host;

/* Fills *out from the scene (all false and zero for NULL); returns out->has_sky. */
SBFX_API bool sbfx_scene_host_get(const sbfx_scene *scene, sbfx_scene_host *out);

/* Helpers for hosts: column-major OpenGL matrices.
 * sbfx_perspective: symmetric frustum; far_z = INFINITY gives the infinite-far matrix
 * (projection[10] = -1, [14] = -2 near_z). sbfx_frustum: glFrustum's off-axis frustum (video
 * walls, simulator channels), far_z = INFINITY allowed. sbfx_reverse_z: rewrites the depth row
 * of either for reversed-Z with glClipControlEXT(GL_LOWER_LEFT, GL_ZERO_TO_ONE) — near -> 1,
 * far -> 0, far_z = INFINITY: 0 at infinity (projection[10] = 0, [14] = near_z) — to be used
 * with a float depth buffer cleared to 0, glDepthFunc(GL_GREATER) and
 * frame.clip_depth_mode = SBFX_CLIP_DEPTH_ZERO_TO_ONE. */
SBFX_API void sbfx_perspective(float out[16], float fov_y_radians, float aspect, float near_z,
                               float far_z);
SBFX_API void sbfx_frustum(float out[16], float left, float right, float bottom, float top,
                           float near_z, float far_z);
SBFX_API void sbfx_reverse_z(float projection[16], float near_z, float far_z);
SBFX_API void sbfx_look_at(float out[16], const float eye[3], const float target[3],
                           const float up[3]);

#ifdef __cplusplus
}
#endif
#endif
