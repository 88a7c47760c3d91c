/* The module's private state, shared by its .c files only. */
#ifndef SBFX_MODULE_H
#define SBFX_MODULE_H

#include "internal.h"
#include "budget/governor.h"
#include "gl/gpu_timer.h"
#include "sim/lod.h"
#include "sim/fire_light.h"

#define SBFX_MAX_EFFECTS 16
#define SBFX_MAX_EMITTERS 8
#define SBFX_MAX_INSTANCES 64
#define SBFX_NAME_MAX 32

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

/* Particle pool, structure of arrays, sized once at load. Live particles are [0, alive). */
typedef struct sbfx_pool {
    int capacity, alive;
    float *pos;        /* 3 per particle, world space */
    float *vel;        /* 3 per particle */
    float *age, *life; /* age < 0: waiting for its emitter's delay */
    float *radius0, *radius1;
    float *intensity0, *intensity1, *fade_in;
    float *drag, *buoyancy;
    float *detail;     /* 3 per particle: window u, v, time offset */
    uint8_t *medium;
} sbfx_pool;

typedef struct sbfx_program {
    GLuint id;
    /* uniform locations used every frame */
    GLint near, projection, target_size, pixel, tau, soft_scale, full_size, heat_strength;
    GLint depth, detail, detail_window, detail_strength, time;
    GLint phase_lut, phase_row, phase_warp, phase_shift, g, albedo_color, light_count, light_vector, light_color;
    GLint ambient, blackbody, blackbody_map, temperature, emission_scale, cmf_rgb, cmf_band, probe;
    GLint smoke, smoke_size, smoke_variants, wrap, translucency, dampening, steps; /* LIGHTING_LIT */
} sbfx_program;

/* A framebuffer with up to SBFX_RT_MAX colour textures and an optional depth texture. */
#define SBFX_RT_MAX 3
typedef struct sbfx_rt_format {
    GLenum internal, format, type;
    int bytes;
} sbfx_rt_format;
extern const sbfx_rt_format sbfx_rt_rgba8, sbfx_rt_rgba16f, sbfx_rt_rgba32f, sbfx_rt_depth32f;

typedef struct sbfx_rt {
    GLuint framebuffer;
    GLuint texture[SBFX_RT_MAX];
    GLuint depth;
    int width, height;
    size_t bytes;
} sbfx_rt;

/* GL objects a module made, known by how they were made (a 64-bit hash of the shader names and
 * defines, or of a target's size, formats and filter): a module built to replace another
 * (sbfx_set_scene, reload.c) takes over those it would make the same way instead of making them
 * again. The donor lends them; if the new module fails, they go back to it. Deleting an object
 * that is lent or borrowed leaves it to the module that keeps it. */
typedef enum sbfx_object_kind { SBFX_OBJECT_PROGRAM = 1, SBFX_OBJECT_TARGET, SBFX_OBJECT_TEXTURE } sbfx_object_kind;
typedef enum sbfx_object_state { SBFX_OBJECT_OWN, SBFX_OBJECT_LENT, SBFX_OBJECT_BORROWED } sbfx_object_state;
typedef struct sbfx_object {
    uint8_t kind, state;
    GLuint id;          /* the program, the target's framebuffer, the texture */
    uint64_t key;
    sbfx_rt rt;         /* targets: the whole of it */
} sbfx_object;
#define SBFX_OBJECTS 256

/* Post-effect state: programs at load, targets with the output size. */
#define SBFX_POST_PROGRAMS 9
#define SBFX_POST_UNIFORMS 40
typedef struct sbfx_post_gl {
    GLuint velocity_program, tile_program, neighbor_program, blur_program;
    GLuint history_program, copy_program, dof_setup_program, dof_blur_program, dof_composite_program;
    const sbfx_rt_format *color_format, *velocity_format;
    bool encode_velocity;      /* RGBA8 velocity: stored as v / (2 max) + 0.5 */
    sbfx_rt frame[2];          /* full-res images between post passes */
    sbfx_rt history[2];        /* history blur ping-pong */
    int history_next;
    bool history_valid;
    sbfx_rt velocity, tile_rows, tiles, neighbors; /* tile_rows: tile max along rows only */
    sbfx_rt dof[2];            /* each: far field + near field, ping-pong of the separable blur */
    int width, height;
    double last_time;          /* simulation time of the previous render */
    bool have_previous;
    bool particles_drawn;      /* this frame drew particles (their velocities are valid) */
    GLuint host_depth, host_color; /* this frame's host textures: read through sbfx's samplers */
    double previous_view_projection[16];
    GLint locations[SBFX_POST_PROGRAMS][SBFX_POST_UNIFORMS]; /* post.c's uniform table */
} sbfx_post_gl;

/* What the scene's plan needs beyond the particle passes. */
typedef struct sbfx_plan {
    bool distortion;           /* heat medium: shimmer offsets */
    bool particle_velocity;    /* velocity blur: particles write their screen motion */
    bool motion_target;        /* velocity blur or depth of field: particles write premultiplied
                                  velocity and depth into attachment 2 */
    bool owns_scene;           /* any post effect: sbfx reads the scene colour and writes out */
    bool fire_light;           /* emitting fire and dust or smoke of the phase model: the fire's
                                  light in-scatters there (FIRE_LIGHT, emitted_lights.c) */
} sbfx_plan;

/* Uniform locations of the full-screen passes, looked up once at load. */
typedef struct sbfx_pass_uniforms {
    GLint scene_depth, divisor, full_size, depth_model, near;         /* depth downsample */
    GLint particles, low_depth, low_size, depth_threshold;            /* composite */
    GLint scene_color, scene_known, distortion;                       /* composite: scene colour */
    GLint tone_curve;                                                 /* composite, tone map */
    GLint low_corners, particles_far, near_over_far;                  /* composite, nearest depth */
} sbfx_pass_uniforms;

/* Run-time quality (quality.c). What a level needs on the GPU is kept per part, indexed
 * directly (no search, no eviction): the particle programs by (opacity, light per particle,
 * analytic black body, analytic phase) as far as the loaded media are affected by each; the
 * composite by upsampling; the targets by (divisor, format). Fixed arrays inside the module:
 * a level used once costs nothing to switch back to. */
typedef struct sbfx_variant_key {
    sbfx_opacity_mode opacity;
    bool lpp, abb, aph;        /* only where a loaded medium is affected by it */
} sbfx_variant_key;
#define SBFX_VARIANTS (SBFX_OPACITY_COUNT * 8)
typedef struct sbfx_variant {
    bool built;
    sbfx_program particle[SBFX_MEDIUM_COUNT];
} sbfx_variant;
#define SBFX_TARGET_SETS (4 * SBFX_FORMAT_COUNT)
typedef struct sbfx_target_set {
    sbfx_rt particles, low_depth, low_corners; /* low_corners: RGBA32F devices only (passes.c) */
    int low_width, low_height;
    GLenum target_type;
    sbfx_target_format format;  /* what was made (a fallback may replace the one asked for) */
} sbfx_target_set;
#define SBFX_LADDER_MAX 16

typedef struct sbfx_gl {
    sbfx_pass_uniforms depth_u, corners_u, composite_u;
    GLuint fullscreen_vao, particle_vao, instance_buffer;
    GLuint depth_program, corners_program, composite_program;
    GLuint lut_program;                      /* particle.frag's TABLE_PROBE (diagnostics.c)... */
    int lut_medium;                          /* ...for this medium's table/analytic choices */
    sbfx_program particle[SBFX_MEDIUM_COUNT];
    GLuint blackbody_texture, phase_texture, detail_texture;
    GLuint smoke_texture[SBFX_MEDIUM_COUNT]; /* 2D arrays, lit media only (tables.h layout) */
    GLuint depth_sampler, color_sampler;     /* how the host's depth and colour are read */
    /* targets, (re)made when the output size changes */
    sbfx_rt particles, low_depth, low_corners;
    GLuint probe_texture, probe_fbo;
    int out_width, out_height, low_width, low_height;
    GLenum target_type;
    sbfx_post_gl post;
    /* quality caches (the fields above hold the current level's copies) */
    sbfx_variant variants[SBFX_VARIANTS];
    GLuint composites[SBFX_UPSAMPLE_COUNT];
    sbfx_pass_uniforms composite_us[SBFX_UPSAMPLE_COUNT];
    sbfx_target_set targets[SBFX_TARGET_SETS];
    bool lut_blackbody_analytic, lut_phase_analytic; /* what lut_program was built with */
} sbfx_gl;

#define SBFX_MAX_SCHEDULE 128
#define SBFX_ANALYTIC_MAX_BANDS 96 /* MAX_BANDS in particle.frag */
#define SBFX_MAX_LIVE_FLASHES 8
#define SBFX_SHADER_LIGHTS 8 /* scene lights (<= 4) + live flashes share these slots */

typedef struct sbfx_scheduled {
    int effect;
    double time;
    float position[3];
} sbfx_scheduled;

typedef struct sbfx_live_flash {
    double start;
    float duration;
    float color[3], position[3];
} sbfx_live_flash;

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

/* The frame budget (budget.c): the ladder it walks, the governor, sbfx's GPU timer. */
typedef struct sbfx_budget {
    bool on;
    int count;                           /* ladder levels; [0] is the top */
    sbfx_quality ladder[SBFX_LADDER_MAX];
    governor gov;
    gpu_timer timer;                     /* timer.ok false: the host reports frame times */
    bool timing;                         /* a query begun this frame */
    bool warned;                         /* the timer's failure was logged */
    int level;                           /* the level rendered last */
} sbfx_budget;

/* GL errors pending when an entry point was called: the host's, read off at entry so that
 * sbfx's checks see only its own, and posted again at return where GL allows (gl_util.c). */
#define SBFX_HOST_ERRORS_MAX 8
typedef struct sbfx_host_errors {
    GLenum code[SBFX_HOST_ERRORS_MAX];
    int count;
    unsigned logged;             /* bit per kind already logged (once per module) */
} sbfx_host_errors;

/* The host's transmittance shadow map (shadow.c): made at load only when asked for. */
typedef struct sbfx_shadow {
    int size;                  /* 0: none */
    sbfx_rt map;               /* one colour texture: RGBA16F, or RGBA8 where half floats do not render */
    GLuint program, vao, buffer;
    GLint u_matrix, u_depth;
    bool clear;                /* the map holds 1 everywhere (no particle since it was cleared) */
} sbfx_shadow;

struct sbfx {
    sbfx_desc desc;                      /* quality fields: the current level's */
    sbfx_quality top;                    /* the quality of the desc (and scene) at create */
    sbfx_quality current;
    sbfx_quality declared[SBFX_LADDER_MAX + 1]; /* made at load: the top and the ladders */
    int declared_count;
    sbfx_budget budget;
    char last_error[512];
    bool loaded;                 /* sbfx_create finished: heap allocations now count */
    uint64_t heap_allocs_after_load;
    bool warned_format;
    sbfx_host_errors host_errors; /* GL errors the host left pending (gl_util.c) */
    unsigned context_parts;       /* SBFX_GL_SAVE_DESKTOP / _COMPAT on desktop OpenGL (context.c) */
    bool mediump_as_highp;        /* a software rasteriser: shaders' mediump compiled as highp (context.c) */
    bool mediump_native;          /* SBFX_MEDIUMP=native: mediump as written, also there (precision.c) */
    int filter_bits;              /* SBFX_FILTER_BITS=N: filtered fetches by hand, N-bit weights; 0: off */
    bool warned_polygon_mode;

    sbfx_medium_params media[SBFX_MEDIUM_COUNT];
    bool uses_medium[SBFX_MEDIUM_COUNT];
    sbfx_post_params post;
    sbfx_plan plan;
    int light_count;
    int light_slots;  /* lights the phase shaders loop over: scene lights + one effect's flashes */
    sbfx_scene_light lights[SBFX_SHADER_LIGHTS];
    float ambient[3];
    sbfx_scheduled schedule[SBFX_MAX_SCHEDULE]; /* sorted by time; [next_scheduled, count) pending */
    int schedule_count, next_scheduled;
    sbfx_live_flash flashes[SBFX_MAX_LIVE_FLASHES];
    int flash_count;
    sbfx_tables tables;
    sbfx_tone_curve tone_curve;  /* the composite's (src/tables/tonemap.c), made at load */

    sbfx_effect effects[SBFX_MAX_EFFECTS];
    int effect_count;

    sbfx_pool pool;
    double time, accumulator;    /* time: seconds since create (whole steps); the clock
                                    is desc.start_time + time (sbfx_time) */
    uint64_t step_index;
    uint32_t trigger_count;
    int particles_simulated;

    /* render scratch, sized max_particles at load */
    sbfx_view_particle *view;
    float *sort_keys;
    uint32_t *order, *order_tmp;
    float *instances;            /* instance_floats per particle */
    int instance_floats;         /* 8, + 4 previous centre (velocity blur), + 4 light */
    int instance_previous;       /* float offset of the previous centre, 0 = none */
    int instance_light;          /* float offset of the per-particle light, 0 = none */
    int instance_fire;           /* float offset of the fire light (8 floats), 0 = none */

    sbfx_gl gl;
    sbfx_shadow shadow;
    sbfx_counters counters;
    int detail_ring_next;        /* next slice sbfx_detail_push_slice writes */
    float previous_view[16];     /* the last render's view and time (particle velocities) */
    double previous_render_time;
    bool have_previous_view;
    /* analytic black body: per band, sRGB weight (matrix x CMF x trapezoid x norm) and the
     * band's wavelength in micrometres; loaded once with the program */
    int cmf_bands;
    float *cmf_rgb, *cmf_band;
    float *detail_scratch;       /* one R32F slice, only with SBFX_DETAIL_R32F */
    /* reload.c: what the module made (lendable), the module it borrows from while a
     * sbfx_set_scene builds it, and the host's desc as given (the plan of every reload) */
    sbfx_object objects[SBFX_OBJECTS];
    int object_count;
    struct sbfx *donor;
    sbfx_desc host_desc;         /* scene and ladder pointers cleared: the names are below */
    char host_ladder[SBFX_LADDER_MAX][64];
    particle_lod lod;            /* level of detail (lodN levels): work memory made with the */
    void *lod_work;              /* first level that needs it (at load for declared ones) */
    /* fire as light (emitted_lights.c): work memory made at load when the scene has fire */
    sbfx_fire_particle *fire_particles;
    sbfx_fire_work *fire_work;
    double fire_detail[SBFX_FIRE_DETAIL_LEVELS]; /* the detail volume's quantiles (fire_light.h) */
    uint16_t *fire_slice_histograms; /* detail_frames x SBFX_FIRE_DETAIL_BINS: each slice's values, so
                                        the quantiles follow pushed slices; only where the scene's
                                        detail is live or a clip and fire emits (luts.c) */
    sbfx_fire_gathered emitted[SBFX_MAX_POINT_LIGHTS]; /* world space, after the last update */
    int emitted_count;
    bool emitted_current;        /* emitted[] gathered since the last sbfx_update */
    sbfx_fire_gathered frame_fire[SBFX_MAX_POINT_LIGHTS]; /* view space, the frame rendered */
    int frame_fire_count;
};

/* projection.c: what a frame's projection says (docs/design.md §5). View distance from window depth d:
 * p14 / (scale (d - window_far) + offset); d = window_far (the clear value) is no surface. */
typedef struct sbfx_depth_model {
    float projection[4];     /* p0, p5, p8, p9 */
    double near, far;        /* view distances of the planes; far = INFINITY without one */
    double scale, window_far, offset, p14;
    float ndc[2];            /* ndc_z = ndc[0] * d + ndc[1] (velocity reprojection) */
    bool reversed;           /* near -> larger depth */
} sbfx_depth_model;
bool sbfx_depth_model_from(sbfx *fx, const sbfx_frame *f, sbfx_depth_model *out);
/* The shaders' vec4 u_depth_model: scale, window_far, offset, p14. */
void sbfx_depth_model_uniform(const sbfx_depth_model *m, float out[4]);

/* gl_state.c: the host's GL state around every entry point (docs/design.md §5) */
#define SBFX_GL_MAX_UNITS 8
#define SBFX_GL_PIXEL_STORE 6
enum {
    SBFX_GL_SAVE_PASS = 1 << 0,    /* draw framebuffer, viewport, blend enable/functions/equations,
                                      depth test/function/mask, stencil, cull and scissor tests,
                                      colour mask, rasterizer discard; and the objects below */
    SBFX_GL_SAVE_OBJECTS = 1 << 1, /* program, vertex array, ARRAY_BUFFER */
    SBFX_GL_SAVE_UNPACK = 1 << 2,  /* PIXEL_UNPACK_BUFFER and the unpack pixel store */
    SBFX_GL_SAVE_PACK = 1 << 3,    /* read framebuffer, PIXEL_PACK_BUFFER and the pack pixel store */
    /* with SBFX_GL_SAVE_PASS on desktop OpenGL (sbfx.context_parts, context.c): what changes
     * sbfx's drawing there and not on ES — the depth range (it clamps gl_FragDepth), polygon
     * mode, colour logic op, depth clamp, clip distances 0-7, polygon smooth; and the
     * compatibility profile's alpha test */
    SBFX_GL_SAVE_DESKTOP = 1 << 4,
    SBFX_GL_SAVE_COMPAT = 1 << 5,
};
/* Bit u: sbfx binds that target on texture unit u (the active texture and each such unit's
 * sampler binding are saved with them). Textures are created on unit 0. */
typedef struct sbfx_gl_units {
    uint32_t tex_2d, tex_3d, tex_array;
} sbfx_gl_units;
typedef struct sbfx_gl_state {
    unsigned parts;
    sbfx_gl_units units;
    int queries;                       /* glGet* / glIs* calls made for this block */
    GLint program, vertex_array, array_buffer;
    GLint draw_framebuffer, read_framebuffer, viewport[4];
    GLint blend_func[4], blend_equation[2], depth_func;
    GLboolean blend, depth_test, depth_mask, stencil_test, cull_face, scissor_test, rasterizer_discard;
    GLboolean color_mask[4];
    GLint unpack_buffer, unpack[SBFX_GL_PIXEL_STORE], pack_buffer, pack[SBFX_GL_PIXEL_STORE];
    GLint active_texture;
    GLint texture_2d[SBFX_GL_MAX_UNITS], texture_3d[SBFX_GL_MAX_UNITS], texture_array[SBFX_GL_MAX_UNITS];
    GLint sampler[SBFX_GL_MAX_UNITS];
    GLint polygon_mode[2];
    GLfloat depth_range[2];
    GLboolean logic_op, depth_clamp, clip_distance[8], polygon_smooth, alpha_test;
    bool polygon_mode_set;             /* sbfx set GL_FILL and puts the host's mode back */
    bool polygon_mode_unfixed;         /* not GL_FILL, and glPolygonMode out of reach */
} sbfx_gl_state;
/* Saves the parts (and units) and sets what every sbfx pass or transfer assumes. */
void sbfx_gl_state_save(sbfx_gl_state *s, unsigned parts, const sbfx_gl_units *units);
/* Puts everything saved back; returns the number of queries the block made. */
int sbfx_gl_state_restore(sbfx_gl_state *s);
/* Binds texture and sampler (0: the texture's own parameters) on a unit. */
void sbfx_bind_texture(GLuint unit, GLenum target, GLuint texture, GLuint sampler);
sbfx_result sbfx_samplers_create(sbfx *fx);
void sbfx_samplers_destroy(sbfx *fx);

/* sim.c */
sbfx_result sbfx_pool_create(sbfx *fx, int capacity);
void sbfx_pool_destroy(sbfx *fx);
sbfx_result sbfx_spawn_effect(sbfx *fx, const sbfx_effect *effect, const float position[3]);
void sbfx_simulate_step(sbfx *fx, float step);

/* post.c */
void sbfx_default_post(sbfx_post_params *post);
/* The texture units the post chain binds (gl_state.c saves them). */
sbfx_gl_units sbfx_post_units(const sbfx *fx);
bool sbfx_post_owns_scene(const sbfx *fx);
sbfx_result sbfx_post_programs_create(sbfx *fx);
void sbfx_post_destroy(sbfx *fx);
sbfx_result sbfx_post_targets_ensure(sbfx *fx, int width, int height);
sbfx_result sbfx_post_run(sbfx *fx, const sbfx_frame *frame, const sbfx_depth_model *depth, GLuint source);
GLuint sbfx_post_composite_target(const sbfx *fx, const sbfx_frame *f);
GLuint sbfx_post_composite_texture(const sbfx *fx);

/* sbfx.c */
sbfx_result sbfx_fire(sbfx *fx, int effect, const float position[3]);
/* Load in two steps, shared by sbfx_create and sbfx_set_scene: plan (the desc with its defaults
 * and the scene's settings, checked; the declared levels) and build (the scene adopted, the pool,
 * the GL objects: borrowed from fx->donor where it has them). */
sbfx_result sbfx_module_build(sbfx *fx, const sbfx_desc *desc);
/* Everything a module holds but its own allocation (GL objects it lent are left alone). */
void sbfx_module_release(sbfx *fx);

/* reload.c */
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

/* The clock's phase in a cycle of |period| seconds, in [0, 1), reduced in double precision
 * (docs/design.md §7): what every periodic value starts from. */
double sbfx_clock_phase(const sbfx *fx, double period);
#define SBFX_MAX_START_TIME 1e10
#define SBFX_DETAIL_LOOP_SECONDS 4.0 /* the detail animation's loop */

/* lights.c: moves orbiting point lights to their place on the clock */
void sbfx_orbit_lights(sbfx *fx);
int sbfx_light_slots_of_scene(const sbfx *fx);
void sbfx_light_slots_reserve(sbfx *fx, int count);

/* effects.c */
void sbfx_default_media(sbfx_medium_params media[SBFX_MEDIUM_COUNT]);
void sbfx_builtin_explosion(sbfx_effect *out);

/* context.c: OpenGL ES 3.0+, or desktop OpenGL that runs GLSL ES 3.00 (issue 18) */
sbfx_result sbfx_context_check(sbfx *fx);
/* precision.c: the diagnostics SBFX_MEDIUMP and SBFX_FILTER_BITS, read once by sbfx_create */
sbfx_result sbfx_precision_from_env(sbfx *fx);
const char *sbfx_filter_library(void);
int sbfx_context_version(bool *desktop); /* major * 10 + minor of the current context */
bool sbfx_context_desktop(void);

/* gl_util.c */
bool sbfx_gl_check(sbfx *fx, const char *what);
/* Around the GL work of a public entry point: enter reads off the errors the host left
 * pending; leave, after sbfx's own errors were checked, posts them again (src/sbfx.h, "GL errors
 * the host left pending"). */
void sbfx_gl_enter(sbfx *fx);
void sbfx_gl_leave(sbfx *fx, const char *entry);
GLuint sbfx_program_build(sbfx *fx, const char *vert_name, const char *frag_name,
                          const char *defines);
void sbfx_texture_params(GLenum target, GLenum filter, GLenum wrap);
GLuint sbfx_texture_create(sbfx *fx, GLenum target, GLenum filter, GLenum wrap);
bool sbfx_has_extension(const char *name);

/* luts.c */
sbfx_result sbfx_luts_create(sbfx *fx);
/* The analytic black body's per-band constants (when a quality level that uses it is chosen later). */
sbfx_result sbfx_blackbody_constants_load(sbfx *fx);
void sbfx_luts_destroy(sbfx *fx);

/* tables.c: the black-body and phase tables of the loaded scene (sbfx_tables). The textures
 * exist when a declared level samples them; a later first use uploads them from the CPU copy. */
sbfx_result sbfx_tables_upload_blackbody(sbfx *fx);
sbfx_result sbfx_tables_upload_phase(sbfx *fx);
#define SBFX_UNIT_PHASE 2
#define SBFX_UNIT_BLACKBODY 3
bool sbfx_medium_uses_phase(const sbfx *fx, sbfx_medium m);
sbfx_result sbfx_tables_create(sbfx *fx, const sbfx_cmf *cmf);
void sbfx_tables_destroy(sbfx *fx);
/* Binds the tables to their units and sets a particle program's table uniforms for medium m. */
void sbfx_tables_bind(const sbfx *fx, const sbfx_program *p, sbfx_medium m);

/* programs.c */
sbfx_result sbfx_programs_create(sbfx *fx);
/* The particle shader's defines for medium m under a variant (its opacity, lighting,
 * table/analytic choices). */
void sbfx_particle_defines(const sbfx *fx, const sbfx_variant_key *key, sbfx_medium m, char *out, size_t size);
/* Builds a variant's particle programs / an upsampling's composite (when not built yet). */
sbfx_result sbfx_variant_build(sbfx *fx, const sbfx_variant_key *key);
sbfx_result sbfx_composite_build(sbfx *fx, sbfx_upsample upsample);
/* The level of detail's work memory (first lodN level). */
sbfx_result sbfx_lod_create(sbfx *fx);
/* Re-creates the instance buffer with room for the per-particle light (first use of lpp). */
sbfx_result sbfx_instances_reserve_light(sbfx *fx);
void sbfx_program_locate(sbfx_program *p);
/* The analytic black body's per-band constants (fire with tables.blackbody_analytic). */
void sbfx_program_load_cmf(const sbfx *fx, const sbfx_program *p);
void sbfx_programs_destroy(sbfx *fx);

/* rt.c */
bool sbfx_rt_create(sbfx *fx, sbfx_rt *rt, int w, int h, const sbfx_rt_format *const colors[SBFX_RT_MAX],
                    const sbfx_rt_format *depth, GLenum filter);
void sbfx_rt_destroy(sbfx *fx, sbfx_rt *rt);
void sbfx_rt_bind(const sbfx_rt *rt);
bool sbfx_half_float_renderable(void);
bool sbfx_float32_blendable(void); /* RGBA32F colour-renderable and blendable */
bool sbfx_float32_renderable(void); /* RGBA32F colour-renderable (the low-res corners, passes.c) */

/* targets.c: the current level's targets at the output size (on a size change, those of
 * every declared level: a budget's switch never creates one) */
sbfx_result sbfx_targets_ensure(sbfx *fx, int width, int height);
void sbfx_targets_destroy(sbfx *fx);

/* quality.c */
sbfx_quality sbfx_quality_from_desc(const sbfx_desc *d);
/* Fills zero fields with the defaults; false (err says why) for values out of range. */
bool sbfx_quality_resolve(sbfx_quality *q, char *err, size_t size);
bool sbfx_quality_equal(const sbfx_quality *a, const sbfx_quality *b);
sbfx_variant_key sbfx_variant_key_of(const sbfx *fx, const sbfx_quality *q);
int sbfx_variant_index(const sbfx_variant_key *k);
int sbfx_target_index(int divisor, sbfx_target_format format);
/* What a level uses of the loaded scene's tables and instance data. */
bool sbfx_quality_uses_blackbody_table(const sbfx *fx, const sbfx_quality *q);
bool sbfx_quality_uses_blackbody_analytic(const sbfx *fx, const sbfx_quality *q);
bool sbfx_quality_uses_phase_table(const sbfx *fx, const sbfx_quality *q);
bool sbfx_quality_uses_light_slot(const sbfx *fx, const sbfx_quality *q);
/* True when one of the levels made at load (fx->declared) does. */
bool sbfx_declared_any(const sbfx *fx, bool (*uses)(const sbfx *, const sbfx_quality *));
/* Load: builds what the declared levels need (inside load_gl's saved state). */
sbfx_result sbfx_quality_load(sbfx *fx);
/* Makes q the current level: builds what its first use needs (own saved state), then points
 * the module's current programs, composite and tables at it. No allocation once used. */
sbfx_result sbfx_quality_apply(sbfx *fx, const sbfx_quality *q);

/* budget.c: the declared levels and the frame budget's ladder */
/* At create, after the desc is validated: fx->top, fx->declared and the budget's ladder. */
sbfx_result sbfx_budget_init(sbfx *fx);
/* ladder_prior.c: the bench's costs of the ladder's levels (ladder_default.h) as g's prior */
void sbfx_ladder_prior(const sbfx_quality *ladder, int count, governor *g);
bool sbfx_budget_active(const sbfx *fx);
/* Around a frame's GL work: picks and applies the level before, measures after. */
sbfx_result sbfx_budget_begin_frame(sbfx *fx);
void sbfx_budget_end_frame(sbfx *fx);
/* The GPU timer (load_gl / destroy_gl). */
void sbfx_budget_gl_init(sbfx *fx);
void sbfx_budget_gl_destroy(sbfx *fx);



/* sort.c: back-to-front order of fx->view[0..count) by view distance into fx->order */
void sbfx_sort_back_to_front(sbfx *fx, int count);

/* passes.c: the frame's passes between one save and restore of the host's state */
sbfx_result sbfx_render_frame(sbfx *fx, const sbfx_frame *frame, const sbfx_depth_model *depth, int count);

/* render.c */
int sbfx_collect_view_particles(sbfx *fx, const float view[16]);
/* A live particle's radius and intensity at its age (what the renderer draws). */
void sbfx_pool_particle_shape(const sbfx_pool *p, int i, float *radius, float *intensity);

/* emitted_lights.c: fire gathered into point lights (src/sim/fire_light.h) */
sbfx_result sbfx_fire_lights_create(sbfx *fx);
void sbfx_fire_lights_destroy(sbfx *fx);
/* The fire model of the loaded scene (its black body: the module's table). */
sbfx_fire_model sbfx_fire_model_of(const sbfx *fx);
/* Whether the scene's fire lights its dust and smoke (the plan's fire_light). */
bool sbfx_fire_lights_media(const sbfx *fx);
/* The frame's fire (fx->view[0..count), view space) gathered into fx->frame_fire. */
void sbfx_fire_lights_of_frame(sbfx *fx, int count);

/* shadow.c: the host's transmittance shadow map (sbfx_render_shadow_map) */
sbfx_result sbfx_shadow_create(sbfx *fx);
void sbfx_shadow_destroy(sbfx *fx);

#endif
