/* Shader programs (gl/gl.h says what the room is for): the particle programs' uniforms, the
 * full-screen passes' uniforms, and the variants a quality level needs — one particle program
 * per medium for each (opacity, light per particle, analytic black body, analytic phase) as far
 * as the loaded media are affected by each (programs.c builds them, levels.c chooses). Fixed
 * arrays inside the module: a level used once costs nothing to switch back to. */
#ifndef SBFX_GL_PROGRAM_H
#define SBFX_GL_PROGRAM_H

#include <GLES3/gl3.h>
#include <stdbool.h>
#include <stddef.h>
#include "sbfx.h"

typedef struct sbfx_program {
    GLuint id;
    /* uniform locations used every frame */
    GLint near, projection, ray_map, pixel, octagon, tau, soft_scale, full_size, heat_strength;
    GLint depth, detail, detail_window, detail_strength, time;
    GLint phase_lut, phase_row, phase_warp, phase_shift, phase_analytic, albedo_color, light_count, light_vector, light_color;
    GLint ambient, blackbody, blackbody_map, temperature, emission_scale, cmf_rgb, cmf_band, probe;
    GLint smoke, smoke_size, smoke_variants, wrap, translucency, dampening, steps; /* LIGHTING_LIT */
} sbfx_program;

/* Uniform locations of the passes drawn over the screen's tiles, looked up once at load. */
typedef struct sbfx_pass_uniforms {
    GLint scene_depth, divisor, full_size, depth_model, near, closer; /* depth downsample */
    GLint particles, low_depth, low_size, depth_threshold;            /* composite */
    GLint scene_color, scene_known, distortion;                       /* composite: scene colour */
    GLint tone_curve;                                                 /* composite, tone map */
    GLint low_corners, particles_far, near_over_far;                  /* composite, nearest depth */
    GLint tile_size, tile_grid, tile_target;                          /* tiles.vert (render/tiles.h) */
    GLint refined, contrast;                                          /* mixed resolution (render/refine.c) */
    GLint inv_divisor, low_texel, corners_texel, near_model, tone_filmic, tone_shoulder, full_texel; /* folded on the CPU (passes.c) */
    GLint epsilon;                                                    /* early termination (render/terminate.c) */
} sbfx_pass_uniforms;

typedef struct sbfx_variant_key {
    sbfx_opacity_mode opacity;
    bool lpp, abb, aph;        /* only where a loaded medium is affected by it */
} sbfx_variant_key;
#define SBFX_VARIANTS (SBFX_OPACITY_COUNT * 8)
typedef struct sbfx_variant {
    bool built;
    sbfx_program particle[SBFX_MEDIUM_COUNT];
} sbfx_variant;

/* programs.c */
/* A variant's place in the module's table (sbfx_gl.variants). */
int sbfx_variant_index(const sbfx_variant_key *k);
sbfx_result sbfx_programs_create(sbfx *fx);
/* The particle shader's defines for medium m under a variant (its opacity, lighting,
 * table/analytic choices). */
void sbfx_particle_defines(const sbfx *fx, const sbfx_variant_key *key, sbfx_medium m, char *out, size_t size);
/* Builds a variant's particle programs / an upsampling's composite (when not built yet). */
sbfx_result sbfx_variant_build(sbfx *fx, const sbfx_variant_key *key);
sbfx_result sbfx_composite_build(sbfx *fx, sbfx_upsample upsample);
/* Early termination's mark program (render/terminate.c), when not built yet. */
sbfx_result sbfx_stop_program_build(sbfx *fx);
/* Re-creates the instance buffer with room for the per-particle light (first use of lpp). */
sbfx_result sbfx_instances_reserve_light(sbfx *fx);
void sbfx_program_locate(sbfx_program *p);
/* The analytic black body's per-band constants (fire with tables.blackbody_analytic). */
void sbfx_program_load_cmf(const sbfx *fx, const sbfx_program *p);
void sbfx_programs_destroy(sbfx *fx);

#endif
