/* The host's transmittance shadow map (RTR 13.8.1; docs/embedding.md "Smoke that shades the
 * host"): the particles seen from one directional light along parallel rays, each multiplying
 * the map by its own transmittance. Made at load only when the desc or scene asks for it;
 * one pass per sbfx_render_shadow_map with particles, none without. */
#include <math.h>
#include <string.h>
#include "render/render.h"

#define SHADOW_MIN_SIZE 16
#define SHADOW_MARGIN_TEXELS 2   /* cleared texels kept on each side: CLAMP_TO_EDGE reads 1 */
#define SHADOW_INSTANCE_FLOATS 5 /* light-view centre, radius, tau x intensity */

static const sbfx_rt_format shadow_rgba16f = {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT, 8, false};

/* ---- load ---- */

static int renderable_limit(void)
{
    GLint texture = 0, renderbuffer = 0, viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    int limit = texture < renderbuffer ? texture : renderbuffer;
    if (viewport[0] < limit) limit = viewport[0];
    return viewport[1] < limit ? viewport[1] : limit;
}

/* Clears the map to transmittance 1; the caller saved the draw framebuffer. */
static void clear_map(sbfx *fx)
{
    GLfloat host_clear[4];
    glGetFloatv(GL_COLOR_CLEAR_VALUE, host_clear);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fx->render->shadow.map.framebuffer);
    glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glClearColor(host_clear[0], host_clear[1], host_clear[2], host_clear[3]);
    fx->render->shadow.clear = true;
}

static sbfx_result create_map(sbfx *fx, int size)
{
    const sbfx_rt_format *half[SBFX_RT_MAX] = {&shadow_rgba16f}, *rgba8[SBFX_RT_MAX] = {&sbfx_rt_rgba8};
    if (sbfx_half_float_renderable() && sbfx_rt_create(fx, &fx->render->shadow.map, size, size, half, NULL, GL_LINEAR))
        return SBFX_OK;
    sbfx_log(fx, SBFX_LOG_INFO, "shadow map: RGBA16F is not renderable here, the map is RGBA8 (transmittance in "
             "steps of 1/255 per particle, depth in 1/255 of the smoke's extent)");
    if (sbfx_rt_create(fx, &fx->render->shadow.map, size, size, rgba8, NULL, GL_LINEAR)) return SBFX_OK;
    return sbfx_fail(fx, SBFX_ERR_GL, "shadow map: a %dx%d RGBA8 framebuffer is incomplete on this context; "
                     "try a smaller desc.shadow_map_size", size, size);
}

static sbfx_result create_buffers(sbfx *fx)
{
    sbfx_shadow *s = &fx->render->shadow;
    glGenVertexArrays(1, &s->vao);
    glGenBuffers(1, &s->buffer);
    glBindVertexArray(s->vao);
    glBindBuffer(GL_ARRAY_BUFFER, s->buffer);
    size_t bytes = (size_t)fx->sim->pool.capacity * SHADOW_INSTANCE_FLOATS * sizeof(float);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)bytes, NULL, GL_DYNAMIC_DRAW);
    GLsizei stride = SHADOW_INSTANCE_FLOATS * sizeof(float);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, stride, (const void *)0);
    glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, stride, (const void *)(4 * sizeof(float)));
    for (GLuint a = 0; a < 2; a++) {
        glEnableVertexAttribArray(a);
        glVertexAttribDivisor(a, 1);
    }
    glBindVertexArray(0);
    fx->counters.gpu_bytes += bytes;
    return sbfx_gl_check(fx, "creating the shadow map's instance buffer") ? SBFX_OK : SBFX_ERR_GL;
}

sbfx_result sbfx_shadow_create(sbfx *fx)
{
    int size = fx->scene->desc.shadow_map_size;
    if (size == 0) return SBFX_OK;
    int limit = renderable_limit();
    if (size < SHADOW_MIN_SIZE || size > limit)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "shadow_map_size %d: this context renders %d .. %d "
                         "texels per side (256 is the default)", size, SHADOW_MIN_SIZE, limit);
    sbfx_shadow *s = &fx->render->shadow;
    s->program = sbfx_program_build(fx, "shadow.vert", "shadow.frag", NULL);
    if (!s->program) return SBFX_ERR_SHADER;
    s->u_matrix = glGetUniformLocation(s->program, "u_matrix");
    s->u_depth = glGetUniformLocation(s->program, "u_depth");
    sbfx_result r = create_buffers(fx);
    if (r != SBFX_OK) return r;
    const sbfx_gl_units unit0 = {1u, 0u, 0u};
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_PASS | fx->gl->context.parts, &unit0);
    r = create_map(fx, size);
    if (r == SBFX_OK) clear_map(fx);
    sbfx_gl_state_restore(&saved);
    if (r != SBFX_OK) return r;
    s->size = size;
    return sbfx_gl_check(fx, "creating the shadow map") ? SBFX_OK : SBFX_ERR_GL;
}

void sbfx_shadow_destroy(sbfx *fx)
{
    sbfx_shadow *s = &fx->render->shadow;
    sbfx_rt_destroy(fx, &s->map);
    sbfx_program_delete(fx, s->program); /* it may be lent to the scene that replaces this one */
    if (s->vao) glDeleteVertexArrays(1, &s->vao);
    if (s->buffer) {
        glDeleteBuffers(1, &s->buffer);
        fx->counters.gpu_bytes -= (size_t)fx->sim->pool.capacity * SHADOW_INSTANCE_FLOATS * sizeof(float);
    }
    *s = (sbfx_shadow){0};
}

/* ---- the light's view ---- */

static bool direction_valid(sbfx *fx, const float d[3])
{
    if (!(isfinite(d[0]) && isfinite(d[1]) && isfinite(d[2]))) {
        sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "shadow map: the light direction is not finite");
        return false;
    }
    if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 1e-20f)) {
        sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "shadow map: the light direction (%g, %g, %g) has zero length: "
                  "give the direction the light travels in", (double)d[0], (double)d[1], (double)d[2]);
        return false;
    }
    return true;
}

/* Light view: looking along the direction of travel, up = world +y unless the light is
 * nearly vertical. */
static void light_view(const float direction[3], float view[16])
{
    const float eye[3] = {0, 0, 0};
    float len = sqrtf(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    const float target[3] = {direction[0] / len, direction[1] / len, direction[2] / len};
    const float y_up[3] = {0, 1, 0}, x_up[3] = {1, 0, 0};
    sbfx_look_at(view, eye, target, fabsf(target[1]) > 0.99f ? x_up : y_up);
}

typedef struct shadow_bounds { float lo[3], hi[3]; } shadow_bounds;

/* Packs the absorbing particles of fx->sim->view[0..n) into fx->sim->instances; returns how many. */
static int pack_instances(sbfx *fx, int n, shadow_bounds *b)
{
    int packed = 0;
    for (int k = 0; k < 3; k++) b->lo[k] = INFINITY, b->hi[k] = -INFINITY;
    for (int i = 0; i < n; i++) {
        const sbfx_view_particle *p = &fx->sim->view[i];
        if (p->medium == SBFX_HEAT) continue;     /* heat neither absorbs nor emits */
        float tau = fx->scene->media[p->medium].tau * p->intensity;
        if (!(tau > 0.0f)) continue;
        float *o = &fx->sim->instances[(size_t)packed++ * SHADOW_INSTANCE_FLOATS];
        memcpy(o, p->center, 3 * sizeof(float));
        o[3] = p->radius;
        o[4] = tau;
        for (int k = 0; k < 3; k++) {
            b->lo[k] = fminf(b->lo[k], p->center[k] - p->radius);
            b->hi[k] = fmaxf(b->hi[k], p->center[k] + p->radius);
        }
    }
    return packed;
}

/* Orthographic light-view -> clip fitted to the bounds, SHADOW_MARGIN_TEXELS of the map left
 * clear on each side (a particle's quad never reaches the border). The quads are drawn at clip
 * z 0 (neither the host's clip control nor its depth range can clip one); the depth along the
 * light, 0 where the particles begin and 1 where they end, is the shader's own (depth: scale and
 * offset of the light view's -z) and the host's matrix's third row (clip z = 2 depth - 1). */
static void fit_projection(const shadow_bounds *b, int size, float proj[16], float depth[2])
{
    float grow = (float)size / (float)(size - 2 * SHADOW_MARGIN_TEXELS);
    memset(proj, 0, 16 * sizeof(float));
    for (int k = 0; k < 2; k++) {
        float mid = 0.5f * (b->lo[k] + b->hi[k]);
        float half = fmaxf(0.5f * (b->hi[k] - b->lo[k]), 1e-3f) * grow;
        proj[k * 5] = 1.0f / half;
        proj[12 + k] = -mid / half;
    }
    proj[15] = 1.0f;
    float near = -b->hi[2], extent = fmaxf(b->hi[2] - b->lo[2], 1e-3f); /* along the light's travel */
    depth[0] = 1.0f / extent;
    depth[1] = -near / extent;
}

/* The host's matrix: the drawing one with the depth row, clip z = 2 (scale (-z) + offset) - 1. */
static void with_depth_row(const float proj[16], const float depth[2], float out[16])
{
    memcpy(out, proj, 16 * sizeof(float));
    out[10] = -2.0f * depth[0];
    out[14] = 2.0f * depth[1] - 1.0f;
}

static void mat4_mul(float out[16], const float a[16], const float b[16])
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            float s = 0.0f;
            for (int k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
            out[c * 4 + r] = s;
        }
}

/* ---- the pass ---- */

static void draw_map(sbfx *fx, int count, const float proj[16], const float depth[2])
{
    sbfx_shadow *s = &fx->render->shadow;
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_PASS | fx->gl->context.parts, NULL);
    /* GL may dither any colour buffer (Mesa does R16F): the product of many particles would
     * then depend on whether the host left GL_DITHER on */
    GLboolean dither = glIsEnabled(GL_DITHER);
    glDisable(GL_DITHER);
    clear_map(fx);
    sbfx_rt_bind(&s->map);
    glEnable(GL_BLEND);
    /* r, g, b: dst * src (products of transmittances); a: the nearest front. The order does not
     * matter. MIN takes no factors. */
    glBlendEquationSeparate(GL_FUNC_ADD, GL_MIN);
    glBlendFuncSeparate(GL_ZERO, GL_SRC_COLOR, GL_ONE, GL_ONE);
    glUseProgram(s->program);
    glUniformMatrix4fv(s->u_matrix, 1, GL_FALSE, proj);
    glUniform2fv(s->u_depth, 1, depth);
    glBindVertexArray(s->vao);
    glBindBuffer(GL_ARRAY_BUFFER, s->buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)((size_t)count * SHADOW_INSTANCE_FLOATS * sizeof(float)),
                    fx->sim->instances);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, count);
    if (dither) glEnable(GL_DITHER);
    sbfx_gl_state_restore(&saved);
    s->clear = false;
    fx->counters.shadow_passes = 1;
}

/* fx->sim->view[0..n) holds the particles in the light's view space. */
static sbfx_result render_map(sbfx *fx, int n, const float view[16], sbfx_shadow_map *out)
{
    shadow_bounds bounds;
    int count = pack_instances(fx, n, &bounds);
    float proj[16], depth[2], host[16];
    if (count == 0) bounds = (shadow_bounds){{-1, -1, -1}, {1, 1, 1}};
    fit_projection(&bounds, fx->render->shadow.size, proj, depth);
    fx->counters.shadow_passes = 0;
    sbfx_result r = SBFX_OK;
    if (count > 0 || !fx->render->shadow.clear) {
        sbfx_gl_enter(fx);
        if (count > 0) {
            draw_map(fx, count, proj, depth);
        } else {
            sbfx_gl_state saved;
            sbfx_gl_state_save(&saved, SBFX_GL_SAVE_PASS | fx->gl->context.parts, NULL);
            clear_map(fx);
            sbfx_gl_state_restore(&saved);
        }
        if (!sbfx_gl_check(fx, "rendering the shadow map")) r = SBFX_ERR_GL;
        sbfx_gl_leave(fx, "sbfx_render_shadow_map");
    }
    out->texture = fx->render->shadow.map.texture[0];
    out->size = fx->render->shadow.size;
    out->particles = count;
    with_depth_row(proj, depth, host);
    mat4_mul(out->view_projection, host, view);
    return r;
}

static sbfx_result check_call(sbfx *fx, const float direction[3], const sbfx_shadow_map *out)
{
    if (!fx) return SBFX_ERR_INVALID_ARGUMENT;
    if (!direction || !out) return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "shadow map: NULL direction or out");
    if (!fx->render->shadow.size)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "shadow map: this module has none: set "
                         "desc.shadow_map_size or the scene's render.host_shadows = true");
    return direction_valid(fx, direction) ? SBFX_OK : SBFX_ERR_INVALID_ARGUMENT;
}

sbfx_result sbfx_render_shadow_map(sbfx *fx, const float direction[3], sbfx_shadow_map *out)
{
    sbfx_result r = check_call(fx, direction, out);
    if (r != SBFX_OK) return r;
    float view[16];
    light_view(direction, view);
    int skipped = fx->counters.particles_skipped; /* that counter belongs to sbfx_render */
    int n = sbfx_collect_view_particles(fx, view);
    fx->counters.particles_skipped = skipped;
    return render_map(fx, n, view, out);
}

sbfx_result sbfx_render_shadow_particles(sbfx *fx, const float direction[3], const sbfx_view_particle *world,
                                         int count, sbfx_shadow_map *out)
{
    sbfx_result r = check_call(fx, direction, out);
    if (r != SBFX_OK) return r;
    if (count < 0 || count > fx->sim->pool.capacity || (count > 0 && !world))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "shadow map: %d particles for a pool of %d", count,
                         fx->sim->pool.capacity);
    float view[16];
    light_view(direction, view);
    int n = 0;
    for (int i = 0; i < count; i++) {
        sbfx_view_particle p = world[i];
        const float *c = world[i].center;
        for (int k = 0; k < 3; k++)
            p.center[k] = view[k] * c[0] + view[4 + k] * c[1] + view[8 + k] * c[2] + view[12 + k];
        if (sbfx_view_particle_valid(&p)) fx->sim->view[n++] = p;
    }
    return render_map(fx, n, view, out);
}

sbfx_result sbfx_read_shadow_map(sbfx *fx, float *values, size_t capacity)
{
    int size = fx->render->shadow.size;
    if (!size) return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "no shadow map");
    size_t n = (size_t)size * size;
    if (!values || capacity < n * 4)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "read buffer holds %zu floats, %zu needed", capacity, n * 4);
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_PACK, NULL);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fx->render->shadow.map.framebuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (fx->render->shadow.map.bytes == n * 4) { /* RGBA8 */
        uint8_t *bytes = (uint8_t *)values;
        glReadPixels(0, 0, size, size, GL_RGBA, GL_UNSIGNED_BYTE, bytes);
        for (size_t i = n * 4; i-- > 0;) values[i] = bytes[i] / 255.0f;
    } else {
        glReadPixels(0, 0, size, size, GL_RGBA, GL_FLOAT, values);
    }
    sbfx_gl_state_restore(&saved);
    return sbfx_gl_check(fx, "reading back the shadow map") ? SBFX_OK : SBFX_ERR_GL;
}
