/* Private to sbfx and its own tools/tests (probe, GL tests, bench). Not installed. */
#ifndef SBFX_INTERNAL_H
#define SBFX_INTERNAL_H

#include <GLES3/gl3.h>
#include <stdarg.h>
#include "sbfx.h"
#include "base/base.h"
#include "base/hash.h"
#include "base/rng.h"
#include "tables/tables.h"

/* Lookup tables (reference.h has their coordinates; docs/accuracy-and-benchmarks.md the sizes'
 * measured error). Float32 entries fetched with texelFetch and interpolated in the shader:
 * half floats would spend half the error budget on rounding (2^-11), float textures are not
 * filterable in core ES 3.0, and the filter's fixed-point weights would add their own error. */
#define SBFX_BLACKBODY_SIZE 512           /* RGBA32F entries, uniform in 1/T */
#define SBFX_PHASE_SIZE 256               /* R32F entries per medium, warped cos θ */
#define SBFX_DEFAULT_MAX_KELVIN 6000.0    /* blackbody_max_kelvin: luminance 1 at this T */
#define SBFX_DEFAULT_WHITE_LUMINANCE 1e4  /* desc.white_luminance, cd/m^2 */
#define SBFX_BLACKBODY_MIN_KELVIN 500.0   /* cooler fire: under 1e-19 of the unit's light */
#define SBFX_BLACKBODY_MARGIN 1.25        /* the range reaches this factor beyond the scene's */
#define SBFX_TABLE_TOLERANCE 1e-3         /* docs/design.md §4: relative to the double function */
#define SBFX_TABLE_GPU_ALLOWANCE 1e-4     /* of it, what the shader's float arithmetic may use
                                             (llvmpipe: 6e-6 black body, 5e-7 phase) */

/* The tables made at load, with the CPU copy of what was uploaded (tests mirror the GPU with
 * it) and what was decided: a medium whose table would miss the tolerance is evaluated
 * analytically instead (logged once). */
typedef struct sbfx_tables {
    float *blackbody;              /* SBFX_BLACKBODY_SIZE x 4; NULL without fire */
    double blackbody_lo, blackbody_hi;  /* kelvin, from the scene's fire (tables.c) */
    double blackbody_norm;         /* 1 / Y(desc.blackbody_max_kelvin) */
    double blackbody_error;        /* the CPU lookup's largest error over the range */
    bool blackbody_missed;         /* the table misses the tolerance: always analytic */
    bool blackbody_analytic;       /* the current level's analytic_blackbody, or the table missed */
    float *phase;                  /* SBFX_MEDIUM_COUNT rows of SBFX_PHASE_SIZE; row m: medium m */
    double phase_error[SBFX_MEDIUM_COUNT];
    bool phase_table[SBFX_MEDIUM_COUNT];    /* the medium samples its row */
    bool phase_analytic[SBFX_MEDIUM_COUNT]; /* the medium evaluates the function per fragment */
    bool phase_missed[SBFX_MEDIUM_COUNT];   /* its table misses the tolerance: always analytic */
} sbfx_tables;

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

/* A particle as the renderer sees it: view space, already validated. */
typedef struct sbfx_view_particle {
    float center[3];  /* view space, center[2] < 0 in front of the camera */
    float radius;
    float detail[3];  /* detail window origin (u, v) and time offset */
    float intensity;  /* density scale in [0,1]; fire also cools as it falls */
    sbfx_medium medium;
    float previous_center[3]; /* view-space centre one frame ago, as seen then (velocity blur) */
} sbfx_view_particle;

/* True when every input of the particle is finite and the radius is positive. */
bool sbfx_view_particle_valid(const sbfx_view_particle *p);

/* ---- embedded shaders (generated from shaders_es/ at build time) ---- */
const char *sbfx_shader_source(const char *name);

/* ---- test / tool entry points ---- */
/* Mutable media parameters (index by sbfx_medium). */
sbfx_medium_params *sbfx_media(sbfx *fx);
/* Sets the world-space direction the light travels in, its irradiance and the ambient term. */
void sbfx_set_light(sbfx *fx, const float direction[3], const float color[3], const float ambient[3]);
/* Renders the given view-space particles (sorted back to front here) through the normal passes:
 * depth downsample, particle passes, composite. Invalid particles are skipped and counted. */
sbfx_result sbfx_render_view_particles(sbfx *fx, const sbfx_frame *frame,
                                       const sbfx_view_particle *particles, int count);
/* Reads back the particle target of the last render as float RGBA (premultiplied radiance,
 * transmittance in alpha). w*h floats*4 must fit in capacity (floats). */
sbfx_result sbfx_read_particle_target(sbfx *fx, float *rgba, size_t capacity, int *w, int *h);
/* The black body at kelvin and a medium's phase function at cos_theta (its g is the one the
 * tables were made for) as the particle shader computes them: particle.frag's own functions
 * (table or analytic, whatever that medium's program uses) in a 1x1 pass. */
sbfx_result sbfx_fetch_luts(sbfx *fx, sbfx_medium medium, float kelvin, float cos_theta, float rgb[3],
                            float *phase);
/* The tables of the loaded scene (sbfx_tables above). */
const sbfx_tables *sbfx_get_tables(const sbfx *fx);
/* The desc the module runs with, defaults filled in (tests, bench, CPU reference). */
const sbfx_desc *sbfx_get_desc(const sbfx *fx);
/* Remakes the tables, shader programs and targets from the current media (sbfx_media): for
 * tests and tools that change media after sbfx_create. Allocates; not for the frame loop. */
sbfx_result sbfx_reload(sbfx *fx);

/* What the renderer would draw for this view: live particles in view space (unsorted,
 * invalid ones skipped), as the last sbfx_render saw them. Returns the count; *out is owned
 * by the module and valid until the next render or update. */
int sbfx_frame_particles(sbfx *fx, const float view[16], const sbfx_view_particle **out);
/* The frame's lights in view space, as the particle shader gets them: w = 0 direction of
 * travel, w = 1 position; colours already faded for light flashes. Returns the count. */
typedef struct sbfx_view_light { float vector[4]; float color[3]; } sbfx_view_light;
int sbfx_frame_lights(const sbfx *fx, const float view[16], sbfx_view_light *out, int capacity);
/* Replaces the scene's lights: world space, w = 0 direction of travel, w = 1 position (no
 * orbit); count <= 8. */
void sbfx_set_lights(sbfx *fx, const sbfx_view_light *lights, int count, const float ambient[3]);
void sbfx_frame_ambient(const sbfx *fx, float ambient[3]);
/* The detail time coordinate the shader samples at (in detail-volume loops). */
double sbfx_detail_time(const sbfx *fx);

/* The window depth a host's depth buffer holds for a view distance under the frame's projection
 * and clip depth mode (the clear value for INFINITY or beyond a finite far plane), and the view
 * distance sbfx reads from a window depth (INFINITY for the clear value): what the shaders
 * compute, in double (src/render/projection.c). A malformed projection gives the clear value / INFINITY. */
float sbfx_window_depth(const sbfx_frame *frame, double distance);
double sbfx_window_distance(const sbfx_frame *frame, float window);

/* Saves and restores the host's GL state exactly as sbfx_render does for a frame with or
 * without live particles, nothing in between (the bench's cost of the host contract). Returns
 * the glGet / glIs calls it made. */
int sbfx_host_state_roundtrip(sbfx *fx, bool particles);

/* sbfx_render_shadow_map for the given particles (world-space centres, not the pool's). */
sbfx_result sbfx_render_shadow_particles(sbfx *fx, const float direction[3], const sbfx_view_particle *world,
                                         int count, sbfx_shadow_map *out);
/* Reads the shadow map back as float RGBA, size * size * 4 floats (row 0 first). */
sbfx_result sbfx_read_shadow_map(sbfx *fx, float *values, size_t capacity);
/* Whether the frame's fire lights its dust and smoke (the CPU reference's fire_light). */
bool sbfx_fire_lit(const sbfx *fx);

/* Hash of the live particles' simulation state (determinism tests). */
uint64_t sbfx_state_hash(const sbfx *fx);

#endif
