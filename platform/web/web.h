/* sbfx in a browser (docs/web.md): a host like sbfx-play's headless display, driven by the
 * authoring page (web/index.html, web/app.js) through the functions below, which the WebGL 2
 * build exports to JavaScript (make web). The page owns the timeline: it asks for the frame at
 * a time t (seconds since the scene's timeline started); this host draws the test scene at t
 * (platform/host/test_scene.c, as the player does), advances sbfx to t, renders over it into an
 * RGBA8 framebuffer (the player's headless one) and copies that onto the canvas.
 *   web_host.c   the context, the module made from the scene text and the settings, the frame
 *   web_pick.c   a canvas pixel to the point of the ground (y = 0) it shows
 *   web_stats.c  the --stats counters and what WebGL 2 offers, as JSON for the page
 * Every function returns 0 or a negative errno-style code; sbfx_web_message() says why. */
#ifndef SBFX_WEB_H
#define SBFX_WEB_H

#include <stdbool.h>
#include <stddef.h>

#include "host/test_scene.h"
#include "sbfx.h"

#define WEB_MAX_CLICKS 64 /* ground clicks kept to be replayed after a scrub back or a new setting */

struct web_click {
    double at; /* sbfx_elapsed() when it was clicked */
    float position[3];
    char effect[32];
};

/* The page's quality settings: sbfx_desc's fields as sbfx-play's options set them (0: the
 * scene's, else the library's default). */
struct web_settings {
    int scale;          /* target_divisor: 0, 1, 2, 4, 8 */
    int opacity;        /* sbfx_opacity_mode */
    int format;         /* sbfx_target_format */
    int upsample;       /* sbfx_upsample */
    int tone_map;       /* sbfx_tone_map */
    float exposure;     /* 0: the scene's */
};

struct web_host {
    int context;                  /* EMSCRIPTEN_WEBGL_CONTEXT_HANDLE */
    int width, height;
    struct test_scene scene;
    bool scene_made;
    unsigned out_framebuffer, out_renderbuffer; /* RGBA8, as display_headless.c's */
    unsigned char *pixels;        /* sbfx_web_read_pixels: width * height * 4 */
    sbfx *fx;
    sbfx_scene *scene_text;       /* the scene the module plays (NULL: the built-in explosion) */
    sbfx_scene_camera camera;
    sbfx_scene_host daylight;
    struct web_settings settings;
    double sim_time;              /* the time sbfx was advanced to (the page's timeline) */
    struct web_click clicks[WEB_MAX_CLICKS];
    int click_count;
    float last_click[3];
    char message[1024];
};

struct web_host *web_host_get(void);

/* web_host.c: what the page calls (make web exports them; web/app.js says how it uses them) */
const char *sbfx_web_message(void);
int sbfx_web_start(const char *canvas, int width, int height);
int sbfx_web_resize(int width, int height);
int sbfx_web_load(const char *text, const char *name);
int sbfx_web_settings(int scale, int opacity, int format, int upsample, int tone_map, float exposure);
int sbfx_web_frame(double t);
unsigned char *sbfx_web_read_pixels(void);
int sbfx_web_trigger(double x, double y, int effect);
const char *sbfx_web_effect_name(int index);
float sbfx_web_click_coordinate(int axis);
float sbfx_web_pick(double x, double y, int axis);
float sbfx_web_project(float x, float y, float z, int axis);
const char *sbfx_web_stats(void);
const char *sbfx_web_info(void);

/* web_pick.c: the ground point (y = 0) seen at canvas pixel (x, y) (y down, as the page's
 * events give it) with this camera at time t; false when that pixel shows the sky. */
bool web_pick_ground(const sbfx_scene_camera *camera, double t, int width, int height, double x, double y,
                     float out[3]);

/* web_stats.c: the JSON objects sbfx_web_stats() and sbfx_web_info() return. */
const char *web_stats_json(struct web_host *h, char *buf, size_t size);
const char *web_info_json(struct web_host *h, char *buf, size_t size);

#endif
