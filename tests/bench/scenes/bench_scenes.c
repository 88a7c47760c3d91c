/* make bench, scenes and post effects (issues #3 and #6):
 *   - simulation throughput: particle updates per second on one core, barrage scene
 *     (DESIGN §4 asks >= 1 M/s on x86), and heap allocations during the run;
 *   - load time and GPU bytes of every example scene;
 *   - post effects: ms per frame for none, shimmer, blur-history, blur-velocity, dof at full
 *     and half output resolution (glFinish-bracketed, median of the timed frames).
 * Writes OUT/scenes.csv and OUT/post.csv and prints both. Timings only, never asserted. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "egl/egl_headless.h"
#include "sbfx.h"
#include "host/test_scene.h"

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof(*v), compare_doubles);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static sbfx_scene *load(const char *path)
{
    char err[512];
    sbfx_scene *scene = NULL;
    if (sbfx_scene_load(path, &scene, err, sizeof(err)) != SBFX_OK) fprintf(stderr, "bench: %s\n", err);
    return scene;
}

/* ---- simulation and load ---- */
static void bench_simulation(FILE *csv)
{
    sbfx_scene *scene = load("scenes/barrage.cfg");
    if (!scene) return;
    sbfx *fx = NULL;
    if (sbfx_create(&(sbfx_desc){.scene = scene}, &fx) != SBFX_OK) return;
    long long updates = 0;
    double ms = 0;
    sbfx_counters before, after;
    sbfx_stats(fx, &before);
    for (int frame = 0; frame < 180; frame++) { /* 3 s at 60 fps: the whole barrage */
        double t0 = now_ms();
        sbfx_update(fx, 1.0 / 60.0);
        ms += now_ms() - t0;
        sbfx_counters c;
        sbfx_stats(fx, &c);
        updates += c.particles_simulated;
    }
    sbfx_stats(fx, &after);
    double rate = updates / (ms / 1e3);
    printf("simulation: barrage, %lld particle updates in %.2f ms on one core = %.1f M/s (target >= 1 M/s), "
           "heap allocations during the run: %llu\n",
           updates, ms, rate / 1e6, (unsigned long long)(after.heap_allocs_after_load - before.heap_allocs_after_load));
    fprintf(csv, "barrage,simulation,%lld,%.3f,%.0f,,\n", updates, ms, rate);
    sbfx_destroy(fx);
    sbfx_scene_free(scene);
}

static void bench_load(FILE *csv, const char *name)
{
    char path[256];
    snprintf(path, sizeof(path), "scenes/%s.cfg", name);
    double times[5];
    size_t bytes = 0;
    int programs = 0;
    for (int rep = 0; rep < 5; rep++) {
        double t0 = now_ms();
        sbfx_scene *scene = load(path);
        sbfx *fx = NULL;
        if (!scene || sbfx_create(&(sbfx_desc){.scene = scene}, &fx) != SBFX_OK) {
            sbfx_scene_free(scene);
            return;
        }
        glFinish();
        times[rep] = now_ms() - t0;
        sbfx_counters c;
        sbfx_stats(fx, &c);
        bytes = c.gpu_bytes, programs = c.programs;
        sbfx_destroy(fx);
        sbfx_scene_free(scene);
    }
    double ms = median(times, 5);
    printf("load: %-10s %7.1f ms  programs %2d  gpu_bytes %zu (before the first frame's targets)\n", name, ms,
           programs, bytes);
    fprintf(csv, "%s,load,,%.3f,,%d,%zu\n", name, ms, programs, bytes);
}

/* ---- post effects ---- */
static const char *const post_blocks[] = {
    "", /* none */
    "", /* shimmer: the heat medium's emitter below */
    "post = { motion_blur = { mode = \"history\"; persistence = 0.08; }; };\n",
    "post = { motion_blur = { mode = \"velocity\"; shutter = 0.5; tile = 8; samples = 15; }; };\n",
    "post = { depth_of_field = { near = [2.0, 6.0]; far = [16.0, 60.0]; max_radius = 6.0; scale = 2; }; };\n",
};
static const char *const post_names[] = {"none", "shimmer", "blur-history", "blur-velocity", "dof"};

/* The explosion scene with one post effect spliced in. */
static char *post_scene(int effect)
{
    FILE *f = fopen("scenes/explosion.cfg", "rb");
    if (!f) return NULL;
    static char text[32768];
    size_t n = fread(text, 1, sizeof(text) - 4096, f);
    fclose(f);
    text[n] = '\0';
    if (effect == 1) {
        /* a heat medium and a heat emitter step, placed before the effect's last step */
        char *media_end = strstr(text, "};\n\neffects");
        char *steps = strstr(text, "{ type = \"light_flash\"");
        if (!media_end || !steps) return NULL;
        static char out[32768];
        snprintf(out, sizeof(out), "%.*s  heat = { density = 1.5; strength = 0.004; };\n%.*s"
                 "{ type = \"emitter\"; medium = \"heat\"; count = 12; spawn_radius = 0.8; speed = [0.5, 1.5];"
                 " upward = 0.9; lifetime = [2.0, 2.8]; radius = [1.0, 2.0]; },\n      %s",
                 (int)(media_end - text), text, (int)(steps - media_end), media_end, steps);
        return out;
    }
    strncat(text, post_blocks[effect], sizeof(text) - strlen(text) - 1);
    return text;
}

static double time_post(int effect, int w, int h)
{
    char *text = post_scene(effect), err[512];
    sbfx_scene *scene = NULL;
    if (!text || sbfx_scene_parse(text, "post-bench", &scene, err, sizeof(err)) != SBFX_OK) {
        fprintf(stderr, "bench: post scene %s: %s\n", post_names[effect], text ? err : "no scenes/explosion.cfg");
        return -1;
    }
    struct test_scene opaque;
    GLuint out_fbo = 0, out_rb = 0;
    if (test_scene_create(&opaque, w, h, err, sizeof(err)) != 0) return -1;
    glGenRenderbuffers(1, &out_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, out_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glGenFramebuffers(1, &out_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, out_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, out_rb);
    sbfx *fx = NULL;
    double times[24];
    int n = 0;
    if (sbfx_create(&(sbfx_desc){.scene = scene}, &fx) == SBFX_OK) {
        for (int frame = 0; frame < 36; frame++) {
            sbfx_frame f = {.scene_color_texture = opaque.color_texture, .scene_depth_texture = opaque.depth_texture,
                            .out_framebuffer = out_fbo, .width = w, .height = h};
            test_scene_orbit_camera(frame / 12.0, (float)w / h, f.view, f.projection);
            test_scene_draw(&opaque, f.view, f.projection);
            glFinish();
            double t0 = now_ms();
            sbfx_update(fx, 1.0 / 12.0);
            sbfx_render(fx, &f);
            glFinish();
            if (frame >= 6 && frame < 30) times[n++] = now_ms() - t0; /* the explosion's busy part */
        }
        sbfx_destroy(fx);
    }
    glDeleteFramebuffers(1, &out_fbo);
    glDeleteRenderbuffers(1, &out_rb);
    test_scene_destroy(&opaque);
    sbfx_scene_free(scene);
    return n ? median(times, n) : -1;
}

static void bench_post(FILE *csv, int w, int h)
{
    const double scales[] = {1.0, 0.5};
    for (int s = 0; s < 2; s++) {
        int sw = (int)(w * scales[s]), sh = (int)(h * scales[s]);
        double base = 0;
        for (int e = 0; e < 5; e++) {
            double ms = time_post(e, sw, sh);
            if (e == 0) base = ms;
            printf("post: %-13s %4dx%-4d %7.2f ms per frame (%+.2f ms over none)\n", post_names[e], sw, sh, ms,
                   ms - base);
            fprintf(csv, "%s,%g,%dx%d,%.3f,%.3f\n", post_names[e], scales[s], sw, sh, ms, ms - base);
        }
    }
}

int main(int argc, char **argv)
{
    const char *out = "build/bench";
    int w = 960, h = 540;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) out = argv[++i];
        else if (strcmp(argv[i], "--size") == 0 && i + 1 < argc && sscanf(argv[++i], "%dx%d", &w, &h) == 2) continue;
        else {
            fprintf(stderr, "usage: bench_scenes [--out DIR] [--size WxH]\n");
            return 1;
        }
    }
    struct egl_headless egl;
    char err[512], path[1024];
    if (egl_headless_open(&egl, err, sizeof(err)) != 0) {
        fprintf(stderr, "bench_scenes: %s\n", err);
        return 1;
    }
    snprintf(path, sizeof(path), "%s/scenes.csv", out);
    FILE *scenes = fopen(path, "w");
    snprintf(path, sizeof(path), "%s/post.csv", out);
    FILE *post = fopen(path, "w");
    if (!scenes || !post) {
        fprintf(stderr, "bench_scenes: cannot write into %s: %s\n", out, strerror(errno));
        return 1;
    }
    fprintf(scenes, "scene,what,particle_updates,ms,updates_per_second,programs,gpu_bytes\n");
    fprintf(post, "effect,scale,size,ms,ms_over_none\n");
    bench_simulation(scenes);
    const char *names[] = {"explosion", "smoke", "campfire", "dust-storm", "barrage", "post", "lit-smoke"};
    for (size_t i = 0; i < sizeof(names) / sizeof(names[0]); i++) bench_load(scenes, names[i]);
    bench_post(post, w, h);
    fclose(scenes);
    fclose(post);
    egl_headless_close(&egl);
    printf("bench: %s/scenes.csv, %s/post.csv\n", out, out);
    return 0;
}
