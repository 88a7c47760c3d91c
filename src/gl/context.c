/* The host's context (issue 18; docs/hosts/desktop-gl.md): OpenGL ES 3.0 or newer, or a desktop
 * OpenGL context that runs sbfx's GLSL ES 3.00 shaders as they are — core or compatibility
 * profile, OpenGL 4.3+ or 3.3+ with GL_ARB_ES3_compatibility (and GL_ARB_texture_storage below
 * 4.2). The ES entry points sbfx calls exist in desktop OpenGL under the same names; what
 * differs is how a context says what it offers, read here:
 *   float colour targets   ES: GL_EXT_color_buffer_half_float / _float (+ GL_EXT_float_blend
 *                          for RGBA32F);  desktop: core since 3.0 (GL_ARB_color_buffer_float)
 *   GPU timer queries      ES: GL_EXT_disjoint_timer_query;  desktop: 3.3 / GL_ARB_timer_query
 *                          (no disjoint flag)
 *   clip control           ES: GL_EXT_clip_control;  desktop: 4.5 / GL_ARB_clip_control (the
 *                          host's business: sbfx only reads frame.clip_depth_mode) */
#include <stdio.h>
#include <string.h>
#include "gl/gl.h"

/* desktop OpenGL 3.2's, not in the ES headers */
#define GL_CONTEXT_PROFILE_MASK_CODE 0x9126
#define GL_CONTEXT_COMPATIBILITY_PROFILE_BIT_CODE 0x2

/* "OpenGL ES 3.2 Mesa ..." or "4.5 (Core Profile) Mesa ...": the API and major*10+minor. */
static int parse_version(const char *version, bool *desktop)
{
    int major = 0, minor = 0;
    *desktop = strncmp(version, "OpenGL ES", 9) != 0;
    if (*desktop ? sscanf(version, "%d.%d", &major, &minor) != 2
                 : sscanf(version, "OpenGL ES %d.%d", &major, &minor) != 2)
        return 0;
    return major * 10 + minor;
}

int sbfx_context_version(bool *desktop)
{
    const char *version = (const char *)glGetString(GL_VERSION);
    *desktop = false;
    return version ? parse_version(version, desktop) : 0;
}

bool sbfx_context_desktop(void)
{
    bool desktop = false;
    sbfx_context_version(&desktop);
    return desktop;
}

/* What a desktop context lacks, named in `missing` ("" when it can run sbfx). */
static void desktop_missing(int version, char *missing, size_t size)
{
    missing[0] = '\0';
    size_t used = 0;
    if (version < 33)
        used += (size_t)snprintf(missing + used, size - used, "OpenGL 3.3 (sampler objects, instanced arrays)");
    if (version < 43 && !sbfx_has_extension("GL_ARB_ES3_compatibility") && used < size)
        used += (size_t)snprintf(missing + used, size - used, "%sGL_ARB_ES3_compatibility or OpenGL 4.3 (GLSL ES "
                                 "3.00 shaders)", used ? ", " : "");
    if (version < 42 && !sbfx_has_extension("GL_ARB_texture_storage") && used < size)
        snprintf(missing + used, size - used, "%sGL_ARB_texture_storage or OpenGL 4.2 (immutable textures)",
                 used ? ", " : "");
}

/* Mesa's software rasterisers (llvmpipe, softpipe) carry mediump values as half floats, converting
 * each one to and from single precision, where a GPU that has half precision runs it at twice the
 * rate: on llvmpipe the composite took 47 ms at 960x540 with its mediump declarations and 16 ms
 * without them (docs/gpus.md, "Precision"). On these renderers the shaders are compiled with
 * mediump meaning highp; every GPU gets them as written. */
static bool software_rasteriser(void)
{
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    return renderer && (strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe"));
}

static sbfx_result context_accepted(sbfx *fx)
{
    fx->gl->context.mediump_as_highp = software_rasteriser() && !fx->gl->context.mediump_native; /* SBFX_MEDIUMP=native: precision.c */
    if (fx->gl->context.mediump_as_highp && !fx->gl->donor) /* said once, not again on each sbfx_set_scene */
        sbfx_log(fx, SBFX_LOG_INFO, "renderer \"%s\" is a software rasteriser: shaders compile their mediump as "
                 "highp (half precision is emulated there, and slower)", (const char *)glGetString(GL_RENDERER));
    return SBFX_OK;
}

sbfx_result sbfx_context_check(sbfx *fx)
{
    const char *version = (const char *)glGetString(GL_VERSION);
    if (!version)
        return sbfx_fail(fx, SBFX_ERR_NO_GLES3,
                         "no current OpenGL context: make an OpenGL ES 3.0 context (or a desktop OpenGL 4.3 "
                         "one) current (eglMakeCurrent, SDL_GL_MakeCurrent...) before sbfx_create");
    bool desktop = false;
    int v = parse_version(version, &desktop);
    if (!desktop) {
        if (v >= 30) return context_accepted(fx);
        return sbfx_fail(fx, SBFX_ERR_NO_GLES3,
                         "the current context is \"%s\"; sbfx needs OpenGL ES 3.0 or newer "
                         "(request EGL_CONTEXT_MAJOR_VERSION 3 with EGL_OPENGL_ES3_BIT)", version);
    }
    char missing[256];
    desktop_missing(v, missing, sizeof(missing));
    if (!missing[0]) {
        GLint profile = 0;
        if (v >= 32) glGetIntegerv(GL_CONTEXT_PROFILE_MASK_CODE, &profile);
        bool compat = v < 32 || (profile & GL_CONTEXT_COMPATIBILITY_PROFILE_BIT_CODE);
        fx->gl->context.parts = SBFX_GL_SAVE_DESKTOP | (compat ? SBFX_GL_SAVE_COMPAT : 0u);
        return context_accepted(fx);
    }
    return sbfx_fail(fx, SBFX_ERR_NO_GLES3,
                     "the current context is desktop OpenGL \"%s\", which lacks %s; sbfx runs on OpenGL ES 3.0 "
                     "or desktop OpenGL 4.3 (core or compatibility profile)", version, missing);
}
