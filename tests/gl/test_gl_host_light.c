/* The host's scene lit and shaded by the effects, as sbfx-play draws it
 * (platform/player/host.c): the smoke's shadow map from the scene's sun (render.host_shadows) and the
 * fire's lights (render.host_lights) on the test scene. The numbers, measured on the
 * composited frame: a low sun's shadows darken at least 1 % of the frame by 5 % or more. */
#include "gl_fixture.h"
#include "host/test_scene.h"

#define W 320
#define H 180

typedef struct host_options { bool shadows, lights; } host_options;

/* What one frame shows: linear luminance of the composited frame and of the host's own scene
 * (before sbfx composites over it), and the camera that saw them. */
typedef struct host_picture {
    float frame[W * H], scene[W * H];
    float view[16], projection[16];
} host_picture;

static double srgb_to_linear(double v) { return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4); }

static void read_luminance(GLuint framebuffer, float *lum)
{
    static uint8_t rgba[W * H * 4];
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    for (int i = 0; i < W * H; i++) {
        const uint8_t *p = &rgba[4 * i];
        lum[i] = (float)(0.2126 * srgb_to_linear(p[0] / 255.0) + 0.7152 * srgb_to_linear(p[1] / 255.0) +
                         0.0722 * srgb_to_linear(p[2] / 255.0));
    }
}

/* The frame at time t of scenes/NAME.cfg from the scene file's camera: sbfx composited over the
 * test scene, lit and shaded as sbfx-play does (platform/player/host.c) where the options say so. */
static void host_frame(gl_fixture *f, const char *name, double t, host_options o, host_picture *out)
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
    if (o.lights) {
        sbfx_point_light lights[SBFX_MAX_POINT_LIGHTS];
        int n = sbfx_emitted_lights(fx, lights, SBFX_MAX_POINT_LIGHTS);
        CHECK(n >= 0, "%s", sbfx_last_error(fx));
        test_scene_set_point_lights(&ts, lights, n);
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
    read_luminance(f->out_fbo, out->frame);
    read_luminance(ts.framebuffer, out->scene);
    memcpy(out->view, frame.view, sizeof(out->view));
    memcpy(out->projection, frame.projection, sizeof(out->projection));
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
    static host_picture on, off;
    const double t = 2.0;
    host_frame(&f, "dust-storm", t, (host_options){.shadows = true}, &on);
    host_frame(&f, "dust-storm", t, (host_options){.shadows = false}, &off);
    double share = darkened(on.frame, off.frame, 0.05), brighter = darkened(off.frame, on.frame, 0.01);
    printf("# dust-storm.cfg at %.1f s (sun 30 degrees high): host_shadows darkens %.2f %% of the frame by 5 %% or "
           "more; brightens %.2f %% by 1 %%\n", t, 100.0 * share, 100.0 * brighter);
    CHECK(share >= 0.01, "only %.2f %% of the frame darkened by 5 %%", 100.0 * share);
    CHECK(brighter == 0.0, "a shadow brightened %.2f %% of the frame", 100.0 * brighter);
    fixture_close(&f);
}

/* Mean luminance of the host's ground over a patch 2.2 .. 3.2 m from the explosion towards the
 * camera (night.cfg's camera: azimuth 25 degrees), clear of the boxes. */
static double ground_in_front(const host_picture *p)
{
    const double a = 25.0 * M_PI / 180.0, toward[2] = {sin(a), cos(a)}, side[2] = {cos(a), -sin(a)};
    double sum = 0.0;
    int n = 0;
    for (double s = 2.2; s <= 3.2 + 1e-9; s += 0.1)
        for (double u = -0.75; u <= 0.25 + 1e-9; u += 0.1) {
            float world[4] = {(float)(s * toward[0] + u * side[0]), 0.0f, (float)(s * toward[1] + u * side[1]), 1.0f};
            float v[4] = {0}, c[4] = {0};
            for (int r = 0; r < 4; r++)
                for (int k = 0; k < 4; k++) v[r] += p->view[k * 4 + r] * world[k];
            for (int r = 0; r < 4; r++)
                for (int k = 0; k < 4; k++) c[r] += p->projection[k * 4 + r] * v[k];
            int x = (int)((c[0] / c[3] * 0.5f + 0.5f) * W), y = (int)((c[1] / c[3] * 0.5f + 0.5f) * H);
            if (x < 0 || y < 0 || x >= W || y >= H) continue;
            sum += p->scene[y * W + x];
            n++;
        }
    CHECK(n > 50, "only %d ground samples in the frame", n);
    return sum / (n > 0 ? n : 1);
}

/* The night scene's flash lights the ground: with host_lights, the ground in front of the
 * explosion is at least twice as bright at the flash as without; before the explosion the
 * lights change nothing. */
CHECK_TEST(the_night_flash_lights_the_ground)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    static host_picture lit, unlit;
    const double times[] = {0.2, 0.6, 1.0, 1.6}; /* the explosion fires at 0.4 s */
    for (size_t i = 0; i < ARRAY_SIZE(times); i++) {
        host_frame(&f, "night", times[i], (host_options){.shadows = true, .lights = true}, &lit);
        host_frame(&f, "night", times[i], (host_options){.shadows = true, .lights = false}, &unlit);
        double with = ground_in_front(&lit), without = ground_in_front(&unlit);
        printf("# night.cfg at %.1f s: ground in front of the explosion %.4f with host_lights, %.4f without (x%.2f)\n",
               times[i], with, without, with / without);
        if (times[i] < 0.4) CHECK(with == without, "lights before the explosion: %g vs %g", with, without);
        if (times[i] == 0.6) CHECK(with >= 2.0 * without, "at the flash only x%.2f", with / without);
    }
    fixture_close(&f);
}

/* What night.cfg says to its host: its own daylight (sky given), the moon as the sun, exposure 2,
 * both host_lights and host_shadows; a scene without `sky` keeps the host's daylight. */
CHECK_TEST(the_scene_file_describes_the_hosts_light)
{
    sbfx_scene *scene = fixture_load_scene("night");
    sbfx_scene_host host;
    CHECK(sbfx_scene_host_get(scene, &host));
    CHECK(host.host_lights && host.host_shadows && host.has_sun && host.exposure == 2.0f);
    CHECK(host.sky[2] == 0.014f && host.ambient[2] == 0.022f && host.sun_color[2] == 0.055f,
          "sky %g ambient %g moon %g", host.sky[2], host.ambient[2], host.sun_color[2]);
    double len = sqrt(0.35 * 0.35 + 0.6 * 0.6 + 0.7 * 0.7);
    CHECK_NEAR(host.sun_direction[1], -0.6 / len, 1e-6);
    sbfx_scene_free(scene);
    scene = fixture_load_scene("post");
    CHECK(!sbfx_scene_host_get(scene, &host));
    CHECK(!host.host_lights && !host.host_shadows && !host.has_sky && host.has_sun && host.exposure == 1.0f);
    sbfx_scene_free(scene);
    CHECK(!sbfx_scene_host_get(NULL, &host) && !host.has_sun && host.exposure == 1.0f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
