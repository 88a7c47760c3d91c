/* A host's pending GL error is not sbfx's failure (issue 18; include/sbfx.h, "GL errors the host
 * left pending"). A host leaves an error pending before every call — create, set_quality,
 * trigger, update, push_slice, render (first frame, live, idle), destroy — as Qt 6.4 does with
 * GL_INVALID_OPERATION each frame. Every call must succeed, draw the picture a clean host gets,
 * and hand the error back: still pending afterwards (posted again, or never read), and nothing
 * else pending. GL_INVALID_FRAMEBUFFER_OPERATION cannot be posted again: the calls that read
 * errors drop it, the others leave it. */
#include "gl_fixture.h"
#include "host/test_scene.h"

#define W 96
#define H 64

/* The host's mistakes, each made with GL calls that fail and change nothing else. */
static GLuint incomplete_fbo;

static void leave_error(GLenum e)
{
    GLint draw = 0;
    switch (e) {
    case GL_INVALID_ENUM: glBindTexture(0x1234, 0); break;
    case GL_INVALID_VALUE: glVertexAttrib4f(100000, 0, 0, 0, 1); break;
    case GL_INVALID_OPERATION: glBindVertexArray(987654); break;
    case GL_INVALID_FRAMEBUFFER_OPERATION:
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, incomplete_fbo);
        glClear(GL_COLOR_BUFFER_BIT);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)draw);
        break;
    default: break;
    }
}

typedef struct host {
    gl_fixture gl;
    struct test_scene scene;
    GLuint out_texture[2], out_fbo[2];
    GLenum error;
} host;

/* What must be pending after a call that was made with h->error pending: the error itself,
 * unless the call reads errors and GL cannot post this one again; then nothing more. */
static void check_handed_back(const host *h, const char *what, bool reads_errors)
{
    bool repostable = h->error != GL_INVALID_FRAMEBUFFER_OPERATION;
    GLenum want = reads_errors && !repostable ? GL_NO_ERROR : h->error;
    GLenum got = glGetError();
    CHECK(got == want, "%s with 0x%04x pending: 0x%04x pending afterwards, expected 0x%04x", what, h->error, got,
          want);
    GLenum more = glGetError();
    CHECK(more == GL_NO_ERROR, "%s: 0x%04x pending as well", what, more);
}

static void make_output(host *h, int i)
{
    fixture_rgba8_target(W, H, &h->out_texture[i], &h->out_fbo[i]);
}

static void host_open(host *h, GLenum error)
{
    memset(h, 0, sizeof(*h));
    fixture_open(&h->gl, W, H);
    char err[256];
    CHECK(test_scene_create(&h->scene, W, H, err, sizeof(err)) == 0, "%s", err);
    h->gl.frame.scene_color_texture = h->scene.color_texture;
    h->gl.frame.scene_depth_texture = h->scene.depth_texture;
    make_output(h, 0);
    make_output(h, 1);
    glGenFramebuffers(1, &incomplete_fbo);
    h->error = error;
}

static void draw_scene(host *h, double t)
{
    test_scene_orbit_camera(t, (float)W / H, h->gl.frame.view, h->gl.frame.projection);
    CHECK(test_scene_draw(&h->scene, h->gl.frame.view, h->gl.frame.projection) == 0);
    for (int i = 0; i < 2; i++) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, h->scene.framebuffer);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, h->out_fbo[i]);
        glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    CHECK(glGetError() == GL_NO_ERROR, "the host's own drawing failed");
}

/* fx[0] rendered by a clean host, fx[1] with the error pending; the same bytes. */
static void render_both(host *h, sbfx *fx[2], double t, const char *what, bool draws)
{
    draw_scene(h, t);
    sbfx_frame frame = h->gl.frame;
    frame.out_framebuffer = h->out_fbo[0];
    CHECK(sbfx_render(fx[0], &frame) == SBFX_OK, "%s", sbfx_last_error(fx[0]));
    frame.out_framebuffer = h->out_fbo[1];
    leave_error(h->error);
    CHECK(sbfx_render(fx[1], &frame) == SBFX_OK, "%s: %s", what, sbfx_last_error(fx[1]));
    check_handed_back(h, what, draws);
    static uint8_t out[2][W * H * 4];
    for (int i = 0; i < 2; i++) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, h->out_fbo[i]);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, out[i]);
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    CHECK(memcmp(out[0], out[1], sizeof(out[0])) == 0, "%s: the picture differs from a clean host's", what);
}

static int infos;
static void count_log(sbfx_log_level level, const char *message, void *user)
{
    (void)user;
    if (strstr(message, "the host's error, not sbfx's")) infos++;
    if (getenv("SBFX_TEST_VERBOSE") || level == SBFX_LOG_ERROR) printf("# sbfx: %s\n", message);
}

static sbfx *module(const char *scene_name)
{
    sbfx_scene *scene = scene_name ? fixture_load_scene(scene_name) : NULL;
    sbfx_desc desc = {.scene = scene, .ignore_timeline = true, .max_particles = 512, .log = count_log};
    sbfx *fx = NULL;
    sbfx_result r = sbfx_create(&desc, &fx);
    sbfx_scene_free(scene);
    CHECK(r == SBFX_OK, "sbfx_create with an error pending: %s", sbfx_result_string(r));
    if (!fx) exit(1);
    return fx;
}

static void every_call(GLenum error, const char *scene_name, const char *effect)
{
    host h;
    host_open(&h, error);
    infos = 0;
    sbfx *fx[2];
    fx[0] = module(scene_name);
    leave_error(error);
    fx[1] = module(scene_name);
    check_handed_back(&h, "sbfx_create", true);

    sbfx_quality q;
    CHECK(sbfx_quality_parse("spherical/2/bl/lpp/abb", &q, NULL, 0) == SBFX_OK);
    CHECK(sbfx_set_quality(fx[0], &q) == SBFX_OK);
    leave_error(error);
    CHECK(sbfx_set_quality(fx[1], &q) == SBFX_OK, "sbfx_set_quality: %s", sbfx_last_error(fx[1]));
    check_handed_back(&h, "sbfx_set_quality (first use)", true);

    CHECK(sbfx_trigger(fx[0], effect, (const float[3]){0, 0, 0}) == SBFX_OK);
    leave_error(error);
    CHECK(sbfx_trigger(fx[1], effect, (const float[3]){0, 0, 0}) == SBFX_OK);
    check_handed_back(&h, "sbfx_trigger", false);

    CHECK(sbfx_update(fx[0], 0.25) == SBFX_OK);
    leave_error(error);
    CHECK(sbfx_update(fx[1], 0.25) == SBFX_OK);
    check_handed_back(&h, "sbfx_update", false);

    static uint16_t slice[64 * 64];
    if (sbfx_detail_push_slice(fx[0], slice, 64) == SBFX_OK) { /* the scene has a detail volume */
        leave_error(error);
        CHECK(sbfx_detail_push_slice(fx[1], slice, 64) == SBFX_OK, "%s", sbfx_last_error(fx[1]));
        check_handed_back(&h, "sbfx_detail_push_slice", true);
    }

    render_both(&h, fx, 0.25, "sbfx_render (first frame)", true);
    for (int i = 0; i < 2; i++) sbfx_update(fx[i], 0.25);
    render_both(&h, fx, 0.5, "sbfx_render (live particles)", true);
    for (int k = 0; k < 40; k++)
        for (int i = 0; i < 2; i++) sbfx_update(fx[i], 10.0);
    render_both(&h, fx, 10.5, "sbfx_render (idle: no GL call)", false);

    sbfx_destroy(fx[0]);
    leave_error(error);
    sbfx_destroy(fx[1]);
    check_handed_back(&h, "sbfx_destroy", false);
    /* create, set_quality, push_slice, 2 renders read it: logged once per module */
    CHECK(infos == 1, "%d log lines about the host's error, expected 1", infos);
    fixture_close(&h.gl);
}

CHECK_TEST(invalid_operation_pending_before_every_call) { every_call(GL_INVALID_OPERATION, NULL, "explosion"); }
CHECK_TEST(invalid_enum_pending_before_every_call) { every_call(GL_INVALID_ENUM, NULL, "explosion"); }
CHECK_TEST(invalid_value_pending_before_every_call) { every_call(GL_INVALID_VALUE, NULL, "explosion"); }
CHECK_TEST(framebuffer_error_pending_is_dropped_not_blamed)
{
    every_call(GL_INVALID_FRAMEBUFFER_OPERATION, NULL, "explosion");
}
/* every post effect: passes and targets of their own */
CHECK_TEST(post_effects_with_an_error_pending) { every_call(GL_INVALID_OPERATION, "post", "explosion"); }

int main(int argc, char **argv) { return check_main_args(argc, argv); }
