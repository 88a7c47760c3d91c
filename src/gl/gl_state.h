/* The host contract (docs/design.md §5; gl/gl.h says what the room is for): the host's GL state
 * saved and put back around every entry point that changes it (gl_state.c), the texture units a
 * pass binds, and the samplers through which the host's own textures are read. */
#ifndef SBFX_GL_STATE_H
#define SBFX_GL_STATE_H

#include <GLES3/gl3.h>
#include <stdbool.h>
#include <stdint.h>
#include "sbfx.h"

#define SBFX_GL_MAX_UNITS 8
#define SBFX_GL_PIXEL_STORE 6
enum {
    SBFX_GL_SAVE_PASS = 1 << 0,    /* draw framebuffer, viewport, blend enable/functions/equations,
                                      depth test/function/mask, stencil, cull and scissor tests,
                                      colour mask, rasterizer discard; and the objects below */
    SBFX_GL_SAVE_OBJECTS = 1 << 1, /* program, vertex array, ARRAY_BUFFER */
    SBFX_GL_SAVE_UNPACK = 1 << 2,  /* PIXEL_UNPACK_BUFFER and the unpack pixel store */
    SBFX_GL_SAVE_PACK = 1 << 3,    /* read framebuffer, PIXEL_PACK_BUFFER and the pack pixel store */
    /* with SBFX_GL_SAVE_PASS on desktop OpenGL (fx->gl->context.parts, context.c): what changes
     * sbfx's drawing there and not on ES — the depth range (it clamps gl_FragDepth), polygon
     * mode, colour logic op, depth clamp, clip distances 0-7, polygon smooth; and the
     * compatibility profile's alpha test */
    SBFX_GL_SAVE_DESKTOP = 1 << 4,
    SBFX_GL_SAVE_COMPAT = 1 << 5,
    /* with SBFX_GL_SAVE_PASS on ES too: the depth range, set to [0, 1] — the mixed-resolution
     * refinement's depth mask compares the particles' window depth (render/refine.c) */
    SBFX_GL_SAVE_DEPTH_RANGE = 1 << 6,
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
/* The samplers the host's depth and colour are read through (NEAREST, no compare; LINEAR for
 * colour): made at load, in fx->gl. */
sbfx_result sbfx_samplers_create(sbfx *fx);
void sbfx_samplers_destroy(sbfx *fx);

#endif
