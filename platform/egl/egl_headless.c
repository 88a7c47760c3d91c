/* Headless GLES 3.0 context: EGL surfaceless on Mesa, with the fallbacks older or other
 * drivers need. See egl_headless.h for the contract. */
#include "egl/egl_headless.h"
#include "egl/gl_reset.h"

#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef EGL_OPENGL_ES3_BIT
#define EGL_OPENGL_ES3_BIT 0x0040 /* EGL 1.5 / EGL_KHR_create_context */
#endif

/* What to tell a user whose machine has no working EGL: Debian package names, because that
 * is what the project's machines run (tools/deps.sh installs the same). */
#define HINT_INSTALL "install libegl-mesa0 and libgl1-mesa-dri (Mesa's EGL and drivers)"

const char *egl_headless_error_string(EGLint code)
{
    static const struct { EGLint code; const char *name; } names[] = {
        {EGL_SUCCESS, "EGL_SUCCESS"},
        {EGL_NOT_INITIALIZED, "EGL_NOT_INITIALIZED"},
        {EGL_BAD_ACCESS, "EGL_BAD_ACCESS"},
        {EGL_BAD_ALLOC, "EGL_BAD_ALLOC"},
        {EGL_BAD_ATTRIBUTE, "EGL_BAD_ATTRIBUTE"},
        {EGL_BAD_CONFIG, "EGL_BAD_CONFIG"},
        {EGL_BAD_CONTEXT, "EGL_BAD_CONTEXT"},
        {EGL_BAD_CURRENT_SURFACE, "EGL_BAD_CURRENT_SURFACE"},
        {EGL_BAD_DISPLAY, "EGL_BAD_DISPLAY"},
        {EGL_BAD_MATCH, "EGL_BAD_MATCH"},
        {EGL_BAD_NATIVE_PIXMAP, "EGL_BAD_NATIVE_PIXMAP"},
        {EGL_BAD_NATIVE_WINDOW, "EGL_BAD_NATIVE_WINDOW"},
        {EGL_BAD_PARAMETER, "EGL_BAD_PARAMETER"},
        {EGL_BAD_SURFACE, "EGL_BAD_SURFACE"},
        {EGL_CONTEXT_LOST, "EGL_CONTEXT_LOST"},
    };
    for (size_t i = 0; i < sizeof(names) / sizeof(names[0]); i++)
        if (names[i].code == code) return names[i].name;
    return "unknown EGL error";
}

static const char *last_egl_error(void)
{
    return egl_headless_error_string(eglGetError());
}

/* Whole-word match in a space-separated extension string (a plain strstr would take
 * "EGL_KHR_surfaceless_context_foo" for "EGL_KHR_surfaceless_context"). */
static bool has_extension(const char *list, const char *name)
{
    size_t len = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)) != NULL; p += len) {
        bool starts = p == list || p[-1] == ' ';
        bool ends = p[len] == '\0' || p[len] == ' ';
        if (starts && ends) return true;
    }
    return false;
}

/* Mesa's surfaceless platform needs no window system and no render node (it falls back to
 * the software rasteriser), which is what a headless board or CI machine has. */
static EGLDisplay surfaceless_display(char *why, size_t n)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client) {
        eglGetError(); /* EGL < 1.5 without client extensions reports EGL_BAD_DISPLAY */
        snprintf(why, n, "no EGL client extensions");
        return EGL_NO_DISPLAY;
    }
    if (!has_extension(client, "EGL_MESA_platform_surfaceless") ||
        !has_extension(client, "EGL_EXT_platform_base")) {
        snprintf(why, n, "EGL_MESA_platform_surfaceless is not offered");
        return EGL_NO_DISPLAY;
    }
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_platform_display) {
        snprintf(why, n, "eglGetPlatformDisplayEXT not found");
        return EGL_NO_DISPLAY;
    }
    EGLDisplay display =
        get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (display == EGL_NO_DISPLAY)
        snprintf(why, n, "eglGetPlatformDisplayEXT failed: %s", last_egl_error());
    return display;
}

static bool initialize(struct egl_headless *egl, EGLDisplay display, char *why, size_t n)
{
    if (display == EGL_NO_DISPLAY) return false;
    if (!eglInitialize(display, &egl->egl_major, &egl->egl_minor)) {
        snprintf(why, n, "eglInitialize failed: %s", last_egl_error());
        eglTerminate(display);
        return false;
    }
    egl->display = display;
    return true;
}

static int open_display(struct egl_headless *egl, char *err, size_t n)
{
    char why_surfaceless[160] = "", why_default[160] = "";
    if (initialize(egl, surfaceless_display(why_surfaceless, sizeof(why_surfaceless)),
                   why_surfaceless, sizeof(why_surfaceless))) {
        egl->platform = "surfaceless";
        return 0;
    }
    /* EGL_DEFAULT_DISPLAY: Mesa picks the platform from EGL_PLATFORM or what it was built
     * with; other vendors' drivers often only offer this path. */
    EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (display == EGL_NO_DISPLAY)
        snprintf(why_default, sizeof(why_default), "eglGetDisplay failed: %s", last_egl_error());
    if (initialize(egl, display, why_default, sizeof(why_default))) {
        egl->platform = "default";
        return 0;
    }
    snprintf(err, n,
             "no EGL display (surfaceless: %s; default display: %s): %s; on a machine without "
             "a GPU, LIBGL_ALWAYS_SOFTWARE=1 selects llvmpipe; without a window system, "
             "EGL_PLATFORM=surfaceless",
             why_surfaceless, why_default, HINT_INSTALL);
    return -ENODEV;
}

/* Without EGL_KHR_surfaceless_context a context can only be made current with a surface, so a
 * 1x1 pbuffer stands in; all rendering goes to FBOs anyway. */
static int choose_config(struct egl_headless *egl, bool surfaceless, char *err, size_t n)
{
    const char *ext = eglQueryString(egl->display, EGL_EXTENSIONS);
    bool configless = has_extension(ext, "EGL_KHR_no_config_context") ||
                      has_extension(ext, "EGL_MESA_configless_context");
    if (configless && surfaceless) {
        egl->config = EGL_NO_CONFIG_KHR;
        return 0;
    }
    const EGLint attribs[] = {
        EGL_RENDERABLE_TYPE, egl->api == EGL_HEADLESS_GLES3 ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_BIT,
        EGL_SURFACE_TYPE, surfaceless ? 0 : EGL_PBUFFER_BIT,
        EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
        EGL_NONE,
    };
    EGLint count = 0;
    if (!eglChooseConfig(egl->display, attribs, &egl->config, 1, &count)) {
        snprintf(err, n, "eglChooseConfig failed: %s", last_egl_error());
        return -EIO;
    }
    if (count < 1) {
        snprintf(err, n, "eglChooseConfig: no RGBA8 config renders OpenGL ES 3 on this %s display; "
                 "%s", egl->platform, HINT_INSTALL);
        return -ENOTSUP;
    }
    return 0;
}

static int create_pbuffer(struct egl_headless *egl, char *err, size_t n)
{
    const EGLint attribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    egl->surface = eglCreatePbufferSurface(egl->display, egl->config, attribs);
    if (egl->surface == EGL_NO_SURFACE) {
        snprintf(err, n, "eglCreatePbufferSurface (needed: no EGL_KHR_surfaceless_context) "
                 "failed: %s", last_egl_error());
        return -EIO;
    }
    return 0;
}

/* Desktop OpenGL 4.5 (EGL 1.5 / EGL_KHR_create_context attributes), core or compatibility. */
static int create_desktop_context(struct egl_headless *egl, char *err, size_t n)
{
    if (!eglBindAPI(EGL_OPENGL_API)) {
        snprintf(err, n, "eglBindAPI(EGL_OPENGL_API) failed: %s; the EGL library offers no desktop "
                 "OpenGL: %s", last_egl_error(), HINT_INSTALL);
        return -ENOTSUP;
    }
    bool core = egl->api == EGL_HEADLESS_GL_CORE;
    const EGLint attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK,
        core ? EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT : EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
        EGL_NONE,
    };
    egl->context = eglCreateContext(egl->display, egl->config, EGL_NO_CONTEXT, attribs);
    if (egl->context == EGL_NO_CONTEXT) {
        snprintf(err, n, "eglCreateContext(OpenGL 4.5 %s profile) failed: %s", core ? "core" : "compatibility",
                 last_egl_error());
        return -ENOTSUP;
    }
    return 0;
}

static int create_context(struct egl_headless *egl, char *err, size_t n)
{
    if (egl->api != EGL_HEADLESS_GLES3) return create_desktop_context(egl, err, n);
    if (!eglBindAPI(EGL_OPENGL_ES_API)) {
        snprintf(err, n, "eglBindAPI(EGL_OPENGL_ES_API) failed: %s; the EGL library has no "
                 "OpenGL ES support: %s", last_egl_error(), HINT_INSTALL);
        return -ENOTSUP;
    }
    EGLint robust[GL_RESET_ATTRIBS_MAX];
    egl->robust = egl->robust && gl_reset_context_attribs(egl->display, true, robust);
    if (egl->robust) egl->context = eglCreateContext(egl->display, egl->config, EGL_NO_CONTEXT, robust);
    if (egl->context != EGL_NO_CONTEXT) return 0;
    egl->robust = false; /* offered but refused for this config: a plain context then */
    const EGLint attribs[] = {EGL_CONTEXT_CLIENT_VERSION, 3, EGL_NONE};
    egl->context = eglCreateContext(egl->display, egl->config, EGL_NO_CONTEXT, attribs);
    if (egl->context == EGL_NO_CONTEXT) {
        EGLint code = eglGetError();
        snprintf(err, n, "eglCreateContext(OpenGL ES 3.0) failed: %s; the driver offers no "
                 "GLES 3.0 context: %s, or try LIBGL_ALWAYS_SOFTWARE=1 (llvmpipe)",
                 egl_headless_error_string(code), HINT_INSTALL);
        return code == EGL_BAD_ALLOC ? -ENOMEM : -ENOTSUP;
    }
    return 0;
}

/* EGL may hand out a context of a lower version than asked for on some drivers; the module
 * needs 3.0, so say so here rather than with a shader error later. */
static int check_gles3(const struct egl_headless *egl, char *err, size_t n)
{
    const char *version = (const char *)glGetString(GL_VERSION);
    int major = 0, minor = 0;
    if (egl->api != EGL_HEADLESS_GLES3) {
        if (version && sscanf(version, "%d.%d", &major, &minor) == 2 && major * 10 + minor >= 45) return 0;
        snprintf(err, n, "the context is '%s', not OpenGL 4.5", version ? version : "(no GL_VERSION)");
        return -ENOTSUP;
    }
    if (!version || sscanf(version, "OpenGL ES %d.%d", &major, &minor) != 2 || major < 3) {
        snprintf(err, n, "the context is '%s', not OpenGL ES 3.0 or later; %s",
                 version ? version : "(no GL_VERSION)", HINT_INSTALL);
        return -ENOTSUP;
    }
    return 0;
}

static int open_context(struct egl_headless *out, enum egl_headless_api api, bool robust, char *err, size_t n)
{
    struct egl_headless egl = {
        .display = EGL_NO_DISPLAY, .context = EGL_NO_CONTEXT, .surface = EGL_NO_SURFACE,
        .robust = robust, .api = api,
    };
    int rc = open_display(&egl, err, n);
    if (rc) return rc;

    bool surfaceless = has_extension(eglQueryString(egl.display, EGL_EXTENSIONS),
                                     "EGL_KHR_surfaceless_context");
    rc = choose_config(&egl, surfaceless, err, n);
    if (rc) goto err_display;
    if (!surfaceless) {
        rc = create_pbuffer(&egl, err, n);
        if (rc) goto err_display;
    }
    rc = create_context(&egl, err, n);
    if (rc) goto err_surface;
    if (!eglMakeCurrent(egl.display, egl.surface, egl.surface, egl.context)) {
        snprintf(err, n, "eglMakeCurrent failed: %s", last_egl_error());
        rc = -EIO;
        goto err_context;
    }
    rc = check_gles3(&egl, err, n);
    if (rc) goto err_current;
    *out = egl;
    return 0;

err_current:
    eglMakeCurrent(egl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
err_context:
    eglDestroyContext(egl.display, egl.context);
err_surface:
    if (egl.surface != EGL_NO_SURFACE) eglDestroySurface(egl.display, egl.surface);
err_display:
    eglTerminate(egl.display);
    eglReleaseThread();
    return rc;
}

int egl_headless_recreate_context(struct egl_headless *egl, char *err, size_t n)
{
    eglMakeCurrent(egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (egl->context != EGL_NO_CONTEXT) eglDestroyContext(egl->display, egl->context);
    egl->context = EGL_NO_CONTEXT;
    int rc = create_context(egl, err, n);
    if (rc) return rc;
    if (!eglMakeCurrent(egl->display, egl->surface, egl->surface, egl->context)) {
        snprintf(err, n, "eglMakeCurrent of the new context failed: %s", last_egl_error());
        return -EIO;
    }
    return check_gles3(egl, err, n);
}

int egl_headless_open(struct egl_headless *out, char *err, size_t n)
{
    return open_context(out, EGL_HEADLESS_GLES3, false, err, n);
}

int egl_headless_open_api(struct egl_headless *out, enum egl_headless_api api, char *err, size_t n)
{
    return open_context(out, api, false, err, n);
}

int egl_headless_open_robust(struct egl_headless *out, char *err, size_t n)
{
    return open_context(out, EGL_HEADLESS_GLES3, true, err, n);
}

enum egl_headless_api egl_headless_test_api(void)
{
    const char *api = getenv("SBFX_TEST_GL_API");
    if (api && strcmp(api, "core") == 0) return EGL_HEADLESS_GL_CORE;
    if (api && strcmp(api, "compat") == 0) return EGL_HEADLESS_GL_COMPAT;
    return EGL_HEADLESS_GLES3;
}

int egl_headless_load_driver(char *err, size_t n)
{
    struct egl_headless egl = {.display = EGL_NO_DISPLAY};
    int r = open_display(&egl, err, n);
    if (r != 0) return r;
    eglTerminate(egl.display);
    eglReleaseThread();
    return 0;
}

void egl_headless_close(struct egl_headless *egl)
{
    if (!egl || egl->display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (egl->context != EGL_NO_CONTEXT) eglDestroyContext(egl->display, egl->context);
    if (egl->surface != EGL_NO_SURFACE) eglDestroySurface(egl->display, egl->surface);
    eglTerminate(egl->display);
    eglReleaseThread();
    egl->display = EGL_NO_DISPLAY;
    egl->context = EGL_NO_CONTEXT;
    egl->surface = EGL_NO_SURFACE;
}
