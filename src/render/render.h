/* The render room (src/rooms.txt; docs/hacking.md): a frame's GPU work, the seed's figure 9.
 * Above the gl room (programs, targets, textures, the host contract) and the simulation (the
 * frame's particles).
 *
 * Exports to the rooms above:
 *   - the frame (frame.c): checked against its projection (projection.h), then between one save
 *     and restore of the host's state its passes — opaque depth and corners, the composite
 *     (passes.c), the particles front to back (particles.c), the post chain (post.h, post.c);
 *   - the frame's lights in view space (lights.c) and the entry points that replace them;
 *   - the host's transmittance shadow map (shadow.c, sbfx_render_shadow_map);
 *   - the screen tiles the particles can change (tiles.h, tiles.c): where the composite and the
 *     depth downsample run;
 *   - read-backs for tests and the probe (diagnostics.c): the particle target, the tables as
 *     the shader computes them.
 * Its state: sbfx_render_state (fx->render). A new pass is a function here that draw_frame
 * (frame.c) calls, with its program in the gl room and its targets' units in frame_units. */
#ifndef SBFX_RENDER_H
#define SBFX_RENDER_H

#include "gl/gl.h"
#include "render/post.h"
#include "render/projection.h"
#include "render/tiles.h"

#define UNIT_DEPTH 0   /* the particle passes' texture units (SBFX_UNIT_PHASE, _BLACKBODY: gl.h) */
#define UNIT_DETAIL 1
#define UNIT_SMOKE 4   /* a lit medium's smoke texture array */
#define SBFX_UNIT_REFINED 5 /* the composite's refined particles (mixed resolution, refine.c) */

/* The host's transmittance shadow map (shadow.c): made at load only when asked for. */
typedef struct sbfx_shadow {
    int size;                  /* 0: none */
    sbfx_rt map;               /* one colour texture: RGBA16F, or RGBA8 where half floats do not render */
    GLuint program, vao, buffer;
    GLint u_matrix, u_depth;
    bool clear;                /* the map holds 1 everywhere (no particle since it was cleared) */
} sbfx_shadow;

/* The read-back probe (diagnostics.c): particle.frag's TABLE_PROBE in a 1x1 RGBA32F target. */
typedef struct sbfx_probe {
    GLuint lut_program;                      /* particle.frag's TABLE_PROBE... */
    int lut_medium;                          /* ...for this medium's table/analytic choices */
    bool lut_blackbody_analytic, lut_phase_analytic; /* what lut_program was built with */
    GLuint probe_texture, probe_fbo;
} sbfx_probe;

/* The render room's state (fx->render). */
typedef struct sbfx_render_state {
    sbfx_post_gl post;
    sbfx_shadow shadow;
    sbfx_probe probe;
    sbfx_tiles tiles;
    bool warned_polygon_mode;
    bool front_to_back;      /* the frame's particles drawn nearest first (early termination) */
    int stops_marked;        /* early termination's marks drawn in the last frame (terminate.c) */
    int stops_skipped;       /* its checkpoints left out: no texel could reach epsilon there */
    float stop_depth[SBFX_TILE_GRID * SBFX_TILE_GRID]; /* terminate.c: optical depth per tile */
} sbfx_render_state;

/* Early termination's checkpoints of one draw of the particles (terminate.c): after the first
 * at[k] particles (nearest first), the texels whose transmittance is below epsilon[k] stop. */
#define SBFX_STOPS 2
typedef struct sbfx_stops {
    int count;
    int at[SBFX_STOPS];
    float epsilon[SBFX_STOPS];
} sbfx_stops;

/* The frame's projection as the passes' uniforms. */
typedef struct frame_params {
    float projection[4];   /* P[0], P[5], P[8], P[9] */
    float depth_model[4];  /* window depth -> distance (projection.c) */
    float near_model[3];   /* window depth -> near / distance: A (d - window_far) + B (sbfx_near_model_uniform) */
    float near;
    float particles_far;   /* view distance (along -z) beyond which no drawn particle reaches */
} frame_params;

/* The lights of a frame in view space: the scene's, then the live flashes. */
typedef struct frame_lights {
    int count;
    float vector[SBFX_SHADER_LIGHTS][4];
    float color[SBFX_SHADER_LIGHTS][3];
} frame_lights;

/* frame.c */
/* A frame's own counters (passes, draw calls, state queries, fire-lit particles, the
 * composite's tiles and pixels) start at 0. */
void sbfx_frame_counters_reset(sbfx *fx);
/* The frame's size, textures and projection usable (its depth model into *depth); else fails. */
bool sbfx_frame_check(sbfx *fx, const sbfx_frame *f, sbfx_depth_model *depth);
/* The frame's passes between one save and restore of the host's state. */
sbfx_result sbfx_render_frame(sbfx *fx, const sbfx_frame *frame, const sbfx_depth_model *depth, int count);
/* Renders the given view-space particles (sorted back to front here) through the normal passes:
 * depth downsample, particle passes, composite. Invalid particles are skipped and counted. */
sbfx_result sbfx_render_view_particles(sbfx *fx, const sbfx_frame *frame,
                                       const sbfx_view_particle *particles, int count);
/* Saves and restores the host's GL state exactly as sbfx_render does for a frame with or
 * without live particles, nothing in between (the bench's cost of the host contract). Returns
 * the glGet / glIs calls it made. */
int sbfx_host_state_roundtrip(sbfx *fx, bool particles);

/* tiles.c: the screen tiles the frame's particles can change (tiles.h) */
sbfx_result sbfx_tiles_create(sbfx *fx);
void sbfx_tiles_destroy(sbfx *fx);
/* Marks the tiles the first `count` particles of fx->sim->view can change, merges them into
 * rectangles (and, where sbfx owns the scene, the rest into the scene copy's) and uploads them;
 * sets the frame's composite_tiles and composite_pixels. */
void sbfx_tiles_plan(sbfx *fx, const sbfx_frame *f, const frame_params *fp, int count);
/* An idle frame's tiles (none marked; every one with full_screen): the rest of the screen for
 * the passes that draw there after it (post.c's depth of field). */
void sbfx_tiles_plan_idle(sbfx *fx, const sbfx_frame *f);
/* The frame has tiles to composite. */
bool sbfx_tiles_any(const sbfx *fx);
/* Draws the composite's rectangles (inside) or the scene copy's (!inside) with the current
 * program (u: its tiles.vert uniforms) into a target of width x height that holds the output
 * at 1 / divisor per axis (the low-res corners: one texel more). */
void sbfx_tiles_draw(sbfx *fx, const sbfx_pass_uniforms *u, bool inside, int width, int height, int divisor);

/* passes.c and particles.c: the passes of a frame with live particles */
/* The upsampling's uniforms (the composite's, mixed resolution's mark): the low-res target's
 * texel, 1 / divisor, the depths' model and threshold, the particles' reach. */
void sbfx_pass_upsample_uniforms(sbfx *fx, const sbfx_pass_uniforms *u, const frame_params *fp);
void sbfx_pass_depth(sbfx *fx, const sbfx_frame *f, const frame_params *fp);
/* The depth downsample into `target`, the output at 1 / divisor per axis, on the tiles. */
void sbfx_pass_depth_into(sbfx *fx, const sbfx_frame *f, const frame_params *fp, const sbfx_rt *target, int divisor);
bool sbfx_corners_used(const sbfx *fx);
void sbfx_pass_corners(sbfx *fx);
void sbfx_pass_particles(sbfx *fx, const sbfx_frame *f, const frame_params *fp, int count);
/* The particles' draws (instances already uploaded) into the bound width x height target, its
 * opaque depth bound on UNIT_DEPTH (particles.c; the refinement draws them again). */
void sbfx_draw_particles(sbfx *fx, const sbfx_frame *f, const frame_params *fp, int count, int width, int height,
                         const sbfx_stops *stops, GLuint depth_texture);
/* The particle drawn i-th of count: the sort's order, back to front, or reversed, nearest
 * first, where the frame terminates early (particles.c and terminate.c both walk it). */
static inline const sbfx_view_particle *sbfx_drawn_particle(const sbfx *fx, int count, int i)
{
    return &fx->sim->view[fx->sim->order[fx->render->front_to_back ? count - 1 - i : i]];
}

/* terminate.c: early termination (the scene's render.early_termination) */
bool sbfx_terminate_used(const sbfx *fx);
/* tiles.c: the tiles a particle can change, columns box[0]..box[2], rows box[1]..box[3] (its
 * region's bounding box, the grid of the frame's plan); false for none. */
bool sbfx_tiles_box(const sbfx *fx, const frame_params *fp, const sbfx_view_particle *v, int box[4]);
/* The frame's checkpoints and their epsilons (none where unused), from the instances written. */
void sbfx_terminate_plan(sbfx *fx, const frame_lights *lights, const frame_params *fp, int count, sbfx_stops *out);
void sbfx_terminate_begin(sbfx *fx);
void sbfx_terminate_mark(sbfx *fx, float epsilon, GLuint depth_texture);
void sbfx_terminate_end(void);
/* refine.c: mixed resolution, the particles again at full resolution where the coarse target
 * fails (after sbfx_pass_particles, before the composite) */
bool sbfx_refine_used(const sbfx *fx);
void sbfx_pass_refine(sbfx *fx, const sbfx_frame *f, const frame_params *fp, int count);
void sbfx_pass_composite(sbfx *fx, const sbfx_frame *f, const frame_params *fp);

/* lights.c */
void sbfx_gather_lights(const sbfx *fx, const float view[16], frame_lights *out);
/* The frame's lights in view space, as the particle shader gets them: w = 0 direction of
 * travel, w = 1 position; colours already faded for light flashes. Returns the count. */
typedef struct sbfx_view_light { float vector[4]; float color[3]; } sbfx_view_light;
int sbfx_frame_lights(const sbfx *fx, const float view[16], sbfx_view_light *out, int capacity);
void sbfx_frame_ambient(const sbfx *fx, float ambient[3]);
/* Sets the world-space direction the light travels in, its irradiance and the ambient term. */
void sbfx_set_light(sbfx *fx, const float direction[3], const float color[3], const float ambient[3]);
/* Replaces the scene's lights: world space, w = 0 direction of travel, w = 1 position (no
 * orbit); count <= 8. */
void sbfx_set_lights(sbfx *fx, const sbfx_view_light *lights, int count, const float ambient[3]);

/* shadow.c: the host's transmittance shadow map (sbfx_render_shadow_map) */
sbfx_result sbfx_shadow_create(sbfx *fx);
void sbfx_shadow_destroy(sbfx *fx);
/* sbfx_render_shadow_map for the given particles (world-space centres, not the pool's). */
sbfx_result sbfx_render_shadow_particles(sbfx *fx, const float direction[3], const sbfx_view_particle *world,
                                         int count, sbfx_shadow_map *out);
/* Reads the shadow map back as float RGBA, size * size * 4 floats (row 0 first). */
sbfx_result sbfx_read_shadow_map(sbfx *fx, float *values, size_t capacity);

/* diagnostics.c */
/* Reads back the particle target of the last render as float RGBA (premultiplied radiance,
 * transmittance in alpha). w*h floats*4 must fit in capacity (floats). */
sbfx_result sbfx_read_particle_target(sbfx *fx, float *rgba, size_t capacity, int *w, int *h);
/* Mixed resolution: reads back the refine target of the last render (output size, float RGBA:
 * premultiplied light and transmittance where refined, alpha -1 elsewhere). */
sbfx_result sbfx_read_refine_target(sbfx *fx, float *rgba, size_t capacity, int *w, int *h);
/* The black body at kelvin and a medium's phase function at cos_theta (its g is the one the
 * tables were made for) as the particle shader computes them: particle.frag's own functions
 * (table or analytic, whatever that medium's program uses) in a 1x1 pass. */
sbfx_result sbfx_fetch_luts(sbfx *fx, sbfx_medium medium, float kelvin, float cos_theta, float rgb[3],
                            float *phase);
void sbfx_probe_destroy(sbfx *fx);

#endif
