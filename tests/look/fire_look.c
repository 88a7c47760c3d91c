/* fire_look.h */
#include "fire_look.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "internal.h"

int fire_look_open(fire_look *l, int width, int height, char *err, size_t n)
{
    memset(l, 0, sizeof(*l));
    l->width = width, l->height = height;
    size_t bytes = (size_t)width * height * 4;
    l->out = malloc(bytes), l->background = malloc(bytes), l->no_fire = malloc(bytes);
    l->fire_mask = malloc((size_t)width * height);
    if (!l->out || !l->background || !l->no_fire || !l->fire_mask) {
        snprintf(err, n, "out of memory");
        return -1;
    }
    if (test_scene_create(&l->scene, width, height, err, n) != 0) return -1;
    glGenRenderbuffers(1, &l->renderbuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, l->renderbuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glGenFramebuffers(1, &l->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, l->fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, l->renderbuffer);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(err, n, "RGBA8 framebuffer incomplete (0x%x)", status);
        return -1;
    }
    return 0;
}

void fire_look_close(fire_look *l)
{
    if (l->fbo) glDeleteFramebuffers(1, &l->fbo);
    if (l->renderbuffer) glDeleteRenderbuffers(1, &l->renderbuffer);
    if (l->scene.framebuffer) test_scene_destroy(&l->scene);
    free(l->out), free(l->background), free(l->no_fire), free(l->fire_mask);
    memset(l, 0, sizeof(*l));
}

/* The scene's picture into the display framebuffer, sbfx over it (fx NULL: nothing), read back. */
static int composite(fire_look *l, sbfx *fx, const sbfx_frame *frame, uint8_t *out, char *err, size_t n)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, l->scene.framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, l->fbo);
    glBlitFramebuffer(0, 0, l->width, l->height, 0, 0, l->width, l->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (fx && sbfx_render(fx, frame) != SBFX_OK) {
        snprintf(err, n, "sbfx_render: %s", sbfx_last_error(fx));
        return -1;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, l->fbo);
    glReadPixels(0, 0, l->width, l->height, GL_RGBA, GL_UNSIGNED_BYTE, out);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        snprintf(err, n, "GL error 0x%x while compositing", e);
        return -1;
    }
    return 0;
}

static sbfx *create_at(const sbfx_scene *scene, sbfx_tone_map op, int scale, double t, char *err, size_t n)
{
    sbfx *fx = NULL;
    sbfx_desc desc = {.scene = scene, .tone_map = op, .target_divisor = scale};
    sbfx_result res = sbfx_create(&desc, &fx);
    if (res != SBFX_OK) {
        snprintf(err, n, "sbfx_create: %s", sbfx_result_string(res));
        return NULL;
    }
    const double step = (double)(1.0f / 120.0f);
    while (sbfx_time(fx) < t - 1e-9) sbfx_update(fx, step);
    return fx;
}

int fire_look_measure(fire_look *l, const sbfx_scene *scene, sbfx_tone_map op, double t, int scale,
                      int use_fire_mask, fire_ratios *r, char *err, size_t n)
{
    sbfx_scene_camera camera;
    sbfx_scene_camera_get(scene, &camera);
    sbfx_frame frame = {.scene_color_texture = l->scene.color_texture, .scene_depth_texture = l->scene.depth_texture,
                        .out_framebuffer = l->fbo, .width = l->width, .height = l->height};
    test_scene_camera(&camera, t, (float)l->width / (float)l->height, frame.view, frame.projection);
    if (test_scene_draw(&l->scene, frame.view, frame.projection) != 0) {
        snprintf(err, n, "test scene: GL error");
        return -1;
    }
    sbfx *fx = create_at(scene, op, scale, t, err, n), *dark = fx ? create_at(scene, op, scale, t, err, n) : NULL;
    int rc = fx && dark ? 0 : -1;
    if (dark) sbfx_media(dark)[SBFX_FIRE].emission_scale = 0.0f; /* the same particles, no emission */
    if (rc == 0) rc = composite(l, fx, &frame, l->out, err, n);
    if (rc == 0) rc = composite(l, dark, &frame, l->no_fire, err, n);
    if (rc == 0) rc = composite(l, NULL, &frame, l->background, err, n);
    if (fx) sbfx_destroy(fx);
    if (dark) sbfx_destroy(dark);
    if (rc != 0) return -1;
    fire_metric_mask(l->out, l->no_fire, l->width, l->height, l->fire_mask);
    if (fire_metric_ratios(l->out, l->background, use_fire_mask ? l->fire_mask : NULL, l->width, l->height, r) != 0)
        snprintf(err, n, "no fire pixels at %.2f s", t);
    return 0;
}
