/* make bench: does fire read as light? (issue 17 item 2; docs/look-fire.md). The fire-only
 * fireball (tests/look/fireball.cfg) at 0.15 .. 0.5 s and the explosion (scenes/explosion.cfg,
 * over the pixels its fire's emission changes) in its first 0.4 s, each from its camera over the
 * test scene, full-resolution and default (1/4) particle target: the fire pixels' luminance
 * against the sky behind them (tests/look/fire_metric.h).
 *
 *   bench_look_fire [--out DIR] [--size WxH] [--tone-map NAME] [--png FILE]
 * writes DIR/look-fire.csv: scene,view,t,scale,fire_median_ratio,fire_p90_ratio; with --png
 * also FILE, the explosion and the fireball at 0.25 s side by side (default target), the
 * pictures of docs/look-fire.md. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "egl/egl_headless.h"
#include "fire_look.h"
#include "image/png_io.h"

typedef struct plan {
    const char *name, *path;
    int use_fire_mask;
    double times[4];
} plan;

static const plan plans[] = {
    {"fireball", "tests/look/fireball.cfg", 0, {0.15, 0.25, 0.35, 0.5}},
    {"explosion", "scenes/explosion.cfg", 1, {0.1, 0.2, 0.3, 0.4}},
};

static void die(const char *what, const char *why)
{
    fprintf(stderr, "bench_look_fire: %s: %s\n", what, why);
    exit(1);
}

static sbfx_tone_map tone_map_named(const char *name)
{
    static const char *const names[] = {"default", "none", "hue-preserving", "per-channel", "filmic"};
    for (int i = 0; i < SBFX_TONE_MAP_COUNT; i++)
        if (strcmp(name, names[i]) == 0) return (sbfx_tone_map)i;
    die("--tone-map", name);
    return SBFX_TONE_MAP_DEFAULT;
}

static void run_plan(fire_look *l, const plan *p, sbfx_tone_map op, FILE *csv)
{
    char err[512];
    sbfx_scene *scene = NULL;
    if (sbfx_scene_load(p->path, &scene, err, sizeof(err)) != SBFX_OK) die(p->path, err);
    static const int scales[] = {1, 4};
    for (int s = 0; s < 2; s++)
        for (int i = 0; i < 4; i++) {
            fire_ratios r;
            if (fire_look_measure(l, scene, op, p->times[i], scales[s], p->use_fire_mask, &r, err, sizeof(err)) != 0)
                die(p->name, err);
            fprintf(csv, "%s,camera,%.2f,%d,%.4f,%.4f\n", p->name, p->times[i], scales[s], r.median, r.p90);
            printf("  %-9s t %.2f s, scale %d: %6ld fire pixels, luminance / sky behind: median %.2f, p90 %.2f\n",
                   p->name, p->times[i], scales[s], r.pixels, r.median, r.p90);
        }
    sbfx_scene_free(scene);
}

/* The explosion and the fireball at 0.25 s, side by side. */
static void write_pictures(fire_look *l, sbfx_tone_map op, const char *path)
{
    char err[512];
    size_t bytes = (size_t)l->width * l->height * 4;
    uint8_t *frames[2] = {malloc(bytes), malloc(bytes)};
    if (!frames[0] || !frames[1]) die("memory", "out of memory");
    for (int i = 0; i < 2; i++) {
        const plan *p = &plans[1 - i];
        sbfx_scene *scene = NULL;
        fire_ratios r;
        if (sbfx_scene_load(p->path, &scene, err, sizeof(err)) != SBFX_OK) die(p->path, err);
        if (fire_look_measure(l, scene, op, 0.25, 4, p->use_fire_mask, &r, err, sizeof(err)) != 0) die(p->name, err);
        memcpy(frames[i], l->out, bytes);
        sbfx_scene_free(scene);
    }
    if (png_write_contact_sheet(path, (const uint8_t *const *)frames, 2, l->width, l->height, true, l->width, err,
                                sizeof(err)) != 0)
        die(path, err);
    free(frames[0]), free(frames[1]);
}

int main(int argc, char **argv)
{
    const char *out = "build/bench", *png = NULL;
    int width = 960, height = 540;
    sbfx_tone_map op = SBFX_TONE_MAP_DEFAULT;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) out = argv[++i];
        else if (strcmp(argv[i], "--png") == 0 && i + 1 < argc) png = argv[++i];
        else if (strcmp(argv[i], "--tone-map") == 0 && i + 1 < argc) op = tone_map_named(argv[++i]);
        else if (strcmp(argv[i], "--size") == 0 && i + 1 < argc && sscanf(argv[++i], "%dx%d", &width, &height) == 2)
            continue;
        else die("usage", "bench_look_fire [--out DIR] [--size WxH] [--tone-map NAME] [--png FILE]");
    }
    struct egl_headless egl;
    char err[512], path[1024];
    if (egl_headless_open(&egl, err, sizeof(err)) != 0) die("EGL", err);
    fire_look l;
    if (fire_look_open(&l, width, height, err, sizeof(err)) != 0) die("test scene", err);
    snprintf(path, sizeof(path), "%s/look-fire.csv", out);
    FILE *csv = fopen(path, "w");
    if (!csv) die(path, strerror(errno));
    fprintf(csv, "scene,view,t,scale,fire_median_ratio,fire_p90_ratio\n");
    printf("fire as light: fire pixels' luminance against the sky behind them, %dx%d\n", width, height);
    for (size_t i = 0; i < sizeof(plans) / sizeof(plans[0]); i++) run_plan(&l, &plans[i], op, csv);
    fclose(csv);
    if (png) write_pictures(&l, op, png);
    fire_look_close(&l);
    egl_headless_close(&egl);
    return 0;
}
