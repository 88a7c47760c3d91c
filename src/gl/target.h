/* Render targets (gl/gl.h says what the room is for): a framebuffer with up to SBFX_RT_MAX colour
 * textures and an optional depth texture (rt.c), and the particle target and downsampled depth
 * of each quality level at the output size (targets.c; docs/design.md §2.5). */
#ifndef SBFX_GL_TARGET_H
#define SBFX_GL_TARGET_H

#include <GLES3/gl3.h>
#include <stdbool.h>
#include <stddef.h>
#include "sbfx.h"

#define SBFX_RT_MAX 3
typedef struct sbfx_rt_format {
    GLenum internal, format, type;
    int bytes;
    bool renderbuffer; /* a depth format made as a renderbuffer: tested, never sampled */
} sbfx_rt_format;
extern const sbfx_rt_format sbfx_rt_rgba8, sbfx_rt_rgba16f, sbfx_rt_rgba32f, sbfx_rt_depth32f;
/* early termination's depth (render/particles.c): DEPTH_COMPONENT16, a renderbuffer */
extern const sbfx_rt_format sbfx_rt_depth16_renderbuffer;

typedef struct sbfx_rt {
    GLuint framebuffer;
    GLuint texture[SBFX_RT_MAX];
    GLuint depth;
    GLuint depth_renderbuffer; /* instead of the depth texture (sbfx_rt_format.renderbuffer) */
    int width, height;
    size_t bytes;
} sbfx_rt;

#define SBFX_TARGET_SETS (4 * SBFX_FORMAT_COUNT)
typedef struct sbfx_target_set {
    sbfx_rt particles, low_depth, low_corners; /* low_corners: RGBA32F devices only (render/passes.c) */
    /* mixed resolution (SBFX_UPSAMPLE_MIXED, render/refine.c), at the output size: the refined
     * particles (RGBA16F; its depth marks the pixels refined) and the opaque depth as near / distance */
    sbfx_rt refine, refine_depth;
    /* early termination (render/particles.c): the framebuffer of the particles' depth
     * renderbuffer alone, which the marks write while they read the particles' colour; 0 where
     * the particle target has no depth */
    GLuint stop_framebuffer;
    int low_width, low_height;
    GLenum target_type;
    sbfx_target_format format;  /* what was made (a fallback may replace the one asked for) */
} sbfx_target_set;

/* rt.c */
bool sbfx_rt_create(sbfx *fx, sbfx_rt *rt, int w, int h, const sbfx_rt_format *const colors[SBFX_RT_MAX],
                    const sbfx_rt_format *depth, GLenum filter);
void sbfx_rt_destroy(sbfx *fx, sbfx_rt *rt);
void sbfx_rt_bind(const sbfx_rt *rt);
bool sbfx_half_float_renderable(void);
bool sbfx_float32_blendable(void); /* RGBA32F colour-renderable and blendable */
bool sbfx_float32_renderable(void); /* RGBA32F colour-renderable (the low-res corners, render/passes.c) */

/* targets.c: the current level's targets at the output size (on a size change, those of
 * every declared level: a budget's switch never creates one) */
sbfx_result sbfx_targets_ensure(sbfx *fx, int width, int height);
void sbfx_targets_destroy(sbfx *fx);
/* The level's target set of a divisor and format (the default format asks for RGBA16F: both
 * share one). */
int sbfx_target_index(int divisor, sbfx_target_format format);

#endif
