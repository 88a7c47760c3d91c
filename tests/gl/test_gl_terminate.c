/* Early termination of the particles (issue 43 item 4; src/render/terminate.c): drawn nearest
 * first, a particle-target texel stops taking particles at a checkpoint once its transmittance
 * is below epsilon = STOP_LEVELS / (255 (L + 1)), L a bound of the light of every particle drawn
 * after it. The same frames rendered with it (nearest first, "under") and without it (back to
 * front, "over"; sbfx_set_early_termination), into RGBA32F targets, where the two orders agree to
 * float rounding (in RGBA16F they do not: "under" carries each stored transmittance's rounding
 * into the light behind it, docs/gpus.md, which test_gl_hard_cases bounds on its own):
 *   - the particle target differs by at most T L < STOP_LEVELS / 255 in light and T < epsilon in
 *     transmittance per texel (the derivation's own bound, in the target's units), plus the
 *     floats' rounding of the values compared (2^-10 of each: far more than RGBA32F's);
 *   - the output (8-bit) by at most 1 level: two values under a quarter of a level apart round to
 *     at most one level apart;
 *   - texels were terminated, and none where what is left behind could still show: counted by
 *     drawing at the particles' window depth against the target's depth afterwards, the
 *     particles after the checkpoint fail there (no shading);
 * for a dense stack of opaque smoke with bright fire behind it (the fire sets L: epsilon at its
 * smallest), the example barrage over its life, and a module loaded without it and turned on. */
#define _GNU_SOURCE
#include <unistd.h>
#include "gl_fixture.h"
#include "host/test_scene.h"

#define W 128
#define H 96
#define STOP_ALLOWANCE (0.25 / 255.0) /* terminate.c's STOP_LEVELS of an 8-bit level */
#define HALF_ROUNDING 0x1p-10

static sbfx_view_particle particle(float x, float y, float z, float r, sbfx_medium m)
{
    return (sbfx_view_particle){.center = {x, y, z}, .radius = r, .detail = {0.3f, 0.6f, 0.1f},
                                .intensity = 1.0f, .medium = m};
}

/* 48 smoke particles stacked in front (each nearly opaque at its centre), 8 fire particles
 * behind them, 8 dust beside: the front's transmittance falls below epsilon where the stack is
 * thick, and the fire behind is what a wrong epsilon would let show. */
static int dense_stack(sbfx_view_particle *p)
{
    int n = 0;
    for (int i = 0; i < 48; i++)
        p[n++] = particle(0.05f * (float)(i % 5) - 0.1f, 0.04f * (float)(i % 3) - 0.04f, -4.0f - 0.05f * (float)i, 1.2f,
                          SBFX_SMOKE);
    for (int i = 0; i < 8; i++) p[n++] = particle(0.2f * (float)(i % 4) - 0.3f, 0.1f * (float)(i / 4), -8.0f, 1.0f, SBFX_FIRE);
    for (int i = 0; i < 8; i++) p[n++] = particle(1.6f, 0.3f * (float)i - 1.0f, -6.0f - 0.1f * (float)i, 0.4f, SBFX_DUST);
    return n;
}

static void dense_media(sbfx_scene *scene)
{
    scene->media[SBFX_SMOKE].tau = 12.0f; /* a thick column: the stack's front is opaque */
    scene->media[SBFX_FIRE].emission_scale *= 20.0f; /* bright fire behind it */
}

typedef struct frame_pair {
    float *on, *off;   /* the particle target, RGBA */
    uint8_t *out_on, *out_off;
    int w, h;
    int stops_marked;  /* in the frame with termination */
    long terminated;   /* target texels whose depth the marks set to 0 */
} frame_pair;

/* How many texels of the particle target fail GL_LESS at the particles' window depth (0.5):
 * those the marks set to 0. A quad at clip z 0 with the depth test on, counting into a colour
 * renderbuffer of its own with the target's depth renderbuffer attached. */
static long terminated_texels(sbfx *fx)
{
    const sbfx_rt *t = &fx->gl->particles;
    if (!t->depth_renderbuffer) return -1;
    static const char vs[] = "#version 300 es\nvoid main() { vec2 p = vec2(gl_VertexID & 1, gl_VertexID >> 1) * 4.0 - 1.0;"
                             " gl_Position = vec4(p, 0.0, 1.0); }\n";
    static const char fs[] = "#version 300 es\nprecision mediump float;\nout vec4 o;\nvoid main() { o = vec4(1.0); }\n";
    GLuint prog = fixture_program(vs, fs);
    GLuint fbo, color, vao;
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(1, &color);
    glGenVertexArrays(1, &vao);
    glBindRenderbuffer(GL_RENDERBUFFER, color);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, t->width, t->height);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->depth_renderbuffer);
    CHECK(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    glViewport(0, 0, t->width, t->height);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);
    glUseProgram(prog);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    uint8_t *px = malloc((size_t)t->width * t->height * 4);
    glReadPixels(0, 0, t->width, t->height, GL_RGBA, GL_UNSIGNED_BYTE, px);
    long stopped = 0;
    for (long i = 0; i < (long)t->width * t->height; i++) stopped += px[4 * i] == 0;
    free(px);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &color);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(prog);
    return stopped;
}

static void render_read(gl_fixture *f, sbfx *fx, const sbfx_view_particle *v, int n, GLuint host_fbo, float **target,
                        uint8_t **out)
{
    if (host_fbo) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, host_fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, f->out_fbo);
        glBlitFramebuffer(0, 0, f->width, f->height, 0, 0, f->width, f->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    } else {
        glBindFramebuffer(GL_FRAMEBUFFER, f->out_fbo);
        glClearColor(0.35f, 0.5f, 0.7f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    sbfx_result r = v ? sbfx_render_view_particles(fx, &f->frame, v, n) : sbfx_render(fx, &f->frame);
    CHECK(r == SBFX_OK, "%s", sbfx_last_error(fx));
    int w, h;
    *target = fixture_read_target(fx, &w, &h);
    *out = malloc((size_t)f->width * f->height * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, f->out_fbo);
    glReadPixels(0, 0, f->width, f->height, GL_RGBA, GL_UNSIGNED_BYTE, *out);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

/* The frame with termination, then without it (the same module, the same particles). */
static frame_pair render_pair(gl_fixture *f, sbfx *fx, const sbfx_view_particle *v, int n, GLuint host_fbo)
{
    frame_pair p = {0};
    CHECK(sbfx_set_early_termination(fx, true) == SBFX_OK, "%s", sbfx_last_error(fx));
    render_read(f, fx, v, n, host_fbo, &p.on, &p.out_on);
    p.stops_marked = fx->render->stops_marked;
    p.terminated = terminated_texels(fx);
    p.w = fx->gl->low_width, p.h = fx->gl->low_height;
    CHECK(sbfx_set_early_termination(fx, false) == SBFX_OK, "%s", sbfx_last_error(fx));
    render_read(f, fx, v, n, host_fbo, &p.off, &p.out_off);
    CHECK(fx->render->stops_marked == 0, "%d marks with termination off", fx->render->stops_marked);
    CHECK(sbfx_set_early_termination(fx, true) == SBFX_OK);
    return p;
}

typedef struct pair_diff {
    double light, transmittance; /* worst excess over the allowance (<= 0: within it) */
    double worst_light, worst_t;
    int out_levels;              /* worst 8-bit difference of the output */
    long nonfinite;
} pair_diff;

static pair_diff compare(const gl_fixture *f, const frame_pair *p)
{
    pair_diff d = {-1e30, -1e30, 0, 0, 0, 0};
    for (long i = 0; i < (long)p->w * p->h; i++)
        for (int k = 0; k < 4; k++) {
            double a = p->on[4 * i + k], b = p->off[4 * i + k];
            if (!isfinite(a)) d.nonfinite++;
            double err = fabs(a - b), allowed = STOP_ALLOWANCE + HALF_ROUNDING * (fabs(a) + fabs(b));
            if (k < 3) d.light = fmax(d.light, err - allowed), d.worst_light = fmax(d.worst_light, err);
            else d.transmittance = fmax(d.transmittance, err - allowed), d.worst_t = fmax(d.worst_t, err);
        }
    for (long i = 0; i < (long)f->width * f->height * 4; i++) {
        int e = abs((int)p->out_on[i] - (int)p->out_off[i]);
        if (e > d.out_levels) d.out_levels = e;
    }
    return d;
}

static void pair_free(frame_pair *p)
{
    free(p->on), free(p->off), free(p->out_on), free(p->out_off);
}

static void check_within(const gl_fixture *f, const frame_pair *p, const char *what)
{
    pair_diff d = compare(f, p);
    printf("# %s: %d marks, %ld of %d target texels terminated; light differs by at most %.2e, transmittance "
           "%.2e (allowed %.2e each); the output by %d levels\n", what, p->stops_marked, p->terminated, p->w * p->h,
           d.worst_light, d.worst_t, STOP_ALLOWANCE, d.out_levels);
    CHECK(d.nonfinite == 0, "%s: %ld values not finite", what, d.nonfinite);
    CHECK(d.light <= 0.0 && d.transmittance <= 0.0, "%s: beyond the derived bound by %.3g (light), %.3g (transmittance)",
          what, d.light, d.transmittance);
    CHECK(d.out_levels <= 1, "%s: the output differs by %d levels", what, d.out_levels);
}

static sbfx *dense_module(gl_fixture *f, bool terminate)
{
    static sbfx_scene scene;
    sbfx_scene_builtin(&scene);
    dense_media(&scene);
    scene.early_termination = terminate;
    return fixture_module(f, (sbfx_desc){.target_divisor = 2, .target_format = SBFX_FORMAT_RGBA32F, .max_particles = 256,
                                         .scene = &scene});
}

CHECK_TEST(dense_stack_terminates_within_the_bound)
{
    gl_fixture f;
    fixture_open_far(&f, W, H);
    sbfx_view_particle v[64];
    int n = dense_stack(v);
    sbfx *fx = dense_module(&f, true);
    frame_pair p = render_pair(&f, fx, v, n, 0);
    check_within(&f, &p, "48 opaque smoke particles over bright fire");
    CHECK(p.stops_marked == SBFX_STOPS, "%d marks", p.stops_marked);
    /* the stack covers the target's middle: a good share of it is opaque after half the
     * particles (the smoke, nearest first) */
    CHECK(p.terminated > p.w * p.h / 20, "only %ld of %d texels terminated", p.terminated, p.w * p.h);
    /* where a texel was terminated, what it still let through was below every epsilon: at most
     * 0.25 / 255 / (1 + L) <= 0.25 / 255, and the final transmittance with termination is at
     * most that too */
    long seen = 0;
    for (long i = 0; i < (long)p.w * p.h; i++) seen += p.on[4 * i + 3] < STOP_ALLOWANCE;
    CHECK(seen >= p.terminated, "%ld texels terminated, %ld below the largest epsilon", p.terminated, seen);
    pair_free(&p);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* Turned on in a module loaded without it: the targets are made again with their depth. */
CHECK_TEST(turned_on_after_load)
{
    gl_fixture f;
    fixture_open_far(&f, W, H);
    sbfx_view_particle v[64];
    int n = dense_stack(v);
    sbfx *fx = dense_module(&f, false);
    CHECK(!fx->gl->stop_program, "a mark program without early termination");
    CHECK(sbfx_render_view_particles(fx, &f.frame, v, n) == SBFX_OK);
    CHECK(fx->render->stops_marked == 0 && !fx->gl->particles.depth_renderbuffer, "marks %d without termination",
          fx->render->stops_marked);
    frame_pair p = render_pair(&f, fx, v, n, 0);
    CHECK(p.stops_marked == SBFX_STOPS && p.terminated > 0, "%d marks, %ld texels", p.stops_marked, p.terminated);
    check_within(&f, &p, "turned on after load");
    pair_free(&p);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* scenes/smoke.cfg with `value` as its render.early_termination, loaded from a file of its own. */
static sbfx_result load_with_key(const char *value, sbfx_scene **scene, char *err, size_t n)
{
    FILE *in = fopen("scenes/smoke.cfg", "r");
    CHECK(in != NULL, "scenes/smoke.cfg");
    static char text[65536];
    size_t len = in ? fread(text, 1, sizeof(text) - 1, in) : 0;
    if (in) fclose(in);
    text[len] = '\0';
    char *render = strstr(text, "render = {");
    CHECK(render != NULL, "smoke.cfg has no render group");
    char path[] = "/tmp/sbfx-terminate-XXXXXX.cfg";
    int fd = mkstemps(path, 4);
    CHECK(fd >= 0, "mkstemps");
    FILE *out = fdopen(fd, "w");
    render += strlen("render = {");
    fprintf(out, "%.*s early_termination = %s;%s", (int)(render - text), text, value, render);
    fclose(out);
    sbfx_result r = sbfx_scene_load(path, scene, err, n);
    remove(path);
    return r;
}

/* The scene key: render.early_termination = true loads with it (off without the key); anything
 * but a boolean is an error that names the key. */
CHECK_TEST(scene_key)
{
    char err[256] = "";
    sbfx_scene *scene = NULL;
    CHECK(load_with_key("true", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    CHECK(scene && scene->early_termination, "the key did not turn it on");
    sbfx_scene_free(scene);
    scene = NULL;
    CHECK(load_with_key("false", &scene, err, sizeof(err)) == SBFX_OK && !scene->early_termination, "%s", err);
    sbfx_scene_free(scene);
    scene = fixture_load_scene("smoke");
    CHECK(!scene->early_termination, "on without the key");
    sbfx_scene_free(scene);
    scene = NULL;
    CHECK(load_with_key("1", &scene, err, sizeof(err)) != SBFX_OK && strstr(err, "early_termination"),
          "a number was taken: %s", err);
}

/* The barrage, the densest example scene, from its own camera over the test scene, every half
 * second of its life. */
CHECK_TEST(barrage_over_its_life)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    char err[256];
    struct test_scene host;
    CHECK(test_scene_create(&host, W, H, err, sizeof(err)) == 0, "%s", err);
    sbfx_scene *scene = fixture_load_scene("barrage");
    sbfx_scene_camera camera;
    CHECK(sbfx_scene_camera_get(scene, &camera));
    sbfx *fx = fixture_module(&f, (sbfx_desc){.scene = scene, .target_format = SBFX_FORMAT_RGBA32F});
    sbfx_scene_free(scene);
    f.frame.scene_color_texture = host.color_texture;
    f.frame.scene_depth_texture = host.depth_texture;
    long terminated = 0;
    int frames = 0;
    unsigned long long allocs = 0;
    for (int step = 1; step <= 8; step++) {
        while (sbfx_time(fx) < 0.5 * step - 1e-9) CHECK(sbfx_update(fx, 1.0 / 60.0) == SBFX_OK);
        test_scene_camera(&camera, sbfx_time(fx), (float)W / H, f.frame.view, f.frame.projection);
        CHECK(test_scene_draw(&host, f.frame.view, f.frame.projection) == 0);
        frame_pair p = render_pair(&f, fx, NULL, 0, host.framebuffer);
        char what[64];
        snprintf(what, sizeof(what), "barrage at %.1f s", sbfx_time(fx));
        check_within(&f, &p, what);
        terminated += p.terminated > 0 ? p.terminated : 0;
        frames++;
        pair_free(&p);
        /* after the first pair (the mark program and the targets with their depth made), both
         * ways allocate nothing per frame */
        sbfx_counters c;
        sbfx_stats(fx, &c);
        if (step == 1) allocs = c.heap_allocs_after_load;
        CHECK(c.heap_allocs_after_load == allocs, "%llu allocations after the first frame",
              (unsigned long long)(c.heap_allocs_after_load - allocs));
    }
    CHECK(terminated > 0, "nothing terminated over %d frames of the barrage", frames);
    CHECK(glGetError() == GL_NO_ERROR);
    sbfx_destroy(fx);
    test_scene_destroy(&host);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
