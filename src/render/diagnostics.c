/* Read-backs for the probe and the GL tests: the particle target and the GPU's view of the
 * lookup tables. Not used by the frame loop; like every entry point they leave the host's GL
 * state as they found it. */
#include <stdio.h>
#include <string.h>
#include "render/render.h"

sbfx_result sbfx_read_particle_target(sbfx *fx, float *rgba, size_t capacity, int *w, int *h)
{
    sbfx_gl *gl = fx->gl;
    if (!gl->particles.framebuffer) return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "no particle target yet: render first");
    size_t n = (size_t)gl->low_width * gl->low_height;
    if (!rgba || capacity < n * 4)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "read buffer holds %zu floats, %zu needed",
                         capacity, n * 4);
    *w = gl->low_width;
    *h = gl->low_height;
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_PACK, NULL);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, gl->particles.framebuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (gl->target_type == GL_UNSIGNED_BYTE) {
        /* Expand bytes in place from the back so the float buffer can hold them first. */
        uint8_t *bytes = (uint8_t *)rgba;
        glReadPixels(0, 0, *w, *h, GL_RGBA, GL_UNSIGNED_BYTE, bytes);
        for (size_t i = n * 4; i-- > 0;) rgba[i] = bytes[i] / 255.0f;
    } else {
        glReadPixels(0, 0, *w, *h, GL_RGBA, GL_FLOAT, rgba);
    }
    sbfx_gl_state_restore(&saved);
    return sbfx_gl_check(fx, "reading back the particle target") ? SBFX_OK : SBFX_ERR_GL;
}

sbfx_result sbfx_read_refine_target(sbfx *fx, float *rgba, size_t capacity, int *w, int *h)
{
    sbfx_gl *gl = fx->gl;
    if (!sbfx_refine_used(fx))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "no refine target: the level is not mixed resolution, or nothing rendered yet");
    size_t n = (size_t)gl->refine.width * gl->refine.height;
    if (!rgba || capacity < n * 4)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "read buffer holds %zu floats, %zu needed", capacity, n * 4);
    *w = gl->refine.width;
    *h = gl->refine.height;
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_PACK, NULL);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, gl->refine.framebuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, *w, *h, GL_RGBA, GL_FLOAT, rgba);
    sbfx_gl_state_restore(&saved);
    return sbfx_gl_check(fx, "reading back the refine target") ? SBFX_OK : SBFX_ERR_GL;
}

static sbfx_result ensure_probe_target(sbfx *fx)
{
    sbfx_probe *probe = &fx->render->probe;
    if (probe->probe_fbo) return SBFX_OK;
    if (!sbfx_context_desktop() && !sbfx_has_extension("GL_EXT_color_buffer_float"))
        return sbfx_fail(fx, SBFX_ERR_GL, "reading tables back needs GL_EXT_color_buffer_float");
    probe->probe_texture = sbfx_texture_create(fx, GL_TEXTURE_2D, GL_NEAREST, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, 1, 1, 0, GL_RGBA, GL_FLOAT, NULL);
    glGenFramebuffers(1, &probe->probe_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, probe->probe_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, probe->probe_texture, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return sbfx_fail(fx, SBFX_ERR_GL, "the 1x1 RGBA32F read-back target is incomplete");
    return sbfx_gl_check(fx, "creating the table read-back target") ? SBFX_OK : SBFX_ERR_GL;
}

/* particle.frag with TABLE_PROBE: its own blackbody() and phase(), table or analytic as the
 * medium's program at the current level has them. */
static sbfx_result ensure_probe_program(sbfx *fx, sbfx_medium m)
{
    sbfx_probe *probe = &fx->render->probe;
    const sbfx_tables *t = fx->tables;
    if (probe->lut_program && probe->lut_medium == (int)m && probe->lut_blackbody_analytic == t->blackbody_analytic &&
        probe->lut_phase_analytic == t->phase_analytic[m])
        return SBFX_OK; /* remade when the medium or the level's table/analytic choice changed */
    sbfx_program_delete(fx, probe->lut_program);
    char defines[256];
    snprintf(defines, sizeof(defines), "#define TABLE_PROBE\n#define MEDIUM_EMITS\n#define MEDIUM_SCATTERS\n%s%s",
             fx->tables->blackbody_analytic ? "#define BLACKBODY_ANALYTIC\n" : "",
             fx->tables->phase_analytic[m] ? "#define PHASE_ANALYTIC\n" : "");
    probe->lut_program = sbfx_program_build(fx, "fullscreen.vert", "particle.frag", defines);
    probe->lut_medium = (int)m;
    probe->lut_blackbody_analytic = t->blackbody_analytic;
    probe->lut_phase_analytic = t->phase_analytic[m];
    if (!probe->lut_program) return SBFX_ERR_SHADER;
    if (fx->tables->blackbody_analytic) {
        sbfx_program p = {.id = probe->lut_program};
        sbfx_program_locate(&p);
        sbfx_program_load_cmf(fx, &p);
    }
    return SBFX_OK;
}

static void draw_lut_fetch(sbfx *fx, sbfx_medium medium, float kelvin, float cos_theta, float rgb[3],
                           float *phase)
{
    const sbfx_probe *probe = &fx->render->probe;
    sbfx_program p = {.id = probe->lut_program};
    sbfx_program_locate(&p);
    glBindFramebuffer(GL_FRAMEBUFFER, probe->probe_fbo);
    glViewport(0, 0, 1, 1);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(p.id);
    sbfx_tables_bind(fx, &p, medium);
    glUniform2f(p.probe, kelvin, cos_theta);
    glBindVertexArray(fx->gl->fullscreen_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    float out[4];
    glReadPixels(0, 0, 1, 1, GL_RGBA, GL_FLOAT, out);
    memcpy(rgb, out, 3 * sizeof(float));
    *phase = out[3];
}

sbfx_result sbfx_fetch_luts(sbfx *fx, sbfx_medium medium, float kelvin, float cos_theta, float rgb[3], float *phase)
{
    if ((unsigned)medium >= SBFX_MEDIUM_COUNT || !fx->tables->blackbody || !sbfx_medium_uses_phase(fx, medium))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "the loaded effects use no fire, or medium %d scatters "
                         "no light through the phase function", (int)medium);
    /* unit 0: where the read-back texture is made; 2 and 3: the tables */
    const sbfx_gl_units units = {.tex_2d = 1u << 0 | 1u << SBFX_UNIT_PHASE | 1u << SBFX_UNIT_BLACKBODY};
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_PASS | SBFX_GL_SAVE_PACK | fx->gl->context.parts, &units);
    sbfx_result r = ensure_probe_target(fx);
    if (r == SBFX_OK) r = ensure_probe_program(fx, medium);
    if (r == SBFX_OK) draw_lut_fetch(fx, medium, kelvin, cos_theta, rgb, phase);
    sbfx_gl_state_restore(&saved);
    if (r != SBFX_OK) return r;
    return sbfx_gl_check(fx, "fetching the tables") ? SBFX_OK : SBFX_ERR_GL;
}

void sbfx_probe_destroy(sbfx *fx)
{
    sbfx_probe *p = &fx->render->probe;
    sbfx_program_delete(fx, p->lut_program);
    if (p->probe_texture) glDeleteTextures(1, &p->probe_texture);
    if (p->probe_fbo) glDeleteFramebuffers(1, &p->probe_fbo);
}
