/* The host's scene lit and shaded by the effects, as sbfx-play draws it (platform/player/
 * player_host.c): the smoke's shadow map from the scene's sun (render.host_shadows) and the
 * fire's lights (render.host_lights) on the test scene. The numbers, measured on the
 * composited frame: a low sun's shadows darken at least 1 % of the frame by 5 % or more. */
#include "gl_fixture.h"
#include "host/test_scene.h"

#define W 320
#define H 180

typedef struct host_options { bool shadows; } host_options;

static double srgb_to_linear(double v) { return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4); }

/* Linear Rec. 709 luminance of the frame at time t of scenes/NAME.cfg, the scene file's
 * camera, sbfx composited over the test scene. */
static void host_frame(gl_fixture *f, const char *name, double t, host_options o, float *lum)
{
    char err[256];
    sbfx_scene *scene = fixture_load_scene(name);
    sbfx_scene_host host;
    sbfx_scene_host_get(scene, &host);
    sbfx_scene_camera camera;
    sbfx_scene_camera_get(scene, &camera);
    sbfx *fx = fixture_module(f, (sbfx_desc){.scene = scene});
    sbfx_scene_free(scene);
    struct test_scene ts;
    CHECK(test_scene_create(&ts, W, H, err, sizeof(err)) == 0, "%s", err);
    for (double done = 0.0; done < t - 1e-9; done += 0.125) CHECK(sbfx_update(fx, fmin(0.125, t - done)) == SBFX_OK);
    test_scene_set_daylight(&ts, &host);
    if (o.shadows) {
        sbfx_shadow_map map;
        CHECK(sbfx_render_shadow_map(fx, host.sun_direction, &map) == SBFX_OK, "%s", sbfx_last_error(fx));
        test_scene_set_shadow(&ts, map.texture, map.view_projection);
    }
    sbfx_frame frame = f->frame;
    test_scene_camera(&camera, t, (float)W / H, frame.view, frame.projection);
    CHECK(test_scene_draw(&ts, frame.view, frame.projection) == 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, ts.framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, f->out_fbo);
    glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    frame.scene_color_texture = ts.color_texture;
    frame.scene_depth_texture = ts.depth_texture;
    CHECK(sbfx_render(fx, &frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    static uint8_t rgba[W * H * 4];
    glBindFramebuffer(GL_READ_FRAMEBUFFER, f->out_fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    for (int i = 0; i < W * H; i++) {
        const uint8_t *p = &rgba[4 * i];
        lum[i] = (float)(0.2126 * srgb_to_linear(p[0] / 255.0) + 0.7152 * srgb_to_linear(p[1] / 255.0) +
                         0.0722 * srgb_to_linear(p[2] / 255.0));
    }
    test_scene_destroy(&ts);
    sbfx_destroy(fx);
}

/* Fraction of the frame that `with` darkens by at least `by` (relative) against `without`. */
static double darkened(const float *with, const float *without, double by)
{
    int n = 0;
    for (int i = 0; i < W * H; i++) n += with[i] <= (1.0 - by) * without[i];
    return (double)n / (W * H);
}

CHECK_TEST(a_low_sun_casts_the_dust_storms_shadow)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    static float on[W * H], off[W * H];
    const double t = 2.0;
    host_frame(&f, "dust-storm", t, (host_options){.shadows = true}, on);
    host_frame(&f, "dust-storm", t, (host_options){.shadows = false}, off);
    double share = darkened(on, off, 0.05), brighter = darkened(off, on, 0.01);
    printf("# dust-storm.cfg at %.1f s (sun 30 degrees high): host_shadows darkens %.2f %% of the frame by 5 %% or "
           "more; brightens %.2f %% by 1 %%\n", t, 100.0 * share, 100.0 * brighter);
    CHECK(share >= 0.01, "only %.2f %% of the frame darkened by 5 %%", 100.0 * share);
    CHECK(brighter == 0.0, "a shadow brightened %.2f %% of the frame", 100.0 * brighter);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
