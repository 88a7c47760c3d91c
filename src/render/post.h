/* The post chain after the particle composite (render/render.h says what the room is for;
 * post.c; docs/design.md §2.6): depth of field, then motion blur, the seed's history blend or
 * McGuire's velocity reconstruction. Each exists in the plan only when the scene asks for it. */
#ifndef SBFX_RENDER_POST_H
#define SBFX_RENDER_POST_H

#include "gl/gl.h"
#include "render/projection.h"

/* Post-effect state: programs at load, targets with the output size. */
#define SBFX_POST_PROGRAMS 14
#define SBFX_POST_UNIFORMS 48
typedef struct sbfx_post_gl {
    GLuint velocity_program, tile_program, neighbor_program, class_program, blur_program, fast_program, still_program;
    GLuint history_program, copy_program, dof_setup_program, dof_blur_program, dof_composite_program;
    GLuint dof_plain_program, dof_setup_plain_program; /* the DoF composite and setup outside the
                                                           particles' tiles (NO_PARTICLES) */
    const sbfx_rt_format *color_format, *velocity_format;
    bool encode_velocity;      /* RGBA8 velocity: stored as v / (2 max) + 0.5 */
    sbfx_rt frame[2];          /* full-res images between post passes */
    sbfx_rt history[2];        /* history blur ping-pong */
    int history_next;
    bool history_valid;
    sbfx_rt velocity, tile_rows, tiles, neighbors; /* tile_rows: tile max along rows only */
    sbfx_rt classes;           /* the velocity blur's blocks: 1 the gather, 0.5 its fast path, 0 still
                                  (tile_class.frag) */
    sbfx_rt dof[2];            /* each: far field + near field, ping-pong of the separable blur */
    int width, height;
    double last_time;          /* simulation time of the previous render */
    bool have_previous;
    bool particles_drawn;      /* this frame drew particles (their velocities are valid) */
    GLuint host_depth, host_color; /* this frame's host textures: read through sbfx's samplers */
    double previous_view_projection[16];
    GLint locations[SBFX_POST_PROGRAMS][SBFX_POST_UNIFORMS]; /* post.c's uniform table */
} sbfx_post_gl;

/* The texture units the post chain binds (gl_state.c saves them). */
sbfx_gl_units sbfx_post_units(const sbfx *fx);
sbfx_result sbfx_post_programs_create(sbfx *fx);
void sbfx_post_destroy(sbfx *fx);
sbfx_result sbfx_post_targets_ensure(sbfx *fx, int width, int height);
sbfx_result sbfx_post_run(sbfx *fx, const sbfx_frame *frame, const sbfx_depth_model *depth, GLuint source);
/* Where the particle composite writes when sbfx owns the scene, and the texture it is then. */
GLuint sbfx_post_composite_target(const sbfx *fx, const sbfx_frame *f);
GLuint sbfx_post_composite_texture(const sbfx *fx);

#endif
