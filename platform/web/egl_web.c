/* egl_headless.h's contract in a browser, for the GL suites built with emscripten
 * (make test-web-suites, tests/web/suites.js): each context is WebGL 2 (OpenGL ES 3.0) on a
 * canvas of its own, made for it and taken away again when it closes (WEBGL_lose_context frees
 * it at once: a browser keeps only so many live contexts), so every test starts from a fresh
 * context as it does over EGL. Desktop OpenGL is not there: asked for, the open fails with the
 * reason, and the test skips. */
#include <emscripten/emscripten.h>
#include <emscripten/html5.h>
#include <GLES3/gl3.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "egl/egl_headless.h"

/* A new canvas in the page, 16 x 16 (the tests draw into framebuffers of their own); its id. */
EM_JS(int, web_new_canvas, (void), {
    const n = (Module.sbfxCanvases = (Module.sbfxCanvases || 0) + 1);
    const c = document.createElement("canvas");
    c.id = "sbfx-test-canvas-" + n;
    c.width = c.height = 16;
    document.body.appendChild(c);
    return n;
});

EM_JS(void, web_drop_canvas, (int n), {
    const c = document.getElementById("sbfx-test-canvas-" + n);
    if (c) c.remove();
});

/* The current context let go at once (the browser would otherwise keep it until collected). */
EM_JS(void, web_lose_context, (void), {
    const e = GLctx && GLctx.getExtension("WEBGL_lose_context");
    if (e) e.loseContext();
});

const char *egl_headless_error_string(EGLint code) { return code == EGL_SUCCESS ? "EGL_SUCCESS" : "EGL error (WebGL)"; }

static int open_webgl(struct egl_headless *out, enum egl_headless_api api, char *err, size_t n)
{
    memset(out, 0, sizeof(*out));
    out->api = api;
    if (api != EGL_HEADLESS_GLES3) {
        snprintf(err, n, "a browser offers WebGL 2 (OpenGL ES 3.0), not desktop OpenGL");
        return -ENODEV;
    }
    int canvas = web_new_canvas();
    char selector[64];
    snprintf(selector, sizeof(selector), "#sbfx-test-canvas-%d", canvas);
    EmscriptenWebGLContextAttributes a;
    emscripten_webgl_init_context_attributes(&a);
    a.majorVersion = 2;
    a.minorVersion = 0;
    a.antialias = false;
    a.enableExtensionsByDefault = true;
    EMSCRIPTEN_WEBGL_CONTEXT_HANDLE ctx = emscripten_webgl_create_context(selector, &a);
    if (ctx <= 0) {
        web_drop_canvas(canvas);
        snprintf(err, n, "no WebGL 2 context (emscripten_webgl_create_context: %d)", (int)ctx);
        return -ENODEV;
    }
    emscripten_webgl_make_context_current(ctx);
    out->context = (EGLContext)(intptr_t)ctx;
    out->display = (EGLDisplay)(intptr_t)canvas; /* the canvas's number, to take it away */
    out->platform = "webgl";
    out->egl_major = 1;
    out->egl_minor = 5;
    return 0;
}

int egl_headless_open(struct egl_headless *out, char *err, size_t n) { return open_webgl(out, EGL_HEADLESS_GLES3, err, n); }

int egl_headless_open_api(struct egl_headless *out, enum egl_headless_api api, char *err, size_t n)
{
    return open_webgl(out, api, err, n);
}

/* WebGL reports a lost context, not a reset with guilt: the plain context. */
int egl_headless_open_robust(struct egl_headless *out, char *err, size_t n) { return open_webgl(out, EGL_HEADLESS_GLES3, err, n); }

enum egl_headless_api egl_headless_test_api(void) { return EGL_HEADLESS_GLES3; }

/* Nothing to load: the browser has its WebGL already. */
int egl_headless_load_driver(char *err, size_t n) { return 0; }

void egl_headless_close(struct egl_headless *egl)
{
    if (!egl->context) return;
    EMSCRIPTEN_WEBGL_CONTEXT_HANDLE ctx = (EMSCRIPTEN_WEBGL_CONTEXT_HANDLE)(intptr_t)egl->context;
    emscripten_webgl_make_context_current(ctx);
    web_lose_context();
    emscripten_webgl_make_context_current(0);
    emscripten_webgl_destroy_context(ctx);
    web_drop_canvas((int)(intptr_t)egl->display);
    memset(egl, 0, sizeof(*egl));
}

int egl_headless_recreate_context(struct egl_headless *egl, char *err, size_t n)
{
    enum egl_headless_api api = egl->api;
    egl_headless_close(egl);
    return open_webgl(egl, api, err, n);
}
