/* A clock that can start anywhere (issue 13, DESIGN §7): a module whose clock starts a year in
 * (desc.start_time = 31536000 s, a whole number of the 4 s detail loop and of the example
 * orbits) renders the frames a module starting at 0 renders, within one 8-bit level, for the
 * explosion and the lit-smoke scenes over the player's test scene; a start that is not such a
 * multiple renders what its remainder renders, finite everywhere. */
#include "gl_fixture.h"
#include "host/test_scene.h"

#define YEAR 31536000.0
#define WIDTH 192
#define HEIGHT 108
#define FRAMES 9
#define FRAME_DT 0.25 /* s: 0 .. 2 s, the explosion's whole life (and at most what one update takes) */

typedef struct clock_run {
    uint8_t *frames[FRAMES];
    int particles_skipped, particles_seen;
    bool target_finite;
} clock_run;

/* Renders FRAMES frames of `scene_name` over the test scene, the camera following the time
 * since the start (as sbfx-play does), the module's clock starting at `start`. */
static void render_run(gl_fixture *f, struct test_scene *host, const char *scene_name, double start, clock_run *out)
{
    sbfx_scene *scene = fixture_load_scene(scene_name);
    sbfx_scene_camera camera;
    sbfx_scene_camera_get(scene, &camera);
    sbfx *fx = fixture_module(f, (sbfx_desc){.scene = scene, .start_time = start});
    sbfx_scene_free(scene);
    memset(out, 0, sizeof(*out));
    out->target_finite = true;
    sbfx_frame frame = {.scene_color_texture = host->color_texture, .scene_depth_texture = host->depth_texture,
                        .out_framebuffer = f->out_fbo, .width = WIDTH, .height = HEIGHT};
    for (int i = 0; i < FRAMES; i++) {
        double since_start = i * FRAME_DT;
        if (i > 0) CHECK(sbfx_update(fx, FRAME_DT) == SBFX_OK, "%s", sbfx_last_error(fx));
        CHECK(fabs(sbfx_elapsed(fx) - since_start) < 0.01 && sbfx_time(fx) == start + sbfx_elapsed(fx),
              "clock %.9f, elapsed %.9f at frame %d", sbfx_time(fx), sbfx_elapsed(fx), i);
        test_scene_camera(&camera, since_start, (float)WIDTH / HEIGHT, frame.view, frame.projection);
        CHECK(test_scene_draw(host, frame.view, frame.projection) == 0);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, host->framebuffer);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, f->out_fbo);
        glBlitFramebuffer(0, 0, WIDTH, HEIGHT, 0, 0, WIDTH, HEIGHT, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        CHECK(sbfx_render(fx, &frame) == SBFX_OK, "%s", sbfx_last_error(fx));
        sbfx_counters c;
        sbfx_stats(fx, &c);
        out->particles_skipped += c.particles_skipped;
        out->particles_seen += c.particles_alive;
        if (c.particles_alive > 0) {
            int tw = 0, th = 0;
            float *target = fixture_read_target(fx, &tw, &th);
            out->target_finite = out->target_finite && all_finite(target, (size_t)tw * th * 4);
            free(target);
        }
        out->frames[i] = malloc((size_t)WIDTH * HEIGHT * 4);
        glBindFramebuffer(GL_FRAMEBUFFER, f->out_fbo);
        glReadPixels(0, 0, WIDTH, HEIGHT, GL_RGBA, GL_UNSIGNED_BYTE, out->frames[i]);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    CHECK(glGetError() == GL_NO_ERROR);
    sbfx_destroy(fx);
}

static void free_run(clock_run *r)
{
    for (int i = 0; i < FRAMES; i++) free(r->frames[i]);
}

static int max_difference(const uint8_t *a, const uint8_t *b)
{
    int worst = 0;
    for (size_t i = 0; i < (size_t)WIDTH * HEIGHT * 4; i++) {
        int d = abs((int)a[i] - (int)b[i]);
        if (d > worst) worst = d;
    }
    return worst;
}

static void open_host(gl_fixture *f, struct test_scene *host)
{
    char err[512];
    fixture_open(f, WIDTH, HEIGHT);
    CHECK(test_scene_create(host, WIDTH, HEIGHT, err, sizeof(err)) == 0, "%s", err);
}

static void close_host(gl_fixture *f, struct test_scene *host)
{
    test_scene_destroy(host);
    fixture_close(f);
}

/* Runs from `a` and from `b` agree within one level on every frame, and the frames change
 * over time (the comparison is not of empty pictures). */
static void compare_starts(const char *scene, double a, double b)
{
    gl_fixture f;
    struct test_scene host;
    open_host(&f, &host);
    clock_run ra, rb;
    render_run(&f, &host, scene, a, &ra);
    render_run(&f, &host, scene, b, &rb);
    int worst = 0, moving = 0;
    for (int i = 0; i < FRAMES; i++) {
        int d = max_difference(ra.frames[i], rb.frames[i]);
        CHECK(d <= 1, "%s: frame %d (t = %.1f s) from start %.2f differs from start %.2f by %d levels", scene, i,
              i * FRAME_DT, b, a, d);
        if (d > worst) worst = d;
        if (i > 0) {
            int m = max_difference(ra.frames[i], ra.frames[i - 1]);
            if (m > moving) moving = m;
        }
    }
    printf("# %s: start %.2f vs %.2f: largest difference %d levels over %d frames (frames change by up to %d)\n",
           scene, b, a, worst, FRAMES, moving);
    CHECK(moving > 16, "%s: the frames hardly change (%d levels): nothing was compared", scene, moving);
    CHECK(ra.particles_seen > 0 && rb.particles_seen > 0, "%s: no particles", scene);
    CHECK(ra.particles_skipped == 0 && rb.particles_skipped == 0, "%s: %d / %d particles skipped (NaN)", scene,
          ra.particles_skipped, rb.particles_skipped);
    CHECK(ra.target_finite && rb.target_finite, "%s: the particle target holds NaN or Inf", scene);
    free_run(&ra);
    free_run(&rb);
    close_host(&f, &host);
}

CHECK_TEST(explosion_a_year_in_renders_as_from_zero) { compare_starts("explosion", 0.0, YEAR); }

CHECK_TEST(lit_smoke_a_year_in_renders_as_from_zero) { compare_starts("lit-smoke", 0.0, YEAR); }

/* A start that is no multiple of the loops: the same frames as a start at its remainder (the
 * detail loop and lit-smoke's 4 s orbit), finite everywhere; also a clock 30 years in. */
CHECK_TEST(odd_start_renders_as_its_remainder)
{
    compare_starts("lit-smoke", 1.375, YEAR + 1.375);
    compare_starts("explosion", 2.9, 30 * YEAR + 2.9);
}

CHECK_TEST(start_time_is_validated)
{
    gl_fixture f;
    fixture_open(&f, 16, 16);
    const double bad[] = {-1.0, NAN, INFINITY, 2e10};
    for (size_t i = 0; i < ARRAY_SIZE(bad); i++) {
        sbfx *fx = NULL;
        sbfx_result r = sbfx_create(&(sbfx_desc){.start_time = bad[i]}, &fx);
        CHECK(r == SBFX_ERR_INVALID_ARGUMENT && !fx, "start_time %g was accepted (%s)", bad[i], sbfx_result_string(r));
        if (fx) sbfx_destroy(fx);
    }
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
