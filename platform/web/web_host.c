/* The browser's host (web.h): a WebGL 2 context on the page's canvas, the module made from the
 * scene text and the page's settings, and one frame at the time the page asks for. */
#include <emscripten/emscripten.h>
#include <emscripten/html5.h>
#include <GLES3/gl3.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "egl/gl_check.h"
#include "web/web.h"

#define MAX_STEP 0.25 /* s: sbfx_update owes at most this much per call (src/sbfx.h) */

static struct web_host host;

struct web_host *web_host_get(void) { return &host; }

/* The library's messages go to the page's log and the browser's console (an error there fails
 * the browser tests: tests/web/). */
EM_JS(void, web_log_to_page, (int level, const char *message), {
    const text = UTF8ToString(message);
    if (Module.onSbfxLog) Module.onSbfxLog(level, text);
    else if (level === 0) console.error("sbfx: " + text);
    else console.log("sbfx: " + text);
});

static void on_sbfx_log(sbfx_log_level level, const char *message, void *user)
{
    web_log_to_page((int)level, message);
}

static int fail(struct web_host *h, int rc, const char *what, sbfx_result r)
{
    snprintf(h->message, sizeof(h->message), "%s: %s: %s", what, sbfx_result_string(r),
             h->fx ? sbfx_last_error(h->fx) : "see the log");
    return rc;
}

/* ---- the canvas's context and the output framebuffer ----------------------------------- */

static int make_context(struct web_host *h, const char *canvas)
{
    EmscriptenWebGLContextAttributes a;
    emscripten_webgl_init_context_attributes(&a);
    a.majorVersion = 2; /* WebGL 2 = OpenGL ES 3.0 */
    a.minorVersion = 0;
    a.alpha = false;    /* the picture is opaque, as on a display */
    a.depth = false;    /* the test scene has its own depth texture */
    a.stencil = false;
    a.antialias = false; /* a multisampled canvas cannot be a blit's destination */
    a.enableExtensionsByDefault = true; /* EXT_color_buffer_float: RGBA16F targets */
    EMSCRIPTEN_WEBGL_CONTEXT_HANDLE ctx = emscripten_webgl_create_context(canvas, &a);
    if (ctx <= 0) {
        snprintf(h->message, sizeof(h->message), "no WebGL 2 context on %s (error %d): this browser or its "
                 "GPU settings do not offer WebGL 2", canvas, (int)ctx);
        return -ENODEV;
    }
    emscripten_webgl_make_context_current(ctx);
    h->context = (int)ctx;
    return 0;
}

static void free_targets(struct web_host *h)
{
    if (h->scene_made) test_scene_destroy(&h->scene);
    h->scene_made = false;
    glDeleteFramebuffers(1, &h->out_framebuffer);
    glDeleteRenderbuffers(1, &h->out_renderbuffer);
    h->out_framebuffer = h->out_renderbuffer = 0;
    free(h->pixels);
    h->pixels = NULL;
}

static int make_targets(struct web_host *h, int width, int height)
{
    free_targets(h);
    h->width = width;
    h->height = height;
    int rc = test_scene_create(&h->scene, width, height, h->message, sizeof(h->message));
    if (rc) return rc;
    h->scene_made = true;
    glGenRenderbuffers(1, &h->out_renderbuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, h->out_renderbuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glGenFramebuffers(1, &h->out_framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, h->out_framebuffer);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, h->out_renderbuffer);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(h->message, sizeof(h->message), "the %dx%d RGBA8 output framebuffer is incomplete (0x%04x)",
                 width, height, status);
        return -EIO;
    }
    h->pixels = malloc((size_t)width * (size_t)height * 4);
    if (!h->pixels) {
        snprintf(h->message, sizeof(h->message), "no memory for a %dx%d read-back", width, height);
        return -ENOMEM;
    }
    return platform_gl_check("the output framebuffer", h->message, sizeof(h->message));
}

/* ---- the module ------------------------------------------------------------------------ */

static void replay_clicks(struct web_host *h)
{
    for (int i = 0; i < h->click_count; i++)
        sbfx_schedule(h->fx, h->clicks[i].effect, h->clicks[i].at, h->clicks[i].position);
}

/* Advances sbfx to the page's time t, in steps sbfx_update takes whole (a scrub forward). */
static int advance(struct web_host *h, double t)
{
    while (h->sim_time < t) {
        double dt = t - h->sim_time < MAX_STEP ? t - h->sim_time : MAX_STEP;
        sbfx_result r = sbfx_update(h->fx, dt);
        if (r != SBFX_OK) return fail(h, -EIO, "sbfx_update", r);
        h->sim_time += dt;
    }
    return 0;
}

/* The module made again from the desc (a new setting): the timeline from 0, the clicks replayed. */
static int create_fx(struct web_host *h)
{
    const struct web_settings *s = &h->settings;
    const sbfx_desc desc = {
        .target_divisor = s->scale,
        .target_format = (sbfx_target_format)s->format,
        .upsample = (sbfx_upsample)s->upsample,
        .opacity = (sbfx_opacity_mode)s->opacity,
        .tone_map = (sbfx_tone_map)s->tone_map,
        .exposure = s->exposure,
        .scene = h->scene_text,
        .log = on_sbfx_log,
    };
    sbfx *fx = NULL;
    sbfx_result r = sbfx_create(&desc, &fx);
    if (r != SBFX_OK) {
        snprintf(h->message, sizeof(h->message), "sbfx_create: %s (the log says why)", sbfx_result_string(r));
        return -EIO;
    }
    sbfx_destroy(h->fx);
    h->fx = fx;
    h->sim_time = 0.0;
    replay_clicks(h);
    return 0;
}

static void take_scene(struct web_host *h, sbfx_scene *scene)
{
    if (scene != h->scene_text) sbfx_scene_free(h->scene_text);
    h->scene_text = scene;
    sbfx_scene_camera_get(scene, &h->camera); /* the default orbit without a camera group */
    sbfx_scene_host_get(scene, &h->daylight);
}

/* ---- exported to the page ---------------------------------------------------------------- */

EMSCRIPTEN_KEEPALIVE const char *sbfx_web_message(void) { return host.message; }

/* The context on the canvas (a CSS selector, "#sbfx-canvas"), targets of width x height, the
 * built-in explosion; the page then loads its scene text. */
EMSCRIPTEN_KEEPALIVE int sbfx_web_start(const char *canvas, int width, int height)
{
    struct web_host *h = &host;
    h->message[0] = '\0';
    int rc = h->context ? 0 : make_context(h, canvas);
    if (!rc) rc = make_targets(h, width, height);
    if (!rc) {
        take_scene(h, NULL);
        rc = create_fx(h);
    }
    return rc;
}

EMSCRIPTEN_KEEPALIVE int sbfx_web_resize(int width, int height)
{
    if (width == host.width && height == host.height) return 0;
    return make_targets(&host, width, height);
}

/* The scene text from the editor. Refused (a syntax error, a value out of range, a shader that
 * does not build): -EINVAL with the message ("scene.cfg:LINE: reason") and the old scene plays
 * on, as sbfx-play --watch does. Taken: its timeline starts again from 0 with the page's. */
EMSCRIPTEN_KEEPALIVE int sbfx_web_load(const char *text, const char *name)
{
    struct web_host *h = &host;
    char why[sizeof(h->message)];
    sbfx_scene *scene = NULL;
    if (sbfx_scene_parse(text, name, &scene, why, sizeof(why)) != SBFX_OK) {
        snprintf(h->message, sizeof(h->message), "%s", why);
        return -EINVAL;
    }
    sbfx_result r = sbfx_restart(h->fx, scene);
    if (r != SBFX_OK) {
        snprintf(h->message, sizeof(h->message), "%s: %s: %s", name, sbfx_result_string(r), sbfx_last_error(h->fx));
        sbfx_scene_free(scene);
        return -EINVAL;
    }
    take_scene(h, scene);
    h->click_count = 0; /* they belonged to the old scene's effects */
    h->sim_time = 0.0;
    h->message[0] = '\0';
    return 0;
}

EMSCRIPTEN_KEEPALIVE int sbfx_web_settings(int scale, int opacity, int format, int upsample, int tone_map,
                                           float exposure)
{
    struct web_host *h = &host;
    struct web_settings old = h->settings;
    h->settings = (struct web_settings){scale, opacity, format, upsample, tone_map, exposure};
    double t = h->sim_time;
    int rc = create_fx(h);
    if (rc) { /* refused: the module made with the old settings plays on */
        h->settings = old;
        return rc;
    }
    return advance(h, t);
}

/* As sbfx-play's player_host_prepare (platform/player/host.c): the scene file's daylight, and
 * where it asks for them the smoke's shadow on the ground and the fire's light on it, which need
 * the simulation at t. */
static int host_prepare(struct web_host *h, double t)
{
    test_scene_set_daylight(&h->scene, &h->daylight);
    bool shadows = h->daylight.host_shadows && h->daylight.has_sun;
    static const float none[16];
    if (!shadows) test_scene_set_shadow(&h->scene, 0, none); /* an edit took them away */
    if (!h->daylight.host_lights) test_scene_set_point_lights(&h->scene, NULL, 0);
    if (!shadows && !h->daylight.host_lights) return 0;
    int rc = advance(h, t);
    if (rc) return rc;
    if (shadows) {
        sbfx_shadow_map map;
        sbfx_result r = sbfx_render_shadow_map(h->fx, h->daylight.sun_direction, &map);
        if (r != SBFX_OK) return fail(h, -EIO, "sbfx_render_shadow_map", r);
        test_scene_set_shadow(&h->scene, map.texture, map.view_projection);
    }
    if (h->daylight.host_lights) {
        sbfx_point_light lights[SBFX_MAX_POINT_LIGHTS];
        int count = sbfx_emitted_lights(h->fx, lights, SBFX_MAX_POINT_LIGHTS);
        if (count < 0) return fail(h, -EIO, "sbfx_emitted_lights", (sbfx_result)count);
        test_scene_set_point_lights(&h->scene, lights, count);
    }
    return 0;
}

/* Draws the frame at the page's time t (seconds since the timeline started): a t before the
 * last frame's starts the timeline again and plays up to t (a scrub back, a restart, a loop). */
EMSCRIPTEN_KEEPALIVE int sbfx_web_frame(double t)
{
    struct web_host *h = &host;
    if (t < h->sim_time) {
        sbfx_result r = sbfx_restart(h->fx, h->scene_text);
        if (r != SBFX_OK) return fail(h, -EIO, "sbfx_restart", r);
        h->sim_time = 0.0;
        replay_clicks(h);
    }
    int rc = host_prepare(h, t);
    if (rc) return rc;
    /* the player's order (loop.c): the scene drawn at t, then sbfx advanced to t and rendered */
    sbfx_frame frame;
    memset(&frame, 0, sizeof(frame));
    test_scene_camera(&h->camera, t, (float)h->width / (float)h->height, frame.view, frame.projection);
    if (test_scene_draw(&h->scene, frame.view, frame.projection) != 0) {
        snprintf(h->message, sizeof(h->message), "test scene: GL error while drawing");
        return -EIO;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, h->scene.framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, h->out_framebuffer);
    glBlitFramebuffer(0, 0, h->width, h->height, 0, 0, h->width, h->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    frame.scene_color_texture = h->scene.color_texture;
    frame.scene_depth_texture = h->scene.depth_texture;
    frame.out_framebuffer = h->out_framebuffer;
    frame.width = h->width;
    frame.height = h->height;
    rc = advance(h, t);
    if (rc) return rc;
    /* a scene's frame budget without GPU timer queries (WebGL 2 has none): its fallback, the
     * host's own time of sbfx's work, between two glFinish calls as sbfx-play headless does */
    sbfx_counters c;
    sbfx_stats(h->fx, &c);
    bool timed = c.budget_ms > 0;
    if (timed) glFinish();
    double start = timed ? emscripten_get_now() : 0.0;
    sbfx_result r = sbfx_render(h->fx, &frame);
    if (r != SBFX_OK) return fail(h, -EIO, "sbfx_render", r);
    if (timed) {
        glFinish();
        sbfx_report_frame_time(h->fx, emscripten_get_now() - start);
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, h->out_framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, h->width, h->height, 0, 0, h->width, h->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return platform_gl_check("the frame's copy onto the canvas", h->message, sizeof(h->message));
}

/* The last frame's pixels, RGBA8, bottom row first (glReadPixels); NULL on a GL error. */
EMSCRIPTEN_KEEPALIVE unsigned char *sbfx_web_read_pixels(void)
{
    struct web_host *h = &host;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, h->out_framebuffer);
    glReadPixels(0, 0, h->width, h->height, GL_RGBA, GL_UNSIGNED_BYTE, h->pixels);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    return platform_gl_check("glReadPixels", h->message, sizeof(h->message)) ? NULL : h->pixels;
}

/* Sets off the effect number `effect` (sbfx_web_effect_name) where canvas pixel (x, y) shows the
 * ground, at the last frame's time; -ERANGE where it shows the sky. */
EMSCRIPTEN_KEEPALIVE int sbfx_web_trigger(double x, double y, int effect)
{
    struct web_host *h = &host;
    const char *name = sbfx_effect_name(h->fx, effect);
    if (!name) {
        snprintf(h->message, sizeof(h->message), "the scene has no effect number %d", effect);
        return -EINVAL;
    }
    float p[3];
    if (!web_pick_ground(&h->camera, h->sim_time, h->width, h->height, x, y, p)) {
        snprintf(h->message, sizeof(h->message), "no ground there: click below the horizon");
        return -ERANGE;
    }
    sbfx_result r = sbfx_trigger(h->fx, name, p);
    if (r != SBFX_OK) return fail(h, -EIO, "sbfx_trigger", r);
    memcpy(h->last_click, p, sizeof(p));
    if (h->click_count < WEB_MAX_CLICKS) {
        struct web_click *c = &h->clicks[h->click_count++];
        c->at = sbfx_elapsed(h->fx);
        memcpy(c->position, p, sizeof(p));
        snprintf(c->effect, sizeof(c->effect), "%s", name);
    }
    return 0;
}

EMSCRIPTEN_KEEPALIVE const char *sbfx_web_effect_name(int index) { return sbfx_effect_name(host.fx, index); }
EMSCRIPTEN_KEEPALIVE float sbfx_web_click_coordinate(int axis) { return host.last_click[axis % 3]; }

/* The ground point under the pixel (x, y) now, without setting anything off (NaN for the sky):
 * lets the page and its tests say where a click would land. */
EMSCRIPTEN_KEEPALIVE float sbfx_web_pick(double x, double y, int axis)
{
    float p[3];
    if (!web_pick_ground(&host.camera, host.sim_time, host.width, host.height, x, y, p)) return __builtin_nanf("");
    return p[axis % 3];
}

/* Where a world point is on the canvas now (pixels, y down): the page's tests aim with it. */
EMSCRIPTEN_KEEPALIVE float sbfx_web_project(float x, float y, float z, int axis)
{
    struct web_host *h = &host;
    float view[16], proj[16];
    test_scene_camera(&h->camera, h->sim_time, (float)h->width / (float)h->height, view, proj);
    const float p[4] = {x, y, z, 1.0f};
    float v[4], c[4];
    for (int r = 0; r < 4; r++) v[r] = view[r] * p[0] + view[4 + r] * p[1] + view[8 + r] * p[2] + view[12 + r] * p[3];
    for (int r = 0; r < 4; r++) c[r] = proj[r] * v[0] + proj[4 + r] * v[1] + proj[8 + r] * v[2] + proj[12 + r] * v[3];
    if (axis == 0) return (c[0] / c[3] * 0.5f + 0.5f) * (float)h->width;
    return (0.5f - c[1] / c[3] * 0.5f) * (float)h->height;
}

EMSCRIPTEN_KEEPALIVE const char *sbfx_web_stats(void)
{
    static char buf[2048];
    return web_stats_json(&host, buf, sizeof(buf));
}

EMSCRIPTEN_KEEPALIVE const char *sbfx_web_info(void)
{
    static char buf[2048];
    return web_info_json(&host, buf, sizeof(buf));
}
