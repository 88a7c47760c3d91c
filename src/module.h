/* The module's private state, shared by its .c files only. */
#ifndef SBFX_MODULE_H
#define SBFX_MODULE_H

#include "internal.h"

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
    GLint near, far, projection, target_size, pixel, tau, soft_scale;
    GLint depth, detail, detail_window, detail_strength, time;
    GLint phase_lut, phase_lut_size, g, albedo_color, light_count, light_vector, light_color, ambient;
    GLint blackbody, blackbody_size, max_kelvin, temperature, emission_scale, cmf_rgb, cmf_band;
} sbfx_program;

/* Uniform locations of the full-screen passes, looked up once at load. */
typedef struct sbfx_pass_uniforms {
    GLint scene_depth, divisor, full_size, depth_params, far;         /* depth downsample */
    GLint particles, low_depth, low_size, depth_threshold;            /* composite */
} sbfx_pass_uniforms;

typedef struct sbfx_gl {
    sbfx_pass_uniforms depth_u, composite_u;
    GLuint fullscreen_vao, particle_vao, instance_buffer;
    GLuint depth_program, composite_program, lut_program;
    sbfx_program particle[SBFX_MEDIUM_COUNT];
    GLuint blackbody_texture, phase_texture, detail_texture;
    /* targets, (re)made when the output size changes */
    GLuint target_texture, target_fbo, low_depth_texture, low_depth_fbo;
    GLuint probe_texture, probe_fbo;
    int out_width, out_height, low_width, low_height;
    GLenum target_internal, target_type;
    size_t target_bytes;
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

typedef struct sbfx_scene_light { /* scene light, as the module keeps it */
    bool point;
    float vector[3], color[3];
} sbfx_scene_light;

struct sbfx {
    sbfx_desc desc;
    char last_error[512];
    bool loaded;                 /* sbfx_create finished: heap allocations now count */
    uint64_t heap_allocs_after_load;
    bool warned_format;

    sbfx_medium_params media[SBFX_MEDIUM_COUNT];
    bool uses_medium[SBFX_MEDIUM_COUNT];
    int light_count;
    sbfx_scene_light lights[SBFX_SHADER_LIGHTS];
    float ambient[3];
    sbfx_scheduled schedule[SBFX_MAX_SCHEDULE]; /* sorted by time; [next_scheduled, count) pending */
    int schedule_count, next_scheduled;
    sbfx_live_flash flashes[SBFX_MAX_LIVE_FLASHES];
    int flash_count;
    float max_kelvin;

    sbfx_effect effects[SBFX_MAX_EFFECTS];
    int effect_count;

    sbfx_pool pool;
    double time, accumulator;
    uint64_t step_index;
    uint32_t trigger_count;
    int particles_simulated;

    /* render scratch, sized max_particles at load */
    sbfx_view_particle *view;
    float *sort_keys;
    uint32_t *order, *order_tmp;
    float *instances;            /* 8 floats per particle */

    sbfx_gl gl;
    sbfx_counters counters;
    int detail_ring_next;        /* next slice sbfx_detail_push_slice writes */
    /* analytic black body: per band, sRGB weight (matrix x CMF x trapezoid x norm) and the
     * band's wavelength in micrometres; loaded once with the program */
    int cmf_bands;
    float *cmf_rgb, *cmf_band;
    float *detail_scratch;       /* one R32F slice, only with SBFX_DETAIL_R32F */
};

/* sim.c */
sbfx_result sbfx_pool_create(sbfx *fx, int capacity);
void sbfx_pool_destroy(sbfx *fx);
sbfx_result sbfx_spawn_effect(sbfx *fx, const sbfx_effect *effect, const float position[3]);
void sbfx_simulate_step(sbfx *fx, float step);

/* sbfx.c */
sbfx_result sbfx_fire(sbfx *fx, int effect, const float position[3]);

/* effects.c */
void sbfx_default_media(sbfx_medium_params media[SBFX_MEDIUM_COUNT]);
void sbfx_builtin_explosion(sbfx_effect *out);

/* gl_util.c */
bool sbfx_gl_check(sbfx *fx, const char *what);
GLuint sbfx_program_build(sbfx *fx, const char *vert_name, const char *frag_name,
                          const char *defines);
void sbfx_texture_params(GLenum target, GLenum filter, GLenum wrap);
bool sbfx_has_extension(const char *name);

/* luts.c */
sbfx_result sbfx_luts_create(sbfx *fx);
void sbfx_luts_destroy(sbfx *fx);

/* programs.c */
sbfx_result sbfx_programs_create(sbfx *fx);
void sbfx_programs_destroy(sbfx *fx);

/* targets.c */
sbfx_result sbfx_targets_ensure(sbfx *fx, int width, int height);
void sbfx_targets_destroy(sbfx *fx);

/* sort.c: back-to-front order of fx->view[0..count) by view distance into fx->order */
void sbfx_sort_back_to_front(sbfx *fx, int count);

/* render.c */
sbfx_result sbfx_render_particles(sbfx *fx, const sbfx_frame *frame, int count);
int sbfx_collect_view_particles(sbfx *fx, const float view[16]);

#endif
