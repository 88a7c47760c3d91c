/* make bench, the host contract (issue 10):
 *   - what saving and restoring the host's GL state costs per sbfx_render: glGet/glIs calls
 *     (sbfx_counters.gl_state_queries) and the time of one save + restore against the time of
 *     the whole frame, for an idle frame, live particles and every post effect;
 *   - the far field: a 5 cm particle at 30 m ... 10 km with an opaque surface 1 cm behind its
 *     centre (near 0.1), the host depth drawn as each set-up draws it (standard 24-bit with a
 *     finite or infinite far plane, standard float, reversed-Z float with GL_EXT_clip_control):
 *     |GPU - CPU reference| of the alpha, and the set-up's depth resolution there (DESIGN §5).
 * Writes OUT/state.csv and OUT/farfield.csv (appends with --append; --label names the run,
 * e.g. "glthread" when Mesa's threaded dispatch is on: mesa_glthread=true) and prints both.
 * Timings are measured, never asserted. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "egl/egl_headless.h"
#include "host/host_depth.h"
#include "internal.h"
#include "reference.h"
#include "host/test_scene.h"

#define W 640
#define H 360

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* ---- the cost of the host contract ---- */

typedef struct state_row {
    const char *scene, *frame;
    int queries;
    double roundtrip_us, frame_ms;
} state_row;

static sbfx *scene_module(const char *path)
{
    char err[512];
    sbfx_scene *scene = NULL;
    if (path && sbfx_scene_load(path, &scene, err, sizeof(err)) != SBFX_OK) {
        fprintf(stderr, "bench_state: %s\n", err);
        return NULL;
    }
    sbfx *fx = NULL;
    sbfx_result r = sbfx_create(&(sbfx_desc){.scene = scene, .ignore_timeline = true}, &fx);
    sbfx_scene_free(scene);
    if (r != SBFX_OK) fprintf(stderr, "bench_state: sbfx_create: %s\n", sbfx_result_string(r));
    return fx;
}

/* One save + restore, timed over many in a row (glFinish on both sides). */
static double roundtrip_us(sbfx *fx, bool particles)
{
    const int n = 4000;
    glFinish();
    double t0 = now_ms();
    for (int i = 0; i < n; i++) sbfx_host_state_roundtrip(fx, particles);
    glFinish();
    return (now_ms() - t0) * 1e3 / n;
}

/* Mean ms of sbfx_render (update excluded) over frames of the explosion's busy part. */
static double frame_ms(sbfx *fx, struct test_scene *scene, sbfx_frame *frame, bool particles, int *queries)
{
    if (particles) sbfx_trigger(fx, "explosion", (const float[3]){0, 0, 0});
    double total = 0;
    int frames = 0;
    for (int i = 0; i < 24; i++) {
        sbfx_update(fx, 1.0 / 30.0);
        test_scene_orbit_camera(i / 30.0, (float)W / H, frame->view, frame->projection);
        test_scene_draw(scene, frame->view, frame->projection);
        glFinish();
        double t0 = now_ms();
        if (sbfx_render(fx, frame) != SBFX_OK) fprintf(stderr, "bench_state: %s\n", sbfx_last_error(fx));
        glFinish();
        if (i >= 4) total += now_ms() - t0, frames++;
        sbfx_counters c;
        sbfx_stats(fx, &c);
        *queries = c.gl_state_queries;
    }
    return total / frames;
}

static int bench_state(state_row *rows)
{
    char err[256];
    struct test_scene scene;
    if (test_scene_create(&scene, W, H, err, sizeof(err)) != 0) {
        fprintf(stderr, "bench_state: %s\n", err);
        return 0;
    }
    GLuint out_tex, out_fbo;
    glGenTextures(1, &out_tex);
    glBindTexture(GL_TEXTURE_2D, out_tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, W, H);
    glGenFramebuffers(1, &out_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, out_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, out_tex, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    sbfx_frame frame = {.scene_color_texture = scene.color_texture, .scene_depth_texture = scene.depth_texture,
                        .out_framebuffer = out_fbo, .width = W, .height = H};
    const struct { const char *name, *path, *frame; bool particles; } cases[] = {
        {"explosion", NULL, "idle", false},
        {"explosion", NULL, "particles", true},
        {"post.cfg", "scenes/post.cfg", "idle", false},
        {"post.cfg", "scenes/post.cfg", "particles", true},
    };
    int n = 0;
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        sbfx *fx = scene_module(cases[i].path);
        if (!fx) continue;
        state_row *r = &rows[n++];
        *r = (state_row){cases[i].name, cases[i].frame, 0, 0, 0};
        r->frame_ms = frame_ms(fx, &scene, &frame, cases[i].particles, &r->queries);
        r->roundtrip_us = roundtrip_us(fx, cases[i].particles);
        sbfx_destroy(fx);
    }
    glDeleteFramebuffers(1, &out_fbo);
    glDeleteTextures(1, &out_tex);
    test_scene_destroy(&scene);
    return n;
}

/* ---- the far field ---- */

typedef struct depth_setup {
    const char *name;
    GLenum format;
    bool reversed, infinite;
} depth_setup;

static const depth_setup setups[] = {
    {"standard 24-bit far=1e5", GL_DEPTH_COMPONENT24, false, false},
    {"standard 24-bit far=inf", GL_DEPTH_COMPONENT24, false, true},
    {"standard float far=inf", GL_DEPTH_COMPONENT32F, false, true},
    {"reversed-Z float far=inf", GL_DEPTH_COMPONENT32F, true, true},
};

/* What the set-up resolves at distance z (one step of its depth value), DESIGN §5. */
static double resolution(const depth_setup *s, double z, double near)
{
    if (s->reversed) return z * pow(2.0, -24); /* float n / z: 24-bit mantissa, relative */
    return z * z / (near * pow(2.0, 24));      /* window depth near 1: steps of 2^-24, 24-bit or float */
}

/* The single pixel's alpha: GPU (host depth drawn by GL) and CPU reference (the true surface). */
static bool far_field(sbfx *fx, sbfx_opacity_mode mode, const depth_setup *s, double z, GLuint out_fbo,
                      double *cpu, double *gpu)
{
    const double near = 0.1, r = 0.05, surface = z + 0.01;
    sbfx_frame frame = {.out_framebuffer = out_fbo, .width = 1, .height = 1};
    frame.view[0] = frame.view[5] = frame.view[10] = frame.view[15] = 1.0f;
    sbfx_perspective(frame.projection, 1.0f, 1.0f, (float)near, s->infinite ? INFINITY : 1e5f);
    if (s->reversed) sbfx_reverse_z(frame.projection, (float)near, INFINITY);
    frame.projection[0] = frame.projection[5] = 1.0f;
    frame.clip_depth_mode = s->reversed ? SBFX_CLIP_DEPTH_ZERO_TO_ONE : SBFX_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE;
    GLuint depth = 0;
    if (host_depth_plane(&depth, 1, 1, s->format, frame.projection, s->reversed, surface) != 0) return false;
    frame.scene_depth_texture = depth;
    sbfx_media(fx)[SBFX_SMOKE].detail_strength = 0.0f;
    sbfx_view_particle p = {.center = {0.0f, 0.0f, (float)-z}, .radius = (float)r, .intensity = 1.0f,
                            .medium = SBFX_SMOKE};
    float rgba[4];
    int w, h;
    bool ok = sbfx_render_view_particles(fx, &frame, &p, 1) == SBFX_OK &&
              sbfx_read_particle_target(fx, rgba, 4, &w, &h) == SBFX_OK;
    glDeleteTextures(1, &depth);
    sbfx_ref_particle rp = {{0.0, 0.0, -z}, r, sbfx_media(fx)[SBFX_SMOKE].tau};
    sbfx_ref_pixel px = {{0.0, 0.0, -1.0}, surface, near, 0.0};
    *cpu = sbfx_ref_opacity(mode, &rp, &px);
    *gpu = 1.0 - rgba[3];
    return ok;
}

static void bench_far_field(FILE *csv, const char *label)
{
    const double distances[] = {30.0, 300.0, 3000.0, 10000.0};
    const sbfx_opacity_mode modes[] = {SBFX_OPACITY_SPHERICAL, SBFX_OPACITY_EXACT};
    GLuint tex, fbo;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, 1, 1);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    printf("\nfar field: r = 5 cm, surface 1 cm behind the centre, near 0.1; |alpha GPU - CPU| (resolution of the depth there)\n");
    printf("%-32s %10s %10s %10s %10s\n", "host depth", "30 m", "300 m", "3000 m", "10000 m");
    for (size_t m = 0; m < 2; m++) {
        sbfx *fx = NULL;
        sbfx_desc desc = {.target_divisor = 1, .target_format = SBFX_FORMAT_RGBA32F, .opacity = modes[m], .max_particles = 4};
        if (sbfx_create(&desc, &fx) != SBFX_OK) continue;
        for (size_t s = 0; s < sizeof(setups) / sizeof(setups[0]); s++) {
            if (setups[s].reversed && !host_depth_has_clip_control()) {
                printf("%-32s (GL_EXT_clip_control missing)\n", setups[s].name);
                continue;
            }
            printf("%-32s", setups[s].name);
            for (size_t d = 0; d < sizeof(distances) / sizeof(distances[0]); d++) {
                double cpu = NAN, gpu = NAN, res = resolution(&setups[s], distances[d], 0.1);
                far_field(fx, modes[m], &setups[s], distances[d], fbo, &cpu, &gpu);
                printf(" %10.2e", fabs(gpu - cpu));
                fprintf(csv, "%s,%s,%s,%g,%.9g,%.9g,%.3g,%.3g\n", label, setups[s].name,
                        modes[m] == SBFX_OPACITY_EXACT ? "exact" : "spherical", distances[d], cpu, gpu, fabs(gpu - cpu), res);
            }
            printf("   (%s)\n", modes[m] == SBFX_OPACITY_EXACT ? "exact" : "spherical");
        }
        sbfx_destroy(fx);
    }
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
}

int main(int argc, char **argv)
{
    const char *out = "build/bench", *label = "default";
    bool append = false;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) out = argv[++i];
        else if (strcmp(argv[i], "--label") == 0 && i + 1 < argc) label = argv[++i];
        else if (strcmp(argv[i], "--append") == 0) append = true;
        else {
            fprintf(stderr, "usage: bench_state [--out DIR] [--label NAME] [--append]\n");
            return 1;
        }
    }
    struct egl_headless egl;
    char err[512];
    if (egl_headless_open(&egl, err, sizeof(err)) != 0) {
        fprintf(stderr, "bench_state: %s\n", err);
        return 1;
    }
    char path[512];
    snprintf(path, sizeof(path), "%s/state.csv", out);
    FILE *csv = fopen(path, append ? "a" : "w");
    snprintf(path, sizeof(path), "%s/farfield.csv", out);
    FILE *far = fopen(path, append ? "a" : "w");
    if (!csv || !far) {
        fprintf(stderr, "bench_state: cannot write into %s\n", out);
        return 1;
    }
    if (!append) {
        fprintf(csv, "config,scene,frame,gl_state_queries,roundtrip_us,frame_ms,share_percent\n");
        fprintf(far, "config,depth,mode,distance_m,cpu_alpha,gpu_alpha,abs_err,resolution_m\n");
    }
    state_row rows[8];
    int n = bench_state(rows);
    printf("host GL state (%s, %s, %dx%d): glGet/glIs per sbfx_render, one save + restore, whole frame\n", label,
           (const char *)glGetString(GL_RENDERER), W, H);
    for (int i = 0; i < n; i++) {
        const state_row *r = &rows[i];
        double share = r->queries > 0 ? 100.0 * r->roundtrip_us * 1e-3 / r->frame_ms : 0; /* idle: no pass, no call */
        printf("  %-10s %-10s %3d queries  %7.2f us  frame %7.2f ms  (%.3f%%)\n", r->scene, r->frame, r->queries,
               r->roundtrip_us, r->frame_ms, share);
        fprintf(csv, "%s,%s,%s,%d,%.3f,%.3f,%.4f\n", label, r->scene, r->frame, r->queries, r->roundtrip_us, r->frame_ms,
                share);
    }
    if (!append) bench_far_field(far, label); /* depth precision does not change with the dispatch */
    fclose(csv);
    fclose(far);
    egl_headless_close(&egl);
    return 0;
}
