/* The host contract (docs/design.md §5): sbfx is a guest in the host's GL context. Every entry point
 * that changes GL state saves exactly the pieces it changes in one block, does its work and
 * puts them back, the way Dear ImGui's GLES3 backend does (sampler bindings included). The
 * host's own textures (scene colour and depth) are read through sbfx's sampler objects, so
 * their parameters are never touched.
 *
 * Every glGet* and glIs* call made here is counted (sbfx_counters.gl_state_queries for a render):
 * some drivers serialise on them (Mesa's glthread syncs its worker thread), so the set is kept
 * to what sbfx really changes — no clear values, polygon offset or dither, which no pass of
 * sbfx touches, and the depth range on ES only for mixed resolution's refinement — and only the texture units the frame binds are queried. */
#define _GNU_SOURCE /* RTLD_DEFAULT */
#include <dlfcn.h>
#include "gl/gl.h"

static void get_int(sbfx_gl_state *s, GLenum name, GLint *out)
{
    glGetIntegerv(name, out);
    s->queries++;
}

static GLboolean is_enabled(sbfx_gl_state *s, GLenum cap)
{
    s->queries++;
    return glIsEnabled(cap);
}

static void set_enabled(GLenum cap, GLboolean on)
{
    if (on) glEnable(cap);
    else glDisable(cap);
}

static uint32_t unit_mask(const sbfx_gl_units *u) { return u->tex_2d | u->tex_3d | u->tex_array; }

static void save_pass(sbfx_gl_state *s)
{
    get_int(s, GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_framebuffer);
    get_int(s, GL_VIEWPORT, s->viewport);
    get_int(s, GL_BLEND_SRC_RGB, &s->blend_func[0]);
    get_int(s, GL_BLEND_DST_RGB, &s->blend_func[1]);
    get_int(s, GL_BLEND_SRC_ALPHA, &s->blend_func[2]);
    get_int(s, GL_BLEND_DST_ALPHA, &s->blend_func[3]);
    get_int(s, GL_BLEND_EQUATION_RGB, &s->blend_equation[0]);
    get_int(s, GL_BLEND_EQUATION_ALPHA, &s->blend_equation[1]);
    get_int(s, GL_DEPTH_FUNC, &s->depth_func);
    s->queries++;
    glGetBooleanv(GL_DEPTH_WRITEMASK, &s->depth_mask);
    s->queries++;
    glGetBooleanv(GL_COLOR_WRITEMASK, s->color_mask);
    s->blend = is_enabled(s, GL_BLEND);
    s->depth_test = is_enabled(s, GL_DEPTH_TEST);
    s->stencil_test = is_enabled(s, GL_STENCIL_TEST);
    s->cull_face = is_enabled(s, GL_CULL_FACE);
    s->scissor_test = is_enabled(s, GL_SCISSOR_TEST);
    s->rasterizer_discard = is_enabled(s, GL_RASTERIZER_DISCARD);
}

/* What every pass of sbfx assumes; blending and the depth pass's depth test are set by the
 * passes. A host depth test left on would test sbfx's last pass against the host's depth. */
static void begin_pass(void)
{
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_RASTERIZER_DISCARD);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

static void restore_pass(const sbfx_gl_state *s)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_framebuffer);
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    glBlendFuncSeparate((GLenum)s->blend_func[0], (GLenum)s->blend_func[1], (GLenum)s->blend_func[2],
                        (GLenum)s->blend_func[3]);
    glBlendEquationSeparate((GLenum)s->blend_equation[0], (GLenum)s->blend_equation[1]);
    glDepthFunc((GLenum)s->depth_func);
    glDepthMask(s->depth_mask);
    glColorMask(s->color_mask[0], s->color_mask[1], s->color_mask[2], s->color_mask[3]);
    set_enabled(GL_BLEND, s->blend);
    set_enabled(GL_DEPTH_TEST, s->depth_test);
    set_enabled(GL_STENCIL_TEST, s->stencil_test);
    set_enabled(GL_CULL_FACE, s->cull_face);
    set_enabled(GL_SCISSOR_TEST, s->scissor_test);
    set_enabled(GL_RASTERIZER_DISCARD, s->rasterizer_discard);
}

/* ---- desktop OpenGL's own raster state (issue 18; docs/hosts/desktop-gl.md) ---- */
#define GL_POLYGON_MODE_CODE 0x0B40
#define GL_FILL_CODE 0x1B02
#define GL_FRONT_AND_BACK_CODE 0x0408
#define GL_COLOR_LOGIC_OP_CODE 0x0BF2
#define GL_DEPTH_CLAMP_CODE 0x864F
#define GL_CLIP_DISTANCE0_CODE 0x3000
#define GL_POLYGON_SMOOTH_CODE 0x0B41
#define GL_ALPHA_TEST_CODE 0x0BC0

typedef void (*polygon_mode_fn)(GLenum face, GLenum mode);

/* glPolygonMode is desktop OpenGL's only: not in libGLESv2. A desktop host has it from libOpenGL
 * or libGL (linked, or loaded by its toolkit); looked up only when a host left a mode other
 * than GL_FILL. */
static polygon_mode_fn polygon_mode_function(void)
{
    static polygon_mode_fn fn;
    if (!fn) *(void **)&fn = dlsym(RTLD_DEFAULT, "glPolygonMode");
    return fn;
}

/* Desktop OpenGL clamps gl_FragDepth to the depth range on float depth buffers (ES to [0, 1]):
 * the depth pass writes the host's depth through it. The mixed-resolution refinement's mask
 * compares the particles' window depth, which the depth range places (on ES as well). */
static bool depth_range_saved(unsigned parts) { return parts & (SBFX_GL_SAVE_DESKTOP | SBFX_GL_SAVE_DEPTH_RANGE); }

static void save_depth_range(sbfx_gl_state *s)
{
    s->queries++;
    glGetFloatv(GL_DEPTH_RANGE, s->depth_range);
    glDepthRangef(0.0f, 1.0f);
}

static void save_desktop(sbfx_gl_state *s)
{
    get_int(s, GL_POLYGON_MODE_CODE, s->polygon_mode);
    s->logic_op = is_enabled(s, GL_COLOR_LOGIC_OP_CODE);
    s->depth_clamp = is_enabled(s, GL_DEPTH_CLAMP_CODE);
    s->polygon_smooth = is_enabled(s, GL_POLYGON_SMOOTH_CODE);
    for (GLenum i = 0; i < 8; i++) s->clip_distance[i] = is_enabled(s, GL_CLIP_DISTANCE0_CODE + i);
    if (s->parts & SBFX_GL_SAVE_COMPAT) s->alpha_test = is_enabled(s, GL_ALPHA_TEST_CODE);
    glDisable(GL_COLOR_LOGIC_OP_CODE);
    glDisable(GL_DEPTH_CLAMP_CODE);
    glDisable(GL_POLYGON_SMOOTH_CODE);
    for (GLenum i = 0; i < 8; i++) glDisable(GL_CLIP_DISTANCE0_CODE + i);
    if (s->parts & SBFX_GL_SAVE_COMPAT) glDisable(GL_ALPHA_TEST_CODE);
    bool fill = s->polygon_mode[0] == GL_FILL_CODE && (s->polygon_mode[1] == 0 || s->polygon_mode[1] == GL_FILL_CODE);
    polygon_mode_fn set_mode = fill ? NULL : polygon_mode_function();
    if (set_mode) set_mode(GL_FRONT_AND_BACK_CODE, GL_FILL_CODE);
    s->polygon_mode_set = set_mode != NULL;
    s->polygon_mode_unfixed = !fill && !set_mode;
}

static void restore_desktop(const sbfx_gl_state *s)
{
    set_enabled(GL_COLOR_LOGIC_OP_CODE, s->logic_op);
    set_enabled(GL_DEPTH_CLAMP_CODE, s->depth_clamp);
    set_enabled(GL_POLYGON_SMOOTH_CODE, s->polygon_smooth);
    for (GLenum i = 0; i < 8; i++) set_enabled(GL_CLIP_DISTANCE0_CODE + i, s->clip_distance[i]);
    if (s->parts & SBFX_GL_SAVE_COMPAT) set_enabled(GL_ALPHA_TEST_CODE, s->alpha_test);
    /* core profile has one mode for both faces; compatibility may hold two */
    polygon_mode_fn set_mode = s->polygon_mode_set ? polygon_mode_function() : NULL;
    if (set_mode && s->polygon_mode[1] && s->polygon_mode[1] != s->polygon_mode[0]) {
        set_mode(GL_FRONT, (GLenum)s->polygon_mode[0]);
        set_mode(GL_BACK, (GLenum)s->polygon_mode[1]);
    } else if (set_mode) {
        set_mode(GL_FRONT_AND_BACK_CODE, (GLenum)s->polygon_mode[0]);
    }
}

static void save_objects(sbfx_gl_state *s)
{
    get_int(s, GL_CURRENT_PROGRAM, &s->program);
    get_int(s, GL_VERTEX_ARRAY_BINDING, &s->vertex_array);
    get_int(s, GL_ARRAY_BUFFER_BINDING, &s->array_buffer);
}

static void restore_objects(sbfx_gl_state *s)
{
    /* A program the host deleted while it was current is gone once sbfx used another: binding
     * it again would be GL_INVALID_VALUE (ImGui #6220). The element array buffer is VAO state:
     * it comes back with the host's vertex array. */
    GLuint program = (GLuint)s->program;
    if (program) {
        s->queries++;
        if (!glIsProgram(program)) program = 0;
    }
    glUseProgram(program);
    glBindVertexArray((GLuint)s->vertex_array);
    glBindBuffer(GL_ARRAY_BUFFER, (GLuint)s->array_buffer);
}

/* Pixel transfers: sbfx's uploads and read-backs need a tight, unshifted layout and no
 * pixel buffer bound (a host's PBO would turn the pointer into an offset). */
static const GLenum unpack_names[SBFX_GL_PIXEL_STORE] = {GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT,
                                                         GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_IMAGES};
static const GLenum pack_names[SBFX_GL_PIXEL_STORE] = {GL_PACK_ALIGNMENT, GL_PACK_ROW_LENGTH, GL_PACK_SKIP_PIXELS,
                                                       GL_PACK_SKIP_ROWS, 0, 0};

static void save_pixel_store(sbfx_gl_state *s, const GLenum names[], GLenum buffer_binding, GLint store[],
                             GLint *buffer)
{
    get_int(s, buffer_binding, buffer);
    for (int i = 0; i < SBFX_GL_PIXEL_STORE && names[i]; i++) get_int(s, names[i], &store[i]);
}

static void set_pixel_store(const GLenum names[], GLenum buffer_target, const GLint store[], GLint buffer)
{
    glBindBuffer(buffer_target, (GLuint)buffer);
    for (int i = 0; i < SBFX_GL_PIXEL_STORE && names[i]; i++) glPixelStorei(names[i], store ? store[i] : i == 0 ? 4 : 0);
}

static void save_units(sbfx_gl_state *s)
{
    const sbfx_gl_units *u = &s->units;
    get_int(s, GL_ACTIVE_TEXTURE, &s->active_texture);
    for (int i = 0; i < SBFX_GL_MAX_UNITS; i++) {
        uint32_t bit = 1u << i;
        if (!(unit_mask(u) & bit)) continue;
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        if (u->tex_2d & bit) get_int(s, GL_TEXTURE_BINDING_2D, &s->texture_2d[i]);
        if (u->tex_3d & bit) get_int(s, GL_TEXTURE_BINDING_3D, &s->texture_3d[i]);
        if (u->tex_array & bit) get_int(s, GL_TEXTURE_BINDING_2D_ARRAY, &s->texture_array[i]);
        get_int(s, GL_SAMPLER_BINDING, &s->sampler[i]);
    }
    /* sbfx creates its textures on unit 0 (rt.c, luts.c): callers that create include it */
    glActiveTexture(GL_TEXTURE0);
}

static void restore_units(const sbfx_gl_state *s)
{
    const sbfx_gl_units *u = &s->units;
    for (int i = 0; i < SBFX_GL_MAX_UNITS; i++) {
        uint32_t bit = 1u << i;
        if (!(unit_mask(u) & bit)) continue;
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        if (u->tex_2d & bit) glBindTexture(GL_TEXTURE_2D, (GLuint)s->texture_2d[i]);
        if (u->tex_3d & bit) glBindTexture(GL_TEXTURE_3D, (GLuint)s->texture_3d[i]);
        if (u->tex_array & bit) glBindTexture(GL_TEXTURE_2D_ARRAY, (GLuint)s->texture_array[i]);
        glBindSampler((GLuint)i, (GLuint)s->sampler[i]);
    }
    glActiveTexture((GLenum)s->active_texture);
}

void sbfx_gl_state_save(sbfx_gl_state *s, unsigned parts, const sbfx_gl_units *units)
{
    *s = (sbfx_gl_state){.parts = parts};
    if (units) s->units = *units;
    if (parts & (SBFX_GL_SAVE_PASS | SBFX_GL_SAVE_OBJECTS)) save_objects(s);
    if (parts & SBFX_GL_SAVE_PASS) {
        save_pass(s);
        begin_pass();
        if (parts & SBFX_GL_SAVE_DESKTOP) save_desktop(s);
        if (depth_range_saved(parts)) save_depth_range(s);
    }
    if (parts & SBFX_GL_SAVE_UNPACK) {
        save_pixel_store(s, unpack_names, GL_PIXEL_UNPACK_BUFFER_BINDING, s->unpack, &s->unpack_buffer);
        set_pixel_store(unpack_names, GL_PIXEL_UNPACK_BUFFER, NULL, 0);
    }
    if (parts & SBFX_GL_SAVE_PACK) {
        save_pixel_store(s, pack_names, GL_PIXEL_PACK_BUFFER_BINDING, s->pack, &s->pack_buffer);
        set_pixel_store(pack_names, GL_PIXEL_PACK_BUFFER, NULL, 0);
        get_int(s, GL_READ_FRAMEBUFFER_BINDING, &s->read_framebuffer);
    }
    if (unit_mask(&s->units)) save_units(s);
}

int sbfx_gl_state_restore(sbfx_gl_state *s)
{
    if (unit_mask(&s->units)) restore_units(s);
    if (s->parts & SBFX_GL_SAVE_PACK) {
        set_pixel_store(pack_names, GL_PIXEL_PACK_BUFFER, s->pack, s->pack_buffer);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_framebuffer);
    }
    if (s->parts & SBFX_GL_SAVE_UNPACK) set_pixel_store(unpack_names, GL_PIXEL_UNPACK_BUFFER, s->unpack, s->unpack_buffer);
    if (s->parts & SBFX_GL_SAVE_PASS) restore_pass(s);
    if ((s->parts & SBFX_GL_SAVE_PASS) && (s->parts & SBFX_GL_SAVE_DESKTOP)) restore_desktop(s);
    if ((s->parts & SBFX_GL_SAVE_PASS) && depth_range_saved(s->parts)) glDepthRangef(s->depth_range[0], s->depth_range[1]);
    if (s->parts & (SBFX_GL_SAVE_PASS | SBFX_GL_SAVE_OBJECTS)) restore_objects(s);
    return s->queries;
}

void sbfx_bind_texture(GLuint unit, GLenum target, GLuint texture, GLuint sampler)
{
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(target, texture);
    glBindSampler(unit, sampler);
}

/* ---- sampler objects for the host's textures (made at load) ---- */

static GLuint make_sampler(GLenum filter)
{
    GLuint s = 0;
    glGenSamplers(1, &s);
    glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, (GLint)filter);
    glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, (GLint)filter);
    glSamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    return s;
}

/* Depth: NEAREST (a float depth texture is not filterable, and a LINEAR one would be
 * incomplete), no comparison (a shadow-mapping host keeps its own compare mode). Colour:
 * LINEAR for the shimmer's displaced look-ups, clamped at the border. Sampler parameters are
 * not state of any binding point: making them changes nothing of the host's. */
sbfx_result sbfx_samplers_create(sbfx *fx)
{
    fx->gl->depth_sampler = make_sampler(GL_NEAREST);
    fx->gl->color_sampler = make_sampler(GL_LINEAR);
    return sbfx_gl_check(fx, "creating the sampler objects for the host's textures") ? SBFX_OK : SBFX_ERR_GL;
}

void sbfx_samplers_destroy(sbfx *fx)
{
    GLuint samplers[] = {fx->gl->depth_sampler, fx->gl->color_sampler};
    for (size_t i = 0; i < ARRAY_SIZE(samplers); i++)
        if (samplers[i]) glDeleteSamplers(1, &samplers[i]);
    fx->gl->depth_sampler = fx->gl->color_sampler = 0;
}
