/* sbfx_restart and sbfx_idle (issue 34: what a stream's host needs). A module restarted after
 * frames renders, bit for bit, the frames a module just created renders; the restart compiles
 * nothing and makes no target; a restart that fails leaves the module as it was, clock
 * included. sbfx_idle says exactly when sbfx_render would make no pass. */
#include "gl_fixture.h"

#define WIDTH 96
#define HEIGHT 64
#define FRAMES 12

static void look_at_origin(gl_fixture *f)
{
    const float eye[3] = {0.0f, 2.0f, 9.0f}, target[3] = {0.0f, 1.5f, 0.0f}, up[3] = {0.0f, 1.0f, 0.0f};
    sbfx_look_at(f->frame.view, eye, target, up);
}

/* One frame: the output cleared to grey, updated by 1/12 s (not for frame 0), rendered, read. */
static void frame(gl_fixture *f, sbfx *fx, int i, uint8_t *pixels)
{
    if (i > 0) CHECK(sbfx_update(fx, 1.0 / 12.0) == SBFX_OK, "%s", sbfx_last_error(fx));
    glBindFramebuffer(GL_FRAMEBUFFER, f->out_fbo);
    glClearColor(0.3f, 0.35f, 0.4f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    CHECK(sbfx_render(fx, &f->frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    glBindFramebuffer(GL_FRAMEBUFFER, f->out_fbo);
    glReadPixels(0, 0, WIDTH, HEIGHT, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

static size_t frame_bytes(void) { return (size_t)WIDTH * HEIGHT * 4; }

CHECK_TEST(restarted_module_renders_the_frames_of_a_new_one)
{
    gl_fixture f;
    fixture_open_far(&f, WIDTH, HEIGHT);
    look_at_origin(&f);
    sbfx_scene *scene = fixture_load_scene("explosion");
    uint8_t *fresh = malloc(frame_bytes() * FRAMES), *again = malloc(frame_bytes() * FRAMES);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.scene = scene});
    for (int i = 0; i < FRAMES; i++) frame(&f, fx, i, fresh + i * frame_bytes());
    sbfx_destroy(fx);

    fx = fixture_module(&f, (sbfx_desc){.scene = scene});
    for (int i = 0; i < 7; i++) frame(&f, fx, i, again); /* half-way through the explosion */
    sbfx_counters before;
    sbfx_stats(fx, &before);
    CHECK(before.particles_alive > 0, "the explosion is live before the restart");
    CHECK(sbfx_restart(fx, scene) == SBFX_OK, "%s", sbfx_last_error(fx));
    sbfx_counters after;
    sbfx_stats(fx, &after);
    CHECK(sbfx_elapsed(fx) == 0.0 && after.particles_alive == 0, "elapsed %g, %d particles after the restart",
          sbfx_elapsed(fx), after.particles_alive);
    CHECK(after.programs_compiled == before.programs_compiled && after.targets_created == before.targets_created,
          "the restart compiled %d programs and made %d targets", after.programs_compiled - before.programs_compiled,
          after.targets_created - before.targets_created);
    int differing = 0, first = -1;
    for (int i = 0; i < FRAMES; i++) {
        frame(&f, fx, i, again + i * frame_bytes());
        if (memcmp(fresh + i * frame_bytes(), again + i * frame_bytes(), frame_bytes()) != 0) {
            differing++;
            if (first < 0) first = i;
        }
    }
    CHECK(differing == 0, "%d of %d frames after the restart differ from a new module's (first: frame %d)", differing,
          FRAMES, first);
    CHECK(glGetError() == GL_NO_ERROR);
    sbfx_destroy(fx);
    sbfx_scene_free(scene);
    free(fresh);
    free(again);
    fixture_close(&f);
}

CHECK_TEST(failed_restart_leaves_the_module_as_it_was)
{
    gl_fixture f;
    fixture_open_far(&f, WIDTH, HEIGHT);
    look_at_origin(&f);
    uint8_t *pixels = malloc(frame_bytes());
    sbfx *fx = fixture_module(&f, (sbfx_desc){0}); /* the built-in explosion, at t = 0 */
    for (int i = 0; i < 5; i++) frame(&f, fx, i, pixels);
    double elapsed = sbfx_elapsed(fx);
    sbfx_counters before;
    sbfx_stats(fx, &before);
    /* lit smoke needs a program the built-in explosion has not: its build fails (injected) */
    sbfx_scene *lit = fixture_load_scene("lit-smoke");
    setenv("SBFX_INJECT_SHADER_FAILURE", "LIGHTING_LIT", 1);
    sbfx_result r = sbfx_restart(fx, lit);
    unsetenv("SBFX_INJECT_SHADER_FAILURE");
    CHECK(r == SBFX_ERR_SHADER, "sbfx_restart: %s", sbfx_result_string(r));
    sbfx_counters after;
    sbfx_stats(fx, &after);
    CHECK(sbfx_elapsed(fx) == elapsed && after.particles_alive == before.particles_alive,
          "elapsed %g -> %g, particles %d -> %d", elapsed, sbfx_elapsed(fx), before.particles_alive,
          after.particles_alive);
    frame(&f, fx, 5, pixels);
    CHECK(glGetError() == GL_NO_ERROR);
    sbfx_scene_free(lit);
    sbfx_destroy(fx);
    free(pixels);
    fixture_close(&f);
}

/* sbfx_idle before each render, against the passes that render made. */
static void idle_follows_passes(gl_fixture *f, sbfx *fx, int frames, int *idle_frames, int *busy_frames)
{
    uint8_t *pixels = malloc(frame_bytes());
    for (int i = 0; i < frames; i++) {
        if (i > 0) CHECK(sbfx_update(fx, 0.25) == SBFX_OK, "%s", sbfx_last_error(fx));
        bool idle = sbfx_idle(fx);
        CHECK(sbfx_render(fx, &f->frame) == SBFX_OK, "%s", sbfx_last_error(fx));
        sbfx_counters c;
        sbfx_stats(fx, &c);
        CHECK(idle == (c.passes == 0), "frame %d: sbfx_idle %d, %d passes", i, idle, c.passes);
        *(idle ? idle_frames : busy_frames) += 1;
    }
    free(pixels);
}

CHECK_TEST(idle_is_true_exactly_when_render_makes_no_pass)
{
    gl_fixture f;
    fixture_open_far(&f, WIDTH, HEIGHT);
    look_at_origin(&f);
    CHECK(sbfx_idle(NULL), "a NULL module is idle");
    sbfx_scene *scene = fixture_load_scene("explosion");
    sbfx *fx = fixture_module(&f, (sbfx_desc){.scene = scene});
    int idle = 0, busy = 0;
    idle_follows_passes(&f, fx, 24, &idle, &busy); /* 6 s: before, during and after the explosion */
    CHECK(idle >= 2 && busy >= 2, "%d idle and %d busy frames", idle, busy);
    sbfx_destroy(fx);
    sbfx_scene_free(scene);

    /* post effects pass every frame, with or without particles */
    scene = fixture_load_scene("post");
    fx = fixture_module(&f, (sbfx_desc){.scene = scene, .ignore_timeline = true});
    GLuint color = 0, color_fbo = 0;
    fixture_rgba8_target(WIDTH, HEIGHT, &color, &color_fbo); /* post effects need a scene colour */
    f.frame.scene_color_texture = color;
    CHECK(!sbfx_idle(fx), "a scene with post effects is idle");
    idle = busy = 0;
    idle_follows_passes(&f, fx, 3, &idle, &busy);
    CHECK(idle == 0, "%d idle frames with post effects", idle);
    sbfx_destroy(fx);
    glDeleteFramebuffers(1, &color_fbo);
    glDeleteTextures(1, &color);
    sbfx_scene_free(scene);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
