/* A snapshot of the GL state a host can rely on — far more than sbfx knows it touches — and a
 * comparison that names every entry that differs. Header-only, for tests/gl/test_gl_state.c.
 *
 * Held: framebuffer (draw, read, their draw/read buffers), renderbuffer, program, vertex array,
 * the current vertex array's attributes 0-7 (enable, size, type, stride, normalised, integer,
 * divisor, buffer, pointer), generic attribute values 0-3, every buffer binding point (generic,
 * and uniform/transform-feedback indexed 0-3), transform feedback object, active texture, and on
 * each of the first SNAP_UNITS units the 2D, 3D, 2D-array and cube bindings and the sampler
 * binding; blend (enable, functions, equations, colour), depth (test, function, mask, range,
 * clear), stencil (test, both faces' functions, masks, operations, clear), cull (enable, mode,
 * front face), scissor (test, box), colour mask, clear colour, polygon offset (enable, factor,
 * units), dither, rasterizer discard, alpha-to-coverage, sample coverage (enable, value,
 * invert), primitive restart, viewport, line width, hints, all pack and unpack pixel store,
 * and the clip control (GL_EXT_clip_control) where the context has it. */
#ifndef SBFX_GL_SNAPSHOT_H
#define SBFX_GL_SNAPSHOT_H

#include <GLES3/gl3.h>
#include <stdio.h>
#include <string.h>

#define SNAP_MAX 1024
#define SNAP_UNITS_CAP 48
#define GL_CLIP_ORIGIN_EXT 0x935C
#define GL_CLIP_DEPTH_MODE_EXT 0x935D

typedef struct snap_entry {
    char name[56];
    double v[4];
    int n;
} snap_entry;

typedef struct snapshot {
    int count;
    snap_entry e[SNAP_MAX];
} snapshot;

/* Desktop OpenGL's compatibility profile: attribute 0 is glVertex's, with no current value to
 * query (GL_INVALID_OPERATION). */
static bool snap_compat_profile;

static int snap_units(void)
{
    GLint units = 0;
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
    return units < SNAP_UNITS_CAP ? units : SNAP_UNITS_CAP;
}

static snap_entry *snap_add(snapshot *s, const char *name, int n)
{
    snap_entry *e = &s->e[s->count < SNAP_MAX ? s->count++ : SNAP_MAX - 1];
    snprintf(e->name, sizeof(e->name), "%s", name);
    e->n = n;
    return e;
}

static void snap_int(snapshot *s, const char *name, GLenum pname, int n)
{
    GLint v[4] = {0};
    glGetIntegerv(pname, v);
    snap_entry *e = snap_add(s, name, n);
    for (int i = 0; i < n; i++) e->v[i] = v[i];
}

static void snap_float(snapshot *s, const char *name, GLenum pname, int n)
{
    GLfloat v[4] = {0};
    glGetFloatv(pname, v);
    snap_entry *e = snap_add(s, name, n);
    for (int i = 0; i < n; i++) e->v[i] = v[i];
}

static void snap_bool(snapshot *s, const char *name, GLenum pname, int n)
{
    GLboolean v[4] = {0};
    glGetBooleanv(pname, v);
    snap_entry *e = snap_add(s, name, n);
    for (int i = 0; i < n; i++) e->v[i] = v[i];
}

static void snap_enabled(snapshot *s, const char *name, GLenum cap) { snap_add(s, name, 1)->v[0] = glIsEnabled(cap); }

#define SNAP_I(s, pname) snap_int(s, #pname, pname, 1)
#define SNAP_F(s, pname) snap_float(s, #pname, pname, 1)
#define SNAP_ON(s, cap) snap_enabled(s, #cap, cap)

static void snap_bindings(snapshot *s)
{
    SNAP_I(s, GL_DRAW_FRAMEBUFFER_BINDING);
    SNAP_I(s, GL_READ_FRAMEBUFFER_BINDING);
    SNAP_I(s, GL_READ_BUFFER);
    for (int i = 0; i < 4; i++) {
        char name[32];
        snprintf(name, sizeof(name), "GL_DRAW_BUFFER%d", i);
        snap_int(s, name, GL_DRAW_BUFFER0 + (GLenum)i, 1);
    }
    SNAP_I(s, GL_RENDERBUFFER_BINDING);
    SNAP_I(s, GL_CURRENT_PROGRAM);
    SNAP_I(s, GL_VERTEX_ARRAY_BINDING);
    SNAP_I(s, GL_ARRAY_BUFFER_BINDING);
    SNAP_I(s, GL_ELEMENT_ARRAY_BUFFER_BINDING);
    SNAP_I(s, GL_UNIFORM_BUFFER_BINDING);
    SNAP_I(s, GL_PIXEL_PACK_BUFFER_BINDING);
    SNAP_I(s, GL_PIXEL_UNPACK_BUFFER_BINDING);
    SNAP_I(s, GL_COPY_READ_BUFFER_BINDING);
    SNAP_I(s, GL_COPY_WRITE_BUFFER_BINDING);
    SNAP_I(s, GL_TRANSFORM_FEEDBACK_BUFFER_BINDING);
    SNAP_I(s, GL_TRANSFORM_FEEDBACK_BINDING);
    for (GLuint i = 0; i < 4; i++) {
        char name[48];
        GLint v = 0;
        glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, i, &v);
        snprintf(name, sizeof(name), "GL_UNIFORM_BUFFER_BINDING[%u]", i);
        snap_add(s, name, 1)->v[0] = v;
    }
    GLint v = 0;
    glGetIntegeri_v(GL_TRANSFORM_FEEDBACK_BUFFER_BINDING, 0, &v);
    snap_add(s, "GL_TRANSFORM_FEEDBACK_BUFFER_BINDING[0]", 1)->v[0] = v;
}

static void snap_attributes(snapshot *s)
{
    static const struct { GLenum pname; const char *name; } params[] = {
        {GL_VERTEX_ATTRIB_ARRAY_ENABLED, "enabled"}, {GL_VERTEX_ATTRIB_ARRAY_SIZE, "size"},
        {GL_VERTEX_ATTRIB_ARRAY_TYPE, "type"}, {GL_VERTEX_ATTRIB_ARRAY_STRIDE, "stride"},
        {GL_VERTEX_ATTRIB_ARRAY_NORMALIZED, "normalized"}, {GL_VERTEX_ATTRIB_ARRAY_INTEGER, "integer"},
        {GL_VERTEX_ATTRIB_ARRAY_DIVISOR, "divisor"}, {GL_VERTEX_ATTRIB_ARRAY_BUFFER_BINDING, "buffer"},
    };
    char name[56];
    for (GLuint a = 0; a < 8; a++) {
        for (size_t k = 0; k < sizeof(params) / sizeof(params[0]); k++) {
            GLint v = 0;
            glGetVertexAttribiv(a, params[k].pname, &v);
            snprintf(name, sizeof(name), "attribute %u %s", a, params[k].name);
            snap_add(s, name, 1)->v[0] = v;
        }
        void *pointer = NULL;
        glGetVertexAttribPointerv(a, GL_VERTEX_ATTRIB_ARRAY_POINTER, &pointer);
        snprintf(name, sizeof(name), "attribute %u pointer", a);
        snap_add(s, name, 1)->v[0] = (double)(size_t)pointer;
        if (a < 4 && !(a == 0 && snap_compat_profile)) {
            GLfloat c[4] = {0};
            glGetVertexAttribfv(a, GL_CURRENT_VERTEX_ATTRIB, c);
            snprintf(name, sizeof(name), "attribute %u current value", a);
            snap_entry *e = snap_add(s, name, 4);
            for (int i = 0; i < 4; i++) e->v[i] = c[i];
        }
    }
}

static void snap_units_state(snapshot *s)
{
    static const struct { GLenum pname; const char *name; } params[] = {
        {GL_TEXTURE_BINDING_2D, "2D"}, {GL_TEXTURE_BINDING_3D, "3D"}, {GL_TEXTURE_BINDING_2D_ARRAY, "2D array"},
        {GL_TEXTURE_BINDING_CUBE_MAP, "cube"}, {GL_SAMPLER_BINDING, "sampler"},
    };
    GLint active = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    snap_add(s, "GL_ACTIVE_TEXTURE", 1)->v[0] = active;
    int units = snap_units();
    for (int u = 0; u < units; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        for (size_t k = 0; k < sizeof(params) / sizeof(params[0]); k++) {
            char name[56];
            GLint v = 0;
            glGetIntegerv(params[k].pname, &v);
            snprintf(name, sizeof(name), "unit %d %s binding", u, params[k].name);
            snap_add(s, name, 1)->v[0] = v;
        }
    }
    glActiveTexture((GLenum)active);
}

static void snap_fragment_ops(snapshot *s)
{
    SNAP_ON(s, GL_BLEND);
    SNAP_I(s, GL_BLEND_SRC_RGB);
    SNAP_I(s, GL_BLEND_DST_RGB);
    SNAP_I(s, GL_BLEND_SRC_ALPHA);
    SNAP_I(s, GL_BLEND_DST_ALPHA);
    SNAP_I(s, GL_BLEND_EQUATION_RGB);
    SNAP_I(s, GL_BLEND_EQUATION_ALPHA);
    snap_float(s, "GL_BLEND_COLOR", GL_BLEND_COLOR, 4);
    SNAP_ON(s, GL_DEPTH_TEST);
    SNAP_I(s, GL_DEPTH_FUNC);
    snap_bool(s, "GL_DEPTH_WRITEMASK", GL_DEPTH_WRITEMASK, 1);
    snap_float(s, "GL_DEPTH_RANGE", GL_DEPTH_RANGE, 2);
    SNAP_F(s, GL_DEPTH_CLEAR_VALUE);
    SNAP_ON(s, GL_STENCIL_TEST);
    static const GLenum stencil[] = {GL_STENCIL_FUNC, GL_STENCIL_REF, GL_STENCIL_VALUE_MASK, GL_STENCIL_WRITEMASK,
                                     GL_STENCIL_FAIL, GL_STENCIL_PASS_DEPTH_FAIL, GL_STENCIL_PASS_DEPTH_PASS,
                                     GL_STENCIL_BACK_FUNC, GL_STENCIL_BACK_REF, GL_STENCIL_BACK_VALUE_MASK,
                                     GL_STENCIL_BACK_WRITEMASK, GL_STENCIL_BACK_FAIL,
                                     GL_STENCIL_BACK_PASS_DEPTH_FAIL, GL_STENCIL_BACK_PASS_DEPTH_PASS,
                                     GL_STENCIL_CLEAR_VALUE};
    for (size_t i = 0; i < sizeof(stencil) / sizeof(stencil[0]); i++) {
        char name[48];
        snprintf(name, sizeof(name), "stencil state 0x%04x", stencil[i]);
        snap_int(s, name, stencil[i], 1);
    }
    snap_bool(s, "GL_COLOR_WRITEMASK", GL_COLOR_WRITEMASK, 4);
    snap_float(s, "GL_COLOR_CLEAR_VALUE", GL_COLOR_CLEAR_VALUE, 4);
    SNAP_ON(s, GL_DITHER);
    SNAP_ON(s, GL_SAMPLE_ALPHA_TO_COVERAGE);
    SNAP_ON(s, GL_SAMPLE_COVERAGE);
    SNAP_F(s, GL_SAMPLE_COVERAGE_VALUE);
    snap_bool(s, "GL_SAMPLE_COVERAGE_INVERT", GL_SAMPLE_COVERAGE_INVERT, 1);
}

static void snap_raster(snapshot *s)
{
    snap_int(s, "GL_VIEWPORT", GL_VIEWPORT, 4);
    SNAP_ON(s, GL_SCISSOR_TEST);
    snap_int(s, "GL_SCISSOR_BOX", GL_SCISSOR_BOX, 4);
    SNAP_ON(s, GL_CULL_FACE);
    SNAP_I(s, GL_CULL_FACE_MODE);
    SNAP_I(s, GL_FRONT_FACE);
    SNAP_ON(s, GL_POLYGON_OFFSET_FILL);
    SNAP_F(s, GL_POLYGON_OFFSET_FACTOR);
    SNAP_F(s, GL_POLYGON_OFFSET_UNITS);
    SNAP_ON(s, GL_RASTERIZER_DISCARD);
    SNAP_ON(s, GL_PRIMITIVE_RESTART_FIXED_INDEX);
    SNAP_F(s, GL_LINE_WIDTH);
    SNAP_I(s, GL_GENERATE_MIPMAP_HINT);
    SNAP_I(s, GL_FRAGMENT_SHADER_DERIVATIVE_HINT);
    static const GLenum store[] = {GL_PACK_ALIGNMENT, GL_PACK_ROW_LENGTH, GL_PACK_SKIP_PIXELS, GL_PACK_SKIP_ROWS,
                                   GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT,
                                   GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_IMAGES};
    for (size_t i = 0; i < sizeof(store) / sizeof(store[0]); i++) {
        char name[48];
        snprintf(name, sizeof(name), "pixel store 0x%04x", store[i]);
        snap_int(s, name, store[i], 1);
    }
}

/* The whole snapshot; `clip_control` adds the GL_EXT_clip_control state. */
static void snapshot_take(snapshot *s, bool clip_control)
{
    s->count = 0;
    snap_bindings(s);
    snap_attributes(s);
    snap_units_state(s);
    snap_fragment_ops(s);
    snap_raster(s);
    if (clip_control) {
        SNAP_I(s, GL_CLIP_ORIGIN_EXT);
        SNAP_I(s, GL_CLIP_DEPTH_MODE_EXT);
    }
}

/* Number of entries that differ; each is printed (up to 12) and the first name kept. */
static int snapshot_diff(const snapshot *a, const snapshot *b, const char *when, char *first, size_t first_size)
{
    int differ = 0;
    if (first && first_size) first[0] = '\0';
    for (int i = 0; i < a->count && i < b->count; i++) {
        const snap_entry *x = &a->e[i], *y = &b->e[i];
        bool same = true;
        for (int k = 0; k < x->n; k++) same = same && x->v[k] == y->v[k];
        if (same) continue;
        if (differ == 0 && first) snprintf(first, first_size, "%s", x->name);
        if (differ++ < 12)
            printf("#   %s: %s was %g %g %g %g, now %g %g %g %g\n", when, x->name, x->v[0], x->v[1], x->v[2], x->v[3],
                   y->v[0], y->v[1], y->v[2], y->v[3]);
    }
    return differ + (a->count != b->count);
}

#endif
