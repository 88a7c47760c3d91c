/* Mixed resolution (SBFX_UPSAMPLE_MIXED; docs/quality-and-budgets.md, "Mixed resolution"): after
 * the particles are drawn into the coarse target, the pixels where it does not hold the picture
 * are shaded again at the output's resolution, as GPU Gems 3 ch. 23.6 does with opaque edges
 * and later practice with the contrast of the coarse image:
 *   1. the opaque depth at full resolution, as near / distance, on the particles' tiles (the
 *      depth downsample with divisor 1), for the refined particles' opacity;
 *   2. the mark (refine_mark.frag), on the tiles: where the coarse texels a pixel's upsampling
 *      reads hold particles and an opaque edge runs through them or the coarse image changes
 *      sharply across them, depth 1 and the refinement's start (no light, transmittance 1) into
 *      the refine target, cleared to depth 0 and alpha -1 (not refined);
 *   3. the particles again, at full resolution, into the refine target with the depth test
 *      passing on the marked pixels only: a tile GPU rejects the others before shading;
 * then the composite (composite.frag REFINED) takes the refined pixel where alpha >= 0 and the
 * upsampled coarse target elsewhere. The depth test is the mask, not the stencil: depth test,
 * function and write mask are already part of the state every render saves (gl/gl_state.c),
 * and the clears are glClearBuffer* (no clear value is changed). The particles are drawn at clip
 * z 0, whose window depth the host's clip control and depth range place: 0.5 with
 * GL_NEGATIVE_ONE_TO_ONE, the range's near end with GL_ZERO_TO_ONE (a reversed-Z host's). The
 * render sets the depth range to [0, 1] for the frame (SBFX_GL_SAVE_DEPTH_RANGE, put back with
 * the rest), so that depth is 0.5 or 0 whatever the host left: GL_LESS passes it under the
 * mark's 1 and fails it over the clear's 0 in both clip depth modes. */
#include "render/render.h"

/* The edge of the coarse image that is refined: a change of transmittance or of display light
 * (v / (1 + v)) between the four texels a pixel reads. Chosen with the accuracy bench
 * (docs/accuracy-and-benchmarks.md, "Mixed resolution"). */
#define REFINE_CONTRAST 0.2f

bool sbfx_refine_used(const sbfx *fx)
{
    return fx->gl->refine.framebuffer != 0 && fx->gl->refine_mark_program != 0 &&
           fx->scene->desc.upsample == SBFX_UPSAMPLE_MIXED;
}

static void pass_mark(sbfx *fx, const sbfx_frame *f, const frame_params *fp)
{
    sbfx_gl *gl = fx->gl;
    sbfx_rt_bind(&gl->refine);
    const GLfloat not_refined[4] = {0.0f, 0.0f, 0.0f, -1.0f}, closed = 0.0f;
    glDepthMask(GL_TRUE);
    glClearBufferfv(GL_COLOR, 0, not_refined);
    glClearBufferfv(GL_DEPTH, 0, &closed);
    glEnable(GL_DEPTH_TEST); /* depth writes need the test on; ALWAYS keeps every fragment */
    glDepthFunc(GL_ALWAYS);
    glDisable(GL_BLEND);
    glUseProgram(gl->refine_mark_program);
    const sbfx_pass_uniforms *u = &gl->refine_mark_u;
    bool corners = sbfx_corners_used(fx);
    sbfx_bind_texture(0, GL_TEXTURE_2D, gl->particles.texture[0], 0);
    sbfx_bind_texture(1, GL_TEXTURE_2D, corners ? gl->low_corners.texture[0] : gl->low_depth.depth, 0);
    sbfx_bind_texture(2, GL_TEXTURE_2D, f->scene_depth_texture, gl->depth_sampler);
    glUniform1i(u->particles, 0);
    glUniform1i(corners ? u->low_corners : u->low_depth, 1);
    glUniform1i(u->scene_depth, 2);
    sbfx_pass_upsample_uniforms(fx, u, fp); /* the composite's (passes.c) */
    glUniform1f(u->contrast, REFINE_CONTRAST);
    sbfx_tiles_draw(fx, u, true, f->width, f->height, 1);
    glDepthMask(GL_FALSE);
    fx->counters.passes++;
}

void sbfx_pass_refine(sbfx *fx, const sbfx_frame *f, const frame_params *fp, int count)
{
    if (!sbfx_refine_used(fx)) return;
    sbfx_gl *gl = fx->gl;
    sbfx_pass_depth_into(fx, f, fp, &gl->refine_depth, 1);
    pass_mark(fx, f, fp);
    /* the refine target is still bound; its depth test passes on the marked pixels only (the
     * particles' window depth, 0.5 or 0, is under the mark's 1 and not under the clear's 0) */
    glDepthFunc(GL_LESS);
    sbfx_bind_texture(UNIT_DEPTH, GL_TEXTURE_2D, gl->refine_depth.depth, 0);
    sbfx_draw_particles(fx, f, fp, count, f->width, f->height, NULL, gl->refine_depth.depth);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
}
