/* Desktop OpenGL's own state for tests/gl/test_gl_state.c (issue 18): what a desktop host may
 * leave set that OpenGL ES has not — program point size, polygon mode, primitive restart with
 * an index, sRGB framebuffer writes, seamless cube maps, colour logic op, depth clamp, clip
 * distances 0-7, polygon and line smoothing, multisampling, point size; in the compatibility
 * profile the alpha test — set to GL's defaults or to a hostile value, and its snapshot.
 * Header-only. */
#ifndef SBFX_GL_DESKTOP_H
#define SBFX_GL_DESKTOP_H

#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include "gl_snapshot.h"

#define GL_PROGRAM_POINT_SIZE 0x8642
#define GL_POLYGON_MODE 0x0B40
#define GL_LINE 0x1B01
#define GL_FILL 0x1B02
#define GL_PRIMITIVE_RESTART 0x8F9D
#define GL_PRIMITIVE_RESTART_INDEX 0x8F9E
#define GL_FRAMEBUFFER_SRGB 0x8DB9
#define GL_TEXTURE_CUBE_MAP_SEAMLESS 0x884F
#define GL_COLOR_LOGIC_OP 0x0BF2
#define GL_LOGIC_OP_MODE 0x0BF0
#define GL_COPY 0x1503
#define GL_XOR 0x1506
#define GL_DEPTH_CLAMP 0x864F
#define GL_CLIP_DISTANCE0 0x3000
#define GL_POLYGON_SMOOTH 0x0B41
#define GL_LINE_SMOOTH 0x0B20
#define GL_MULTISAMPLE 0x809D
#define GL_POINT_SIZE 0x0B11
#define GL_ALPHA_TEST 0x0BC0
#define GL_ALPHA_TEST_FUNC 0x0BC1
#define GL_ALPHA_TEST_REF 0x0BC2

typedef struct desktop_fns {
    void (*polygon_mode)(GLenum face, GLenum mode);
    void (*logic_op)(GLenum op);
    void (*primitive_restart_index)(GLuint index);
    void (*point_size)(GLfloat size);
    void (*alpha_func)(GLenum func, GLfloat ref);
} desktop_fns;

/* The core profile has no GL_GENERATE_MIPMAP_HINT to set. */
static bool snap_core_profile;

static void desktop_fns_load(desktop_fns *f)
{
    *(void **)&f->polygon_mode = (void *)eglGetProcAddress("glPolygonMode");
    *(void **)&f->logic_op = (void *)eglGetProcAddress("glLogicOp");
    *(void **)&f->primitive_restart_index = (void *)eglGetProcAddress("glPrimitiveRestartIndex");
    *(void **)&f->point_size = (void *)eglGetProcAddress("glPointSize");
    *(void **)&f->alpha_func = (void *)eglGetProcAddress("glAlphaFunc");
}

static void desktop_on(GLenum cap, bool on)
{
    if (on) glEnable(cap);
    else glDisable(cap);
}

static void desktop_state(const desktop_fns *f, bool compat, bool hostile)
{
    desktop_on(GL_PROGRAM_POINT_SIZE, hostile);
    f->polygon_mode(GL_FRONT_AND_BACK, hostile ? GL_LINE : GL_FILL);
    desktop_on(GL_PRIMITIVE_RESTART, hostile);
    f->primitive_restart_index(hostile ? 7u : 0u);
    desktop_on(GL_FRAMEBUFFER_SRGB, hostile);
    desktop_on(GL_TEXTURE_CUBE_MAP_SEAMLESS, hostile);
    desktop_on(GL_COLOR_LOGIC_OP, hostile);
    f->logic_op(hostile ? GL_XOR : GL_COPY);
    desktop_on(GL_DEPTH_CLAMP, hostile);
    for (GLenum i = 0; i < 8; i++) desktop_on(GL_CLIP_DISTANCE0 + i, hostile);
    desktop_on(GL_POLYGON_SMOOTH, hostile);
    desktop_on(GL_LINE_SMOOTH, hostile);
    desktop_on(GL_MULTISAMPLE, !hostile);
    f->point_size(hostile ? 3.0f : 1.0f);
    if (compat) {
        desktop_on(GL_ALPHA_TEST, hostile);
        f->alpha_func(hostile ? GL_GREATER : GL_ALWAYS, hostile ? 0.9f : 0.0f);
    }
}

static void snap_desktop(snapshot *s, bool compat)
{
    SNAP_ON(s, GL_PROGRAM_POINT_SIZE);
    snap_int(s, "GL_POLYGON_MODE", GL_POLYGON_MODE, 2);
    SNAP_ON(s, GL_PRIMITIVE_RESTART);
    SNAP_I(s, GL_PRIMITIVE_RESTART_INDEX);
    SNAP_ON(s, GL_FRAMEBUFFER_SRGB);
    SNAP_ON(s, GL_TEXTURE_CUBE_MAP_SEAMLESS);
    SNAP_ON(s, GL_COLOR_LOGIC_OP);
    SNAP_I(s, GL_LOGIC_OP_MODE);
    SNAP_ON(s, GL_DEPTH_CLAMP);
    for (GLenum i = 0; i < 8; i++) {
        char name[32];
        snprintf(name, sizeof(name), "GL_CLIP_DISTANCE%u", i);
        snap_enabled(s, name, GL_CLIP_DISTANCE0 + i);
    }
    SNAP_ON(s, GL_POLYGON_SMOOTH);
    SNAP_ON(s, GL_LINE_SMOOTH);
    SNAP_ON(s, GL_MULTISAMPLE);
    SNAP_F(s, GL_POINT_SIZE);
    if (compat) {
        SNAP_ON(s, GL_ALPHA_TEST);
        SNAP_I(s, GL_ALPHA_TEST_FUNC);
        SNAP_F(s, GL_ALPHA_TEST_REF);
    }
}

#endif
