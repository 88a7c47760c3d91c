/* One shot of an example scene for the look measurements: see look_render.h. */
#include "look_render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "internal.h" /* sbfx_media: the detail switched off without reloading */

int look_renderer_open(look_renderer *r, int width, int height, char *err, size_t n)
{
    memset(r, 0, sizeof(*r));
    r->width = width;
    r->height = height;
    if (test_scene_create(&r->scene, width, height, err, n) != 0) return -1;
    glGenRenderbuffers(1, &r->out_renderbuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, r->out_renderbuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glGenFramebuffers(1, &r->out_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, r->out_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->out_renderbuffer);
    bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    r->out_rgba = malloc((size_t)width * height * 4);
    r->background_rgba = malloc((size_t)width * height * 4);
    if (!complete || !r->out_rgba || !r->background_rgba) {
        snprintf(err, n, "%s", complete ? "out of memory" : "the RGBA8 output framebuffer is incomplete");
        look_renderer_close(r);
        return -1;
    }
    return 0;
}

void look_renderer_close(look_renderer *r)
{
    if (r->out_fbo) glDeleteFramebuffers(1, &r->out_fbo);
    if (r->out_renderbuffer) glDeleteRenderbuffers(1, &r->out_renderbuffer);
    if (r->scene.framebuffer) test_scene_destroy(&r->scene);
    free(r->out_rgba);
    free(r->background_rgba);
    memset(r, 0, sizeof(*r));
}

static void read_rgba8(GLuint fbo, int w, int h, uint8_t *out)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

static sbfx *create_module(const look_shot *shot, sbfx_scene **scene, char *err, size_t n)
{
    *scene = NULL;
    if (shot->scene_path && sbfx_scene_load(shot->scene_path, scene, err, n) != SBFX_OK) return NULL;
    sbfx_desc d = shot->base ? *shot->base : (sbfx_desc){0};
    d.scene = *scene;
    if (shot->divisor) d.target_divisor = shot->divisor;
    sbfx *fx = NULL;
    sbfx_result res = sbfx_create(&d, &fx);
    if (res != SBFX_OK) {
        snprintf(err, n, "sbfx_create(%s): %s", shot->scene_path ? shot->scene_path : "built-in",
                 fx ? sbfx_last_error(fx) : sbfx_result_string(res));
        sbfx_destroy(fx);
        return NULL;
    }
    if (shot->detail_off || shot->detail_unloaded)
        for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) sbfx_media(fx)[m].detail_strength = 0.0f;
    if (shot->fire_dark) sbfx_media(fx)[SBFX_FIRE].emission_scale = 0.0f; /* as tests/look/fire_look.c */
    if (shot->detail_unloaded && (res = sbfx_reload(fx)) != SBFX_OK) {
        snprintf(err, n, "sbfx_reload: %s", sbfx_last_error(fx));
        sbfx_destroy(fx);
        return NULL;
    }
    return fx;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

int look_render(look_renderer *r, const look_shot *shot, char *err, size_t n)
{
    sbfx_scene *scene;
    sbfx *fx = create_module(shot, &scene, err, n);
    if (!fx) {
        sbfx_scene_free(scene);
        return -1;
    }
    sbfx_scene_camera cam;
    sbfx_scene_camera_get(scene, &cam);
    sbfx_scene_free(scene);
    cam.azimuth += shot->azimuth_offset;
    sbfx_frame frame = {.scene_color_texture = r->scene.color_texture, .scene_depth_texture = r->scene.depth_texture,
                        .out_framebuffer = r->out_fbo, .width = r->width, .height = r->height};
    test_scene_camera(&cam, shot->t, (float)r->width / (float)r->height, frame.view, frame.projection);
    int rc = -1;
    if (test_scene_draw(&r->scene, frame.view, frame.projection) != 0) {
        snprintf(err, n, "drawing the test scene failed");
        goto done;
    }
    const double step = (double)(1.0f / 120.0f);
    while (sbfx_time(fx) < shot->t - 1e-9) sbfx_update(fx, step);
    double ms[32];
    int reps = shot->reps < 1 ? 1 : shot->reps > 32 ? 32 : shot->reps;
    sbfx_result res = SBFX_OK;
    for (int k = 0; k < reps && res == SBFX_OK; k++) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, r->scene.framebuffer);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r->out_fbo);
        glBlitFramebuffer(0, 0, r->width, r->height, 0, 0, r->width, r->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glFinish();
        double start = now_ms();
        res = sbfx_render(fx, &frame);
        glFinish();
        ms[k] = now_ms() - start;
    }
    for (int i = 1; i < reps; i++) /* insertion sort: the median */
        for (int j = i; j > 0 && ms[j] < ms[j - 1]; j--) {
            double t = ms[j];
            ms[j] = ms[j - 1];
            ms[j - 1] = t;
        }
    r->particle_ms = ms[reps / 2];
    if (res != SBFX_OK) {
        snprintf(err, n, "sbfx_render: %s", sbfx_last_error(fx));
        goto done;
    }
    read_rgba8(r->out_fbo, r->width, r->height, r->out_rgba);
    read_rgba8(r->scene.framebuffer, r->width, r->height, r->background_rgba);
    rc = glGetError() == GL_NO_ERROR ? 0 : -1;
    if (rc) snprintf(err, n, "GL error reading the shot back");
done:
    sbfx_destroy(fx);
    return rc;
}
