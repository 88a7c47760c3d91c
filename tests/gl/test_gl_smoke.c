/* The GL smoke test of `make check` (tests/run.sh --check): every pass of a frame runs once,
 * small and fast, on each example scene that needs it, from the scene's own camera over the
 * test scene. Per pass: the frame renders, the pass ran (sbfx_stats' pass and draw counts),
 * the particle target is finite and the picture changed where the particles are. The passes:
 *   explosion   depth, (RGBA32F devices) low-res corners, particles, composite
 *   campfire    + heat shimmer in the composite (its float target)
 *   lit-smoke   the lit smoke's ray march
 *   post        + velocity motion blur and depth of field (post.c's steps)
 * What each pass must compute is tested elsewhere (test_gl_hard_cases, test_gl_post, test_gl_lit...);
 * this only catches an edit that breaks a pass outright, in seconds. */
#include "gl_fixture.h"
#include "host/test_scene.h"

#define W 96
#define H 54
#define SECONDS 1.2

typedef struct smoke_result {
    sbfx_counters counters;
    int changed;  /* output pixels that differ from the host's scene */
    bool finite;  /* the particle target */
} smoke_result;

/* The scene `name` for SECONDS of its own timeline, then one frame over the test scene. */
static smoke_result render_scene(const char *name)
{
    smoke_result out = {.finite = true};
    gl_fixture f;
    fixture_open(&f, W, H);
    char err[256];
    struct test_scene host;
    CHECK(test_scene_create(&host, W, H, err, sizeof(err)) == 0, "%s", err);
    sbfx_scene *scene = fixture_load_scene(name);
    sbfx_scene_camera camera;
    bool has_camera = sbfx_scene_camera_get(scene, &camera);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.scene = scene});
    sbfx_scene_free(scene);
    while (sbfx_time(fx) < SECONDS) CHECK(sbfx_update(fx, 1.0 / 30) == SBFX_OK);
    if (has_camera) test_scene_camera(&camera, SECONDS, (float)W / H, f.frame.view, f.frame.projection);
    else test_scene_orbit_camera(SECONDS, (float)W / H, f.frame.view, f.frame.projection);
    CHECK(test_scene_draw(&host, f.frame.view, f.frame.projection) == 0);
    static uint8_t before[W * H * 4], after[W * H * 4];
    /* the host's picture in the output, as a host composites over its own frame */
    glBindFramebuffer(GL_READ_FRAMEBUFFER, host.framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, f.out_fbo);
    glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, before);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    f.frame.scene_color_texture = host.color_texture;
    f.frame.scene_depth_texture = host.depth_texture;
    CHECK(sbfx_render(fx, &f.frame) == SBFX_OK, "%s: %s", name, sbfx_last_error(fx));
    sbfx_stats(fx, &out.counters);
    glBindFramebuffer(GL_FRAMEBUFFER, f.out_fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, after);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    for (int i = 0; i < W * H; i++)
        out.changed += abs(after[4 * i] - before[4 * i]) + abs(after[4 * i + 1] - before[4 * i + 1]) +
                           abs(after[4 * i + 2] - before[4 * i + 2]) > 3;
    int tw, th;
    float *target = fixture_read_target(fx, &tw, &th);
    out.finite = all_finite(target, 4u * (size_t)tw * th);
    free(target);
    printf("# %s: %d passes, %d draw calls, %d of %d pixels changed, %d particles\n", name, out.counters.passes,
           out.counters.draw_calls, out.changed, W * H, out.counters.particles_alive);
    CHECK(out.counters.particles_alive > 0, "%s: no particle alive after %.1f s", name, SECONDS);
    CHECK(out.finite, "%s: the particle target holds a NaN or an infinity", name);
    CHECK(out.changed > 0, "%s: the particles changed no pixel", name);
    CHECK(glGetError() == GL_NO_ERROR);
    sbfx_destroy(fx);
    test_scene_destroy(&host);
    fixture_close(&f);
    return out;
}

CHECK_TEST(particles_and_composite)
{
    smoke_result r = render_scene("explosion");
    CHECK(r.counters.passes >= 3 && r.counters.draw_calls >= 3, "%d passes, %d draws", r.counters.passes,
          r.counters.draw_calls);
}

CHECK_TEST(heat_shimmer)
{
    smoke_result r = render_scene("campfire");
    CHECK(r.counters.passes >= 3, "%d passes", r.counters.passes);
}

CHECK_TEST(lit_smoke)
{
    smoke_result r = render_scene("lit-smoke");
    CHECK(r.counters.passes >= 3, "%d passes", r.counters.passes);
}

/* the post steps are passes of their own: more than the explosion alone runs */
CHECK_TEST(motion_blur_and_depth_of_field)
{
    smoke_result plain = render_scene("explosion");
    smoke_result post = render_scene("post");
    CHECK(post.counters.passes > plain.counters.passes, "post: %d passes, the explosion alone %d",
          post.counters.passes, plain.counters.passes);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
