/* The reduced-resolution particle target and the downsampled opaque depth (docs/design.md §2.5).
 * Made on the first render and again only when the output size changes.
 * The particle framebuffer's attachments: 0 light + transmittance; 1 heat-shimmer offsets
 * (scenes with heat); 2 premultiplied screen velocity and view distance (scenes with velocity
 * motion blur or depth of field). */
#include "gl/gl.h"

typedef struct target_format {
    sbfx_target_format id;
    const sbfx_rt_format *rt;
    const char *name;
} target_format;

static const target_format formats[] = {
    {SBFX_FORMAT_RGBA32F, &sbfx_rt_rgba32f, "RGBA32F"},
    {SBFX_FORMAT_RGBA16F, &sbfx_rt_rgba16f, "RGBA16F"},
    {SBFX_FORMAT_RGBA8, &sbfx_rt_rgba8, "RGBA8"},
};

/* Blending into 32-bit floats needs EXT_float_blend as well. */
static bool format_allowed(const target_format *f)
{
    if (f->id == SBFX_FORMAT_RGBA8) return true;
    if (f->id == SBFX_FORMAT_RGBA32F)
        return sbfx_float32_blendable();
    return sbfx_half_float_renderable();
}

static bool try_format(sbfx *fx, sbfx_target_set *set, const target_format *f)
{
    if (!format_allowed(f)) return false;
    /* Signed offsets and velocities need a float format: with RGBA8 they are left out
     * (the shaders' extra outputs then go nowhere) and the loss is logged at load. The shimmer
     * offsets are RGBA16F whatever the light's format: the composite reads them with one
     * filtered fetch (RGBA32F is not filterable in ES 3.0), and a half float holds an offset
     * of at most a few hundredths to 2^-11 of itself (docs/gpus.md, "Precision"). */
    bool is_float = f->id != SBFX_FORMAT_RGBA8;
    const sbfx_rt_format *colors[SBFX_RT_MAX] = {f->rt, is_float && fx->scene->plan.distortion ? &sbfx_rt_rgba16f : NULL,
                                                 is_float && fx->scene->plan.motion_target ? f->rt : NULL};
    /* early termination's depth, only where the scene uses it (render/terminate.c) */
    const sbfx_rt_format *depth = fx->scene->early_termination ? &sbfx_rt_depth16_renderbuffer : NULL;
    if (!sbfx_rt_create(fx, &set->particles, set->low_width, set->low_height, colors, depth, GL_NEAREST)) return false;
    set->target_type = f->rt->type;
    set->format = f->id;
    return true;
}

static const target_format *format_by_id(sbfx_target_format id)
{
    for (size_t i = 0; i < ARRAY_SIZE(formats); i++)
        if (formats[i].id == id) return &formats[i];
    return &formats[1];
}

/* Requested format first, then each cheaper one; RGBA8 always works. */
static sbfx_result create_particle_target(sbfx *fx, sbfx_target_set *set, sbfx_target_format want)
{
    if (!want) want = SBFX_FORMAT_RGBA16F;
    size_t start = 0;
    while (formats[start].id != want) start++;
    for (size_t i = start; i < ARRAY_SIZE(formats); i++) {
        if (!try_format(fx, set, &formats[i])) continue;
        if (i != start && !fx->gl->context.warned_format) {
            fx->gl->context.warned_format = true;
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

/* Early termination's marks (render/terminate.c) write the particle target's depth while they
 * read its colour: a framebuffer of that depth alone, so the read is no feedback loop. */
static sbfx_result create_stop_framebuffer(sbfx *fx, sbfx_target_set *set)
{
    if (!set->particles.depth_renderbuffer || set->stop_framebuffer) return SBFX_OK;
    glGenFramebuffers(1, &set->stop_framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, set->stop_framebuffer);
    glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, set->particles.depth_renderbuffer);
    const GLenum none = GL_NONE;
    glDrawBuffers(1, &none);
    fx->counters.framebuffers++;
    if (glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return sbfx_fail(fx, SBFX_ERR_GL, "the %dx%d DEPTH_COMPONENT16 framebuffer of early termination is incomplete",
                         set->low_width, set->low_height);
    return sbfx_gl_check(fx, "creating early termination's framebuffer") ? SBFX_OK : SBFX_ERR_GL;
}

static void destroy_stop_framebuffer(sbfx *fx, sbfx_target_set *set)
{
    if (!set->stop_framebuffer) return;
    glDeleteFramebuffers(1, &set->stop_framebuffer);
    set->stop_framebuffer = 0;
    fx->counters.framebuffers--;
}

static sbfx_result create_low_depth(sbfx *fx, sbfx_target_set *set)
{
    if (!sbfx_rt_create(fx, &set->low_depth, set->low_width, set->low_height, NULL, &sbfx_rt_depth32f, GL_NEAREST))
        return sbfx_fail(fx, SBFX_ERR_GL, "the %dx%d DEPTH_COMPONENT32F target is incomplete",
                         set->low_width, set->low_height);
    const sbfx_rt_format *corners[SBFX_RT_MAX] = {&sbfx_rt_rgba32f, NULL, NULL};
    if (fx->gl->corners_program &&
        !sbfx_rt_create(fx, &set->low_corners, set->low_width + 1, set->low_height + 1, corners, NULL, GL_NEAREST))
        return sbfx_fail(fx, SBFX_ERR_GL, "the %dx%d RGBA32F target of the low-res corners is incomplete",
                         set->low_width + 1, set->low_height + 1);
    return sbfx_gl_check(fx, "creating the low-resolution depth target") ? SBFX_OK : SBFX_ERR_GL;
}

/* Mixed resolution (render/refine.c): the refined particles at the output size, RGBA16F (its
 * clear value -1 in alpha marks the pixels not refined, which RGBA8 cannot hold) with a depth
 * attachment that masks the refinement to the marked pixels, and the opaque depth at the output size. Where half floats do not
 * render the level is nearest-depth upsampling (logged once). */
static sbfx_result create_refine(sbfx *fx, sbfx_target_set *set)
{
    if (set->refine.framebuffer) return SBFX_OK;
    if (!sbfx_half_float_renderable()) {
        if (!fx->gl->context.warned_refine) {
            fx->gl->context.warned_refine = true;
            sbfx_log(fx, SBFX_LOG_WARN, "mixed resolution needs a colour-renderable RGBA16F target "
                     "(GL_EXT_color_buffer_half_float or GL_EXT_color_buffer_float): upsampling by nearest depth only");
        }
        return SBFX_OK;
    }
    int w = fx->gl->out_width, h = fx->gl->out_height;
    const sbfx_rt_format *colors[SBFX_RT_MAX] = {&sbfx_rt_rgba16f, NULL, NULL};
    if (!sbfx_rt_create(fx, &set->refine, w, h, colors, &sbfx_rt_depth32f, GL_NEAREST))
        return sbfx_fail(fx, SBFX_ERR_GL, "the %dx%d RGBA16F + DEPTH_COMPONENT32F target of mixed resolution is incomplete", w, h);
    if (!sbfx_rt_create(fx, &set->refine_depth, w, h, NULL, &sbfx_rt_depth32f, GL_NEAREST))
        return sbfx_fail(fx, SBFX_ERR_GL, "the %dx%d DEPTH_COMPONENT32F target of mixed resolution is incomplete", w, h);
    return sbfx_gl_check(fx, "creating the targets of mixed resolution") ? SBFX_OK : SBFX_ERR_GL;
}

static void destroy_set(sbfx *fx, sbfx_target_set *set)
{
    destroy_stop_framebuffer(fx, set);
    sbfx_rt_destroy(fx, &set->refine);
    sbfx_rt_destroy(fx, &set->refine_depth);
    sbfx_rt_destroy(fx, &set->particles);
    sbfx_rt_destroy(fx, &set->low_depth);
    sbfx_rt_destroy(fx, &set->low_corners);
}

/* The default format asks for RGBA16F: both share a target. */
int sbfx_target_index(int divisor, sbfx_target_format format)
{
    int log2 = divisor == 1 ? 0 : divisor == 2 ? 1 : divisor == 4 ? 2 : 3;
    return log2 * SBFX_FORMAT_COUNT + (int)(format ? format : SBFX_FORMAT_RGBA16F);
}

/* The targets of level q at the output size (made once per size). */
static sbfx_result ensure_set(sbfx *fx, const sbfx_quality *q)
{
    sbfx_target_set *set = &fx->gl->targets[sbfx_target_index(q->target_divisor, q->target_format)];
    sbfx_result r = SBFX_OK;
    if (!set->particles.framebuffer) {
        int div = q->target_divisor;
        set->low_width = (fx->gl->out_width + div - 1) / div;
        set->low_height = (fx->gl->out_height + div - 1) / div;
        r = create_particle_target(fx, set, q->target_format);
        if (r == SBFX_OK) r = create_low_depth(fx, set);
    }
    if (r == SBFX_OK) r = create_stop_framebuffer(fx, set);
    if (r == SBFX_OK && q->upsample == SBFX_UPSAMPLE_MIXED) r = create_refine(fx, set);
    if (r != SBFX_OK) destroy_set(fx, set);
    return r;
}

sbfx_result sbfx_targets_ensure(sbfx *fx, int width, int height)
{
    sbfx_gl *gl = fx->gl;
    sbfx_result r = SBFX_OK;
    if (gl->out_width != width || gl->out_height != height) {
        sbfx_targets_destroy(fx);
        gl->out_width = width;
        gl->out_height = height;
        for (int i = 0; i < fx->scene->declared_count && r == SBFX_OK; i++) r = ensure_set(fx, &fx->scene->declared[i]);
    }
    if (r == SBFX_OK) r = ensure_set(fx, &fx->scene->current);
    if (r != SBFX_OK) {
        sbfx_targets_destroy(fx);
        return r;
    }
    const sbfx_target_set *set = &gl->targets[sbfx_target_index(fx->scene->current.target_divisor, fx->scene->current.target_format)];
    gl->particles = set->particles;
    gl->low_depth = set->low_depth;
    gl->low_corners = set->low_corners;
    gl->stop_framebuffer = set->stop_framebuffer;
    bool mixed = fx->scene->current.upsample == SBFX_UPSAMPLE_MIXED;
    gl->refine = mixed ? set->refine : (sbfx_rt){0};
    gl->refine_depth = mixed ? set->refine_depth : (sbfx_rt){0};
    gl->low_width = set->low_width;
    gl->low_height = set->low_height;
    gl->target_type = set->target_type;
    fx->counters.target_format = set->format;
    return SBFX_OK;
}

void sbfx_targets_destroy(sbfx *fx)
{
    for (int i = 0; i < SBFX_TARGET_SETS; i++) destroy_set(fx, &fx->gl->targets[i]);
    fx->gl->particles = fx->gl->low_depth = fx->gl->low_corners = fx->gl->refine = fx->gl->refine_depth = (sbfx_rt){0};
    fx->gl->stop_framebuffer = 0;
    fx->gl->out_width = fx->gl->out_height = 0;
}
