/* Passes 1 and 3 of a frame with live particles (frame.c): the opaque depth downsampled to the
 * particle target's resolution (and, for nearest-depth upsampling on RGBA32F devices, its
 * corners gathered), and the composite of the particle target over the host's framebuffer. Each
 * draws only the screen tiles the frame's particles can change (tiles.h, tiles.c). */
#include <math.h>
#include <string.h>
#include "render/render.h"

/* Mixed resolution's refined particles in the composite (refine.c made them; the test is
 * sbfx_refine_used's, here so that the passes do not call back into refine.c, which calls them). */
static bool refined(const sbfx *fx)
{
    return fx->gl->refine.framebuffer != 0 && fx->gl->refine_mark_program != 0 &&
           fx->scene->desc.upsample == SBFX_UPSAMPLE_MIXED;
}

/* Heat shimmer in the composite: heat particles and a float target to hold their offsets. */
static bool shimmer(const sbfx *fx) { return fx->scene->plan.distortion && fx->gl->particles.texture[1]; }

/* The closest opaque distance of each texel of `target` (the output at 1 / divisor per axis), as
 * near / distance (0: none), on the tiles. */
void sbfx_pass_depth_into(sbfx *fx, const sbfx_frame *f, const frame_params *fp, const sbfx_rt *target, int divisor)
{
    sbfx_gl *gl = fx->gl;
    /* divisor 1 (mixed resolution's full-resolution depth): the one-texel variant */
    bool single = divisor == 1 && gl->refine_depth_program && target == &gl->refine_depth;
    GLuint prog = single ? gl->refine_depth_program : gl->depth_program;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target->framebuffer);
    glViewport(0, 0, target->width, target->height);
    glEnable(GL_DEPTH_TEST); /* depth writes need the test on; ALWAYS keeps every fragment */
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glUseProgram(prog);
    sbfx_bind_texture(0, GL_TEXTURE_2D, f->scene_depth_texture, gl->depth_sampler);
    const sbfx_pass_uniforms *u = single ? &gl->refine_depth_u : &gl->depth_u;
    glUniform1i(u->scene_depth, 0);
    glUniform1i(u->divisor, divisor);
    glUniform2i(u->full_size, f->width, f->height);
    glUniform3fv(u->near_model, 1, fp->near_model);
    /* near / distance grows with window depth where scale / p14 > 0 (reversed-Z) */
    glUniform1f(u->closer, (fp->depth_model[0] > 0.0f) == (fp->depth_model[3] > 0.0f) ? 1.0f : -1.0f);
    sbfx_tiles_draw(fx, u, true, target->width, target->height, divisor);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    fx->counters.passes++;
}

/* Pass 1: the particle target's resolution. */
void sbfx_pass_depth(sbfx *fx, const sbfx_frame *f, const frame_params *fp)
{
    sbfx_pass_depth_into(fx, f, fp, &fx->gl->low_depth, fx->scene->desc.target_divisor);
}

/* Pass 1b (nearest-depth upsampling, RGBA32F devices): the four low-res depths around each
 * texel gathered into one RGBA32F texel (low_corners.frag), so the composite reads them in one
 * fetch instead of four. */
bool sbfx_corners_used(const sbfx *fx)
{
    return fx->gl->low_corners.framebuffer &&
           (fx->scene->desc.upsample == SBFX_UPSAMPLE_NEAREST_DEPTH || fx->scene->desc.upsample == SBFX_UPSAMPLE_MIXED);
}

void sbfx_pass_corners(sbfx *fx)
{
    sbfx_gl *gl = fx->gl;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gl->low_corners.framebuffer);
    glViewport(0, 0, gl->low_corners.width, gl->low_corners.height);
    glDisable(GL_BLEND); /* a copy: whatever blending the host left on */
    glUseProgram(gl->corners_program);
    sbfx_bind_texture(0, GL_TEXTURE_2D, gl->low_depth.depth, 0);
    glUniform1i(gl->corners_u.low_depth, 0);
    glUniform2i(gl->corners_u.low_size, gl->low_width, gl->low_height);
    sbfx_tiles_draw(fx, &gl->corners_u, true, gl->low_corners.width, gl->low_corners.height,
                    fx->scene->desc.target_divisor);
    fx->counters.passes++;
}

/* The tone map leaves room for the host's picture (composite.frag) when it may read the scene
 * colour: given, and not attached to the framebuffer being drawn (a feedback loop is undefined
 * in GLES). Two counted queries of the bound draw framebuffer when it is the host's own. */
static bool scene_color_readable(sbfx *fx, const sbfx_frame *f)
{
    if (!f->scene_color_texture) return false;
    if (f->out_framebuffer == 0) return true;
    GLint type = GL_NONE, name = 0;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                          GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    fx->counters.gl_state_queries++;
    if (type != GL_TEXTURE) return true;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                          GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
    fx->counters.gl_state_queries++;
    return (GLuint)name != f->scene_color_texture;
}

/* Where sbfx owns the scene, the composite's image outside the tiles is the scene as the
 * composite reads it there (composite.frag SCENE_ONLY). */
static void pass_scene_outside_tiles(sbfx *fx, const sbfx_frame *f)
{
    const sbfx_gl *gl = fx->gl;
    glUseProgram(gl->scene_only_program);
    sbfx_bind_texture(3, GL_TEXTURE_2D, f->scene_color_texture, gl->color_sampler);
    glUniform1i(gl->scene_only_u.scene_color, 3);
    glUniform2f(gl->scene_only_u.full_texel, 1.0f / (float)f->width, 1.0f / (float)f->height);
    sbfx_tiles_draw(fx, &gl->scene_only_u, false, f->width, f->height, 1);
}

/* What the composite's upsampling (and mixed resolution's mark, refine.c) reads of the low-res
 * target and the depths, folded here so that no fragment divides by a uniform. */
void sbfx_pass_upsample_uniforms(sbfx *fx, const sbfx_pass_uniforms *u, const frame_params *fp)
{
    const sbfx_gl *gl = fx->gl;
    int divisor = fx->scene->desc.target_divisor;
    glUniform1f(u->inv_divisor, 1.0f / (float)divisor); /* a power of 2: exact */
    glUniform2f(u->low_texel, 1.0f / (float)gl->low_width, 1.0f / (float)gl->low_height);
    glUniform2f(u->corners_texel, 1.0f / (float)(gl->low_width + 1), 1.0f / (float)(gl->low_height + 1));
    glUniform3fv(u->near_model, 1, fp->near_model);
    glUniform1f(u->depth_threshold, 0.05f);
    /* the particles' reach, at most the far plane's distance (near / it is near_model's B): a window
     * depth of no surface then lands on the reach in the shaders, as the low-res depths' 0 does */
    glUniform1f(u->near_over_far, fmaxf(fp->near / fp->particles_far, fp->near_model[2]));
}

/* Pass 3: dst = dst * T + C over the host's framebuffer (its alpha is kept) on the tiles; where
 * sbfx owns the scene, scene * T + C into its image, and the scene elsewhere. */
void sbfx_pass_composite(sbfx *fx, const sbfx_frame *f, const frame_params *fp)
{
    sbfx_gl *gl = fx->gl;
    GLuint prog = gl->composite_program;
    bool owns = fx->scene->plan.owns_scene;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, owns ? sbfx_post_composite_target(fx, f) : f->out_framebuffer);
    glViewport(0, 0, f->width, f->height);
    if (owns) {
        glDisable(GL_BLEND); /* writes the whole image: scene * T + C, the scene outside the tiles */
        pass_scene_outside_tiles(fx, f);
    } else {
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
    }
    fx->counters.passes++;
    if (!sbfx_tiles_any(fx)) {
        glDisable(GL_BLEND);
        return;
    }
    glUseProgram(prog);
    bool scene_known = owns || scene_color_readable(fx, f);
    if (scene_known) sbfx_bind_texture(3, GL_TEXTURE_2D, f->scene_color_texture, gl->color_sampler);
    glUniform1i(gl->composite_u.scene_color, 3);
    glUniform1i(gl->composite_u.scene_known, scene_known);
    if (owns) glUniform2f(gl->composite_u.full_texel, 1.0f / (float)f->width, 1.0f / (float)f->height);
    if (shimmer(fx)) {
        sbfx_bind_texture(4, GL_TEXTURE_2D, gl->particles.texture[1], gl->color_sampler); /* LINEAR: bilinear in one fetch */
        glUniform1i(gl->composite_u.distortion, 4);
    }
    sbfx_bind_texture(0, GL_TEXTURE_2D, gl->particles.texture[0], 0);
    sbfx_bind_texture(1, GL_TEXTURE_2D, sbfx_corners_used(fx) ? gl->low_corners.texture[0] : gl->low_depth.depth, 0);
    sbfx_bind_texture(2, GL_TEXTURE_2D, f->scene_depth_texture, gl->depth_sampler);
    const sbfx_pass_uniforms *u = &gl->composite_u;
    glUniform1i(u->particles, 0);
    glUniform1i(u->low_depth, 1);
    glUniform1i(u->low_corners, 1);
    glUniform1i(u->scene_depth, 2);
    sbfx_pass_upsample_uniforms(fx, u, fp);
    const sbfx_tone_curve *tc = &fx->scene->tone_curve;
    glUniform3f(u->tone_curve, (float)tc->knee, (float)tc->steepness, (float)tc->inverse_log_white);
    /* the filmic shoulder's constants folded here (composite.frag tone_curve_smooth_white) */
    double slope = tc->steepness / (1.0 - tc->knee), c = M_LN2 * tc->inverse_log_white;
    glUniform4f(u->tone_filmic, (float)slope, (float)(-tc->knee * slope), (float)(1.0 / c), (float)tc->knee);
    glUniform2f(u->tone_shoulder, (float)(2.0 * (1.0 - tc->knee) * c), (float)((1.0 - tc->knee) * c * c));
    if (refined(fx)) {
        sbfx_bind_texture(SBFX_UNIT_REFINED, GL_TEXTURE_2D, gl->refine.texture[0], 0);
        glUniform1i(u->refined, SBFX_UNIT_REFINED);
    }
    sbfx_tiles_draw(fx, u, true, f->width, f->height, 1);
    glDisable(GL_BLEND);
}

