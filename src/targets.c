/* The reduced-resolution particle target and the downsampled opaque depth (DESIGN §2.5).
 * Made on the first render and again only when the output size changes. */
#include "module.h"

typedef struct target_format {
    sbfx_target_format id;
    GLenum internal, format, type;
    int bytes_per_texel;
    const char *name;
} target_format;

static const target_format formats[] = {
    {SBFX_FORMAT_RGBA32F, GL_RGBA32F, GL_RGBA, GL_FLOAT, 16, "RGBA32F"},
    {SBFX_FORMAT_RGBA16F, GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT, 8, "RGBA16F"},
    {SBFX_FORMAT_RGBA8, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 4, "RGBA8"},
};

/* Float colour buffers are not renderable in core ES 3.0: the extensions must say so, and
 * blending into 32-bit floats needs EXT_float_blend as well. */
static bool format_allowed(const target_format *f)
{
    if (f->id == SBFX_FORMAT_RGBA8) return true;
    if (f->id == SBFX_FORMAT_RGBA32F)
        return sbfx_has_extension("GL_EXT_color_buffer_float") && sbfx_has_extension("GL_EXT_float_blend");
    return sbfx_has_extension("GL_EXT_color_buffer_half_float") ||
           sbfx_has_extension("GL_EXT_color_buffer_float");
}

static GLuint attach_new_texture(GLenum attachment, GLenum internal, GLenum format, GLenum type,
                                 int w, int h)
{
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    sbfx_texture_params(GL_TEXTURE_2D, GL_NEAREST, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, format, type, NULL);
    glFramebufferTexture2D(GL_FRAMEBUFFER, attachment, GL_TEXTURE_2D, tex, 0);
    return tex;
}

static bool try_format(sbfx *fx, const target_format *f)
{
    sbfx_gl *gl = &fx->gl;
    if (!format_allowed(f)) return false;
    glGenFramebuffers(1, &gl->target_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, gl->target_fbo);
    gl->target_texture = attach_new_texture(GL_COLOR_ATTACHMENT0, f->internal, f->format, f->type,
                                            gl->low_width, gl->low_height);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    while (glGetError() != GL_NO_ERROR) {
    }
    if (status == GL_FRAMEBUFFER_COMPLETE) {
        gl->target_internal = f->internal;
        gl->target_type = f->type;
        fx->counters.target_format = f->id;
        gl->target_bytes = (size_t)gl->low_width * gl->low_height * f->bytes_per_texel;
        return true;
    }
    glDeleteTextures(1, &gl->target_texture);
    glDeleteFramebuffers(1, &gl->target_fbo);
    gl->target_texture = gl->target_fbo = 0;
    return false;
}

static const target_format *format_by_id(sbfx_target_format id)
{
    for (size_t i = 0; i < ARRAY_SIZE(formats); i++)
        if (formats[i].id == id) return &formats[i];
    return &formats[1];
}

/* Requested format first, then each cheaper one; RGBA8 always works. */
static sbfx_result create_particle_target(sbfx *fx)
{
    sbfx_target_format want = fx->desc.target_format ? fx->desc.target_format : SBFX_FORMAT_RGBA16F;
    size_t start = 0;
    while (formats[start].id != want) start++;
    for (size_t i = start; i < ARRAY_SIZE(formats); i++) {
        if (!try_format(fx, &formats[i])) continue;
        if (i != start && !fx->warned_format) {
            fx->warned_format = true;
            sbfx_log(fx, SBFX_LOG_WARN,
                     "%s is not colour-renderable here (needs GL_EXT_color_buffer_half_float or "
                     "GL_EXT_color_buffer_float%s): particles render into %s instead; light above "
                     "1.0 is clipped there", format_by_id(want)->name,
                     want == SBFX_FORMAT_RGBA32F ? " and GL_EXT_float_blend" : "", formats[i].name);
        }
        return SBFX_OK;
    }
    return sbfx_fail(fx, SBFX_ERR_GL, "no particle target format is renderable (not even RGBA8)");
}

static sbfx_result create_low_depth(sbfx *fx)
{
    sbfx_gl *gl = &fx->gl;
    glGenFramebuffers(1, &gl->low_depth_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, gl->low_depth_fbo);
    gl->low_depth_texture = attach_new_texture(GL_DEPTH_ATTACHMENT, GL_DEPTH_COMPONENT32F,
                                               GL_DEPTH_COMPONENT, GL_FLOAT, gl->low_width,
                                               gl->low_height);
    GLenum none = GL_NONE;
    glDrawBuffers(1, &none);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return sbfx_fail(fx, SBFX_ERR_GL, "the %dx%d DEPTH_COMPONENT32F target is incomplete (0x%04x)",
                         gl->low_width, gl->low_height, status);
    return sbfx_gl_check(fx, "creating the low-resolution depth target") ? SBFX_OK : SBFX_ERR_GL;
}

static size_t target_gpu_bytes(const sbfx_gl *gl)
{
    return gl->target_bytes + (size_t)gl->low_width * gl->low_height * 4;
}

sbfx_result sbfx_targets_ensure(sbfx *fx, int width, int height)
{
    sbfx_gl *gl = &fx->gl;
    if (gl->target_fbo && gl->out_width == width && gl->out_height == height) return SBFX_OK;
    sbfx_targets_destroy(fx);
    int div = fx->desc.target_divisor;
    gl->out_width = width;
    gl->out_height = height;
    gl->low_width = (width + div - 1) / div;
    gl->low_height = (height + div - 1) / div;
    sbfx_result r = create_particle_target(fx);
    if (r == SBFX_OK) r = create_low_depth(fx);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (r != SBFX_OK) {
        sbfx_targets_destroy(fx);
        return r;
    }
    fx->counters.textures += 2;
    fx->counters.framebuffers += 2;
    fx->counters.gpu_bytes += target_gpu_bytes(gl);
    return SBFX_OK;
}

void sbfx_targets_destroy(sbfx *fx)
{
    sbfx_gl *gl = &fx->gl;
    if (gl->target_fbo && gl->low_depth_fbo) {
        fx->counters.textures -= 2;
        fx->counters.framebuffers -= 2;
        fx->counters.gpu_bytes -= target_gpu_bytes(gl);
    }
    GLuint textures[] = {gl->target_texture, gl->low_depth_texture};
    GLuint fbos[] = {gl->target_fbo, gl->low_depth_fbo};
    for (size_t i = 0; i < 2; i++) {
        if (textures[i]) glDeleteTextures(1, &textures[i]);
        if (fbos[i]) glDeleteFramebuffers(1, &fbos[i]);
    }
    gl->target_texture = gl->low_depth_texture = gl->target_fbo = gl->low_depth_fbo = 0;
    gl->out_width = gl->out_height = 0;
}
