/* Render targets: a framebuffer with up to SBFX_RT_MAX colour textures and an optional depth
 * texture, all of one size, NEAREST filtered. Made inside a render's saved state: they bind
 * the draw framebuffer and unit 0's 2D texture, which the render puts back. Creation and deletion keep the counters of
 * textures, framebuffers and GPU bytes true. */
#include "gl/gl.h"

const sbfx_rt_format sbfx_rt_rgba8 = {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 4, false};
const sbfx_rt_format sbfx_rt_rgba16f = {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT, 8, false};
const sbfx_rt_format sbfx_rt_rgba32f = {GL_RGBA32F, GL_RGBA, GL_FLOAT, 16, false};
const sbfx_rt_format sbfx_rt_depth32f = {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, 4, false};
const sbfx_rt_format sbfx_rt_depth16_renderbuffer = {GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT, 2, true};

static GLuint new_texture(const sbfx_rt_format *f, int w, int h, GLenum filter)
{
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    sbfx_texture_params(GL_TEXTURE_2D, filter, GL_CLAMP_TO_EDGE);
    /* immutable storage: no pixel transfer, so the host's unpack buffer and store do not matter */
    glTexStorage2D(GL_TEXTURE_2D, 1, f->internal, w, h);
    return tex;
}

static void count(sbfx *fx, const sbfx_rt *rt, int sign)
{
    int textures = rt->depth ? 1 : 0;
    for (int i = 0; i < SBFX_RT_MAX; i++) textures += rt->texture[i] ? 1 : 0;
    fx->counters.textures += sign * textures;
    fx->counters.framebuffers += sign;
    if (sign > 0) fx->counters.gpu_bytes += rt->bytes;
    else fx->counters.gpu_bytes -= rt->bytes;
}

/* How a target is made: size, attachments' formats, filter (sbfx_hash64). */
static uint64_t target_key(int w, int h, const sbfx_rt_format *const colors[SBFX_RT_MAX], const sbfx_rt_format *depth,
                           GLenum filter)
{
    GLenum recipe[SBFX_RT_MAX + 4] = {(GLenum)w, (GLenum)h, filter, depth ? depth->internal : GL_NONE};
    /* (a renderbuffer's format, DEPTH_COMPONENT16, is never a texture's here: the key tells them apart) */
    for (int i = 0; i < SBFX_RT_MAX; i++) recipe[4 + i] = colors && colors[i] ? colors[i]->internal : GL_NONE;
    return sbfx_hash64(0, recipe, sizeof(recipe));
}

bool sbfx_rt_create(sbfx *fx, sbfx_rt *rt, int w, int h, const sbfx_rt_format *const colors[SBFX_RT_MAX],
                    const sbfx_rt_format *depth, GLenum filter)
{
    uint64_t key = target_key(w, h, colors, depth, filter);
    if (sbfx_object_borrow(fx, SBFX_OBJECT_TARGET, key, NULL, rt)) {
        count(fx, rt, +1);
        return true;
    }
    *rt = (sbfx_rt){.width = w, .height = h};
    GLenum buffers[SBFX_RT_MAX];
    int last = -1;
    glGenFramebuffers(1, &rt->framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, rt->framebuffer);
    for (int i = 0; i < SBFX_RT_MAX; i++) {
        buffers[i] = GL_NONE;
        if (!colors || !colors[i]) continue;
        rt->texture[i] = new_texture(colors[i], w, h, filter);
        glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)i, GL_TEXTURE_2D, rt->texture[i], 0);
        buffers[i] = GL_COLOR_ATTACHMENT0 + (GLenum)i;
        rt->bytes += (size_t)w * h * colors[i]->bytes;
        last = i;
    }
    if (depth && depth->renderbuffer) {
        GLint host = 0; /* the host's renderbuffer binding, which the render's save does not hold */
        glGetIntegerv(GL_RENDERBUFFER_BINDING, &host);
        glGenRenderbuffers(1, &rt->depth_renderbuffer);
        glBindRenderbuffer(GL_RENDERBUFFER, rt->depth_renderbuffer);
        glRenderbufferStorage(GL_RENDERBUFFER, depth->internal, w, h);
        glBindRenderbuffer(GL_RENDERBUFFER, (GLuint)host);
        glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rt->depth_renderbuffer);
        rt->bytes += (size_t)w * h * depth->bytes;
    } else if (depth) {
        rt->depth = new_texture(depth, w, h, GL_NEAREST);
        glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, rt->depth, 0);
        rt->bytes += (size_t)w * h * depth->bytes;
    }
    GLenum none = GL_NONE;
    if (last >= 0) glDrawBuffers(last + 1, buffers);
    else glDrawBuffers(1, &none);
    bool complete = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    while (glGetError() != GL_NO_ERROR) {
    }
    count(fx, rt, +1);
    fx->counters.targets_created++;
    if (complete) sbfx_object_note(fx, SBFX_OBJECT_TARGET, rt->framebuffer, key, rt);
    else sbfx_rt_destroy(fx, rt);
    return complete;
}

void sbfx_rt_destroy(sbfx *fx, sbfx_rt *rt)
{
    if (!rt->framebuffer) return;
    count(fx, rt, -1);
    if (!sbfx_object_release(fx, SBFX_OBJECT_TARGET, rt->framebuffer)) { /* another module's now */
        *rt = (sbfx_rt){0};
        return;
    }
    for (int i = 0; i < SBFX_RT_MAX; i++)
        if (rt->texture[i]) glDeleteTextures(1, &rt->texture[i]);
    if (rt->depth) glDeleteTextures(1, &rt->depth);
    if (rt->depth_renderbuffer) glDeleteRenderbuffers(1, &rt->depth_renderbuffer);
    glDeleteFramebuffers(1, &rt->framebuffer);
    *rt = (sbfx_rt){0};
}

void sbfx_rt_bind(const sbfx_rt *rt)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, rt->framebuffer);
    glViewport(0, 0, rt->width, rt->height);
}

/* Float colour buffers are not renderable in core ES 3.0: the extensions must say so. Desktop
 * OpenGL renders (and blends) them since 3.0 (GL_ARB_color_buffer_float). */
bool sbfx_half_float_renderable(void)
{
    return sbfx_context_desktop() || sbfx_has_extension("GL_EXT_color_buffer_half_float") ||
           sbfx_has_extension("GL_EXT_color_buffer_float");
}

bool sbfx_float32_renderable(void)
{
    return sbfx_context_desktop() || sbfx_has_extension("GL_EXT_color_buffer_float");
}

bool sbfx_float32_blendable(void)
{
    return sbfx_context_desktop() ||
           (sbfx_has_extension("GL_EXT_color_buffer_float") && sbfx_has_extension("GL_EXT_float_blend"));
}
