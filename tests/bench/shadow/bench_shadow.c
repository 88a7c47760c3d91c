/* make bench, the host's shadow map (issue 27, RTR 13.8.1): what sbfx_render_shadow_map costs
 * at each map size — ms per call (glFinish on both sides, mean over the busy part of the
 * effect), the map's bytes, the particles drawn — next to the frame's own sbfx_render at
 * 640x360, for the explosion and the barrage (the stress case). Writes OUT/shadow.csv and
 * prints it. Timings are measured, never asserted. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "egl/egl_headless.h"
#include "host/test_scene.h"
#include "internal.h"
#include "module.h" /* the packed instances: the map's fragments */
#include "scene/scene.h"  /* render.shadow_map_size: a module without the scene's map */
#include <math.h>

#define W 640
#define H 360
#define FRAMES 16

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

typedef struct shadow_row {
    double map_ms, frame_ms;
    int particles;
    double overdraw;  /* fragments shaded per texel of the map (the quads' area) */
    size_t bytes;
} shadow_row;

static sbfx *module(const char *path, int size)
{
    char err[512];
    sbfx_scene *scene = NULL;
    if (sbfx_scene_load(path, &scene, err, sizeof(err)) != SBFX_OK) {
        fprintf(stderr, "bench_shadow: %s\n", err);
        return NULL;
    }
    scene->render.shadow_map_size = 0; /* size 0 below: no map at all */
    sbfx *fx = NULL;
    sbfx_result r = sbfx_create(&(sbfx_desc){.scene = scene, .shadow_map_size = size}, &fx);
    sbfx_scene_free(scene);
    if (r != SBFX_OK) fprintf(stderr, "bench_shadow: sbfx_create: %s\n", sbfx_result_string(r));
    return fx;
}

/* GPU bytes the map adds at load: its texture and its instance buffer. */
static size_t map_bytes(const char *path, int size)
{
    sbfx *with = module(path, size), *without = module(path, 0);
    sbfx_counters a = {0}, b = {0};
    if (with) sbfx_stats(with, &a);
    if (without) sbfx_stats(without, &b);
    sbfx_destroy(with);
    sbfx_destroy(without);
    return a.gpu_bytes - b.gpu_bytes;
}

/* Frames 0.2 .. 0.2 + FRAMES / 30 s of the scene's timeline: the map, then the frame. */
static int measure(const char *path, int size, struct test_scene *scene, GLuint out, shadow_row *row)
{
    sbfx *fx = module(path, size);
    if (!fx) return -1;
    sbfx_frame frame = {.scene_color_texture = scene->color_texture, .scene_depth_texture = scene->depth_texture,
                        .out_framebuffer = out, .width = W, .height = H};
    const float sun[3] = {-0.45f, -0.8f, -0.4f};
    sbfx_update(fx, 0.2);
    *row = (shadow_row){0};
    for (int i = 0; i < FRAMES; i++) {
        sbfx_update(fx, 1.0 / 30.0);
        test_scene_orbit_camera(0.2 + i / 30.0, (float)W / H, frame.view, frame.projection);
        test_scene_draw(scene, frame.view, frame.projection);
        sbfx_shadow_map map;
        glFinish();
        double t0 = now_ms();
        if (sbfx_render_shadow_map(fx, sun, &map) != SBFX_OK) fprintf(stderr, "bench_shadow: %s\n", sbfx_last_error(fx));
        glFinish();
        double t1 = now_ms();
        /* the fill, before sbfx_render reuses the instances: quad k covers (r sx size) x
         * (r sy size) texels of size^2, sx and sy the lengths of the matrix's first two rows */
        const float *m = map.view_projection;
        double sx = sqrt(m[0] * m[0] + m[4] * m[4] + m[8] * m[8]), sy = sqrt(m[1] * m[1] + m[5] * m[5] + m[9] * m[9]);
        for (int k = 0; k < map.particles; k++) {
            double r = fx->sim->instances[(size_t)k * 5 + 3];
            row->overdraw += r * sx * r * sy / FRAMES;
        }
        if (sbfx_render(fx, &frame) != SBFX_OK) fprintf(stderr, "bench_shadow: %s\n", sbfx_last_error(fx));
        glFinish();
        row->map_ms += (t1 - t0) / FRAMES;
        row->frame_ms += (now_ms() - t1) / FRAMES;
        row->particles += map.particles;
    }
    row->particles /= FRAMES;
    sbfx_destroy(fx);
    row->bytes = map_bytes(path, size);
    return 0;
}

int main(int argc, char **argv)
{
    const char *out = "build/bench";
    for (int i = 1; i + 1 < argc; i++)
        if (strcmp(argv[i], "--out") == 0) out = argv[++i];
    struct egl_headless egl;
    char err[512];
    if (egl_headless_open(&egl, err, sizeof(err)) != 0) {
        fprintf(stderr, "bench_shadow: %s\n", err);
        return 1;
    }
    struct test_scene scene;
    if (test_scene_create(&scene, W, H, err, sizeof(err)) != 0) {
        fprintf(stderr, "bench_shadow: %s\n", err);
        return 1;
    }
    /* the frame's output: an RGBA8 framebuffer (surfaceless EGL has no default one) */
    GLuint out_texture = 0, out_fbo = 0;
    glGenTextures(1, &out_texture);
    glBindTexture(GL_TEXTURE_2D, out_texture);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, W, H);
    glGenFramebuffers(1, &out_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, out_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, out_texture, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    char path[1024];
    snprintf(path, sizeof(path), "%s/shadow.csv", out);
    FILE *csv = fopen(path, "w");
    if (!csv) {
        fprintf(stderr, "bench_shadow: cannot write %s\n", path);
        return 1;
    }
    fprintf(csv, "scene,map_size,map_bytes,particles,fragments_per_texel,map_ms,frame_ms\n");
    printf("shadow map (sbfx_render_shadow_map, %dx%d frame, llvmpipe):\n", W, H);
    printf("  %-10s %5s %10s %9s %9s %8s %10s\n", "scene", "size", "bytes", "particles", "frag/texel", "map ms",
           "frame ms");
    static const char *const scenes[] = {"explosion", "barrage"};
    static const int sizes[] = {128, 256, 512, 1024, 2048};
    int rc = 0;
    for (size_t s = 0; s < sizeof(scenes) / sizeof(scenes[0]); s++)
        for (size_t k = 0; k < sizeof(sizes) / sizeof(sizes[0]); k++) {
            snprintf(path, sizeof(path), "scenes/%s.cfg", scenes[s]);
            shadow_row row;
            if (measure(path, sizes[k], &scene, out_fbo, &row) != 0) {
                rc = 1;
                continue;
            }
            fprintf(csv, "%s,%d,%zu,%d,%.2f,%.3f,%.3f\n", scenes[s], sizes[k], row.bytes, row.particles, row.overdraw,
                    row.map_ms, row.frame_ms);
            printf("  %-10s %5d %10zu %9d %9.1f %8.2f %10.2f\n", scenes[s], sizes[k], row.bytes, row.particles,
                   row.overdraw, row.map_ms, row.frame_ms);
        }
    fclose(csv);
    glDeleteFramebuffers(1, &out_fbo);
    glDeleteTextures(1, &out_texture);
    test_scene_destroy(&scene);
    egl_headless_close(&egl);
    return rc;
}
