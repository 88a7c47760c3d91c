/* make bench, the look (issue 17 items 3-4, docs/look.md): how much fine structure each example
 * scene keeps, per view, time and particle target scale, detail on and off.
 *
 * For every shot the full-resolution render with detail is the reference: its effect mask
 * (tests/look/look_metrics.h) is the one every row of that shot is measured over, so the band
 * energies of the other scales and of the detail-off render compare the same pixels.
 *
 *   bench_look [--out DIR] [--size WxH] [--quick] [--png] [--scales N] [--scene NAME]...
 *
 * Writes DIR/look.csv: one row per (scene, view, t, scale, detail) with the columns of
 * `columns[]` below (add a field to look_row and a line there to add a column), the fire
 * luminance ratios (tests/look/fire_metric.h) on the same frame where the shot has fire, and with --png
 * DIR/look-SCENE-VIEW-T-sSCALE[-off].png. Prints a summary per shot. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "egl/egl_headless.h"
#include "fire_metric.h"
#include "look_metrics.h"
#include "look_render.h"
#include "image/png_io.h"

typedef struct look_row {
    const char *scene, *view;
    double t;
    int scale;
    int detail;                   /* 1 on, 0 off */
    double beta, beta_8_32;       /* look_spectrum beta, beta_coarse */
    double band_2_8, band_8_32;   /* relative to the full-resolution reference with detail */
    double e[LOOK_SCALES];        /* E(2) .. E(32) */
    double mask_pixels;
    double render_ms;             /* wall time of sbfx_render (llvmpipe: not a GPU time) */
    double fire_median_ratio, fire_p90_ratio; /* fire pixels' luminance / the sky behind (fire_metric.h) */
    double fire_pixels;           /* how many; all three nan where not measured (no fire in the shot) */
} look_row;

typedef struct column {
    const char *name;
    size_t offset;   /* of a double in look_row, or SIZE_MAX for the fixed ones */
    const char *format;
} column;

#define COL(field, fmt) {#field, offsetof(look_row, field), fmt}
static const column columns[] = {
    {"scene", SIZE_MAX, NULL}, {"view", SIZE_MAX, NULL}, {"t", SIZE_MAX, NULL}, {"scale", SIZE_MAX, NULL},
    {"detail", SIZE_MAX, NULL}, COL(beta, "%.3f"), COL(beta_8_32, "%.3f"), COL(band_2_8, "%.4f"),
    COL(band_8_32, "%.4f"), {"e2", offsetof(look_row, e[0]), "%.4g"}, {"e4", offsetof(look_row, e[1]), "%.4g"},
    {"e8", offsetof(look_row, e[2]), "%.4g"}, {"e16", offsetof(look_row, e[3]), "%.4g"},
    {"e32", offsetof(look_row, e[4]), "%.4g"}, COL(mask_pixels, "%.0f"), COL(render_ms, "%.1f"),
    COL(fire_median_ratio, "%.4f"), COL(fire_p90_ratio, "%.4f"), COL(fire_pixels, "%.0f"),
};
#define COLUMN_COUNT (sizeof columns / sizeof columns[0])

static void write_header(FILE *f)
{
    for (size_t c = 0; c < COLUMN_COUNT; c++) fprintf(f, "%s%s", c ? "," : "", columns[c].name);
    fputc('\n', f);
}

static void write_row(FILE *f, const look_row *r)
{
    fprintf(f, "%s,%s,%.3f,%d,%d", r->scene, r->view, r->t, r->scale, r->detail);
    for (size_t c = 5; c < COLUMN_COUNT; c++) {
        double v = *(const double *)((const char *)r + columns[c].offset);
        fputc(',', f);
        if (isfinite(v)) fprintf(f, columns[c].format, v);
        else fputs("nan", f);
    }
    fputc('\n', f);
}

typedef struct view {
    const char *name;
    float azimuth_offset;
} view;

typedef struct plan {
    const char *scene;
    double times[2];
} plan;

static const view views[] = {{"default", 0.0f}, {"az+100", 100.0f}, {"az-140", -140.0f}};
static const plan plans[] = {
    {"explosion", {2.2, 1.5}}, {"smoke", {3.0, 4.5}}, {"dust-storm", {2.5, 4.0}}, {"campfire", {2.0, 3.5}},
    {"barrage", {1.5, 2.5}},   {"lit-smoke", {3.0, 5.0}}, {"post", {1.5, 2.2}},
};

typedef struct options {
    const char *out;
    int width, height;
    bool quick, png;
    int scales; /* the first this many of 1, 2, 4, 8 (--scales N; --quick: 3) */
    const char *only[8];
    int only_count;
} options;

static void die(const char *what, const char *why)
{
    fprintf(stderr, "bench_look: %s: %s\n", what, why);
    exit(1);
}

static options parse(int argc, char **argv)
{
    options o = {"build/bench", 960, 540, false, false, 4, {0}, 0};
    for (int i = 1; i < argc; i++) {
        bool more = i + 1 < argc;
        if (!strcmp(argv[i], "--out") && more) o.out = argv[++i];
        else if (!strcmp(argv[i], "--size") && more && sscanf(argv[++i], "%dx%d", &o.width, &o.height) == 2) {}
        else if (!strcmp(argv[i], "--quick")) o.quick = true;
        else if (!strcmp(argv[i], "--png")) o.png = true;
        else if (!strcmp(argv[i], "--scales") && more) o.scales = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--scene") && more && o.only_count < 8) o.only[o.only_count++] = argv[++i];
        else die("usage", "bench_look [--out DIR] [--size WxH] [--quick] [--png] [--scales 1..4] [--scene NAME]...");
    }
    if (o.quick && o.scales > 3) o.scales = 3;
    if (o.scales < 1 || o.scales > 4) die("options", "--scales 1..4");
    if (o.width < 64 || o.height < 64 || o.width > 4096 || o.height > 4096) die("options", "--size 64x64..4096x4096");
    return o;
}

static bool wanted(const options *o, const char *scene)
{
    if (!o->only_count) return true;
    for (int i = 0; i < o->only_count; i++)
        if (!strcmp(o->only[i], scene)) return true;
    return false;
}

static void save_png(const options *o, const look_renderer *r, const look_row *row)
{
    char path[1024], err[256];
    snprintf(path, sizeof path, "%s/look-%s-%s-%.2f-s%d%s.png", o->out, row->scene, row->view, row->t, row->scale,
             row->detail ? "" : "-off");
    if (png_write_rgba(path, r->out_rgba, r->width, r->height, true, err, sizeof err) != 0)
        fprintf(stderr, "bench_look: %s\n", err);
}

/* The fire luminance ratios of the frame just rendered (r->out_rgba, the shot `lit`): the same
 * shot again with the fire's emission off gives the pixels the fire's light changes
 * (fire_metric_mask, as bench_look_fire does for the explosion); over those, the output's
 * luminance against the background's. Leaves r->out_rgba as it found it. */
static void measure_fire(look_renderer *r, const look_shot *lit, uint8_t *frame, uint8_t *fire_mask, look_row *row)
{
    size_t bytes = (size_t)r->width * r->height * 4;
    char err[512];
    memcpy(frame, r->out_rgba, bytes);
    look_shot dark = *lit;
    dark.fire_dark = true;
    if (look_render(r, &dark, err, sizeof err) != 0) die("fire", err);
    fire_metric_mask(frame, r->out_rgba, r->width, r->height, fire_mask);
    fire_ratios fr;
    fire_metric_ratios(frame, r->background_rgba, fire_mask, r->width, r->height, &fr); /* none: nan ratios */
    row->fire_median_ratio = fr.median;
    row->fire_p90_ratio = fr.p90;
    row->fire_pixels = (double)fr.pixels;
    memcpy(r->out_rgba, frame, bytes);
}

/* One shot at every scale and detail setting, measured over the reference's mask. The fire
 * ratios are measured on every row of a shot whose reference frame (full resolution, detail on)
 * has fire pixels; the other shots' rows have nan there. */
static void run_shot(const options *o, look_renderer *r, FILE *csv, const plan *p, const view *v, double t)
{
    static const int scales[] = {1, 2, 4, 8};
    size_t n = (size_t)r->width * r->height;
    uint8_t *mask = malloc(n), *fire_mask = malloc(n), *frame = malloc(n * 4);
    double *y = malloc(n * sizeof(double));
    if (!mask || !fire_mask || !frame || !y) die("memory", "out of memory");
    bool fire = true; /* until the reference frame shows none */
    char path[256], err[512];
    snprintf(path, sizeof path, "scenes/%s.cfg", p->scene);
    look_spectrum ref = {0};
    int nscales = o->scales;
    for (int detail = 1; detail >= 0; detail--)
        for (int s = 0; s < nscales; s++) {
            if (!detail && s > 0) continue; /* detail off: full resolution */
            look_shot shot = {path, t, v->azimuth_offset, scales[s], !detail, NULL, false, 1, false};
            if (look_render(r, &shot, err, sizeof err) != 0) die(p->scene, err);
            if (detail && s == 0) look_effect_mask(r->out_rgba, r->background_rgba, r->width, r->height, mask);
            look_luminance(r->out_rgba, n, y);
            look_spectrum sp;
            if (look_measure(y, mask, r->width, r->height, &sp) != 0) die("measure", "out of memory");
            if (detail && s == 0) ref = sp;
            look_row row = {p->scene, v->name, t, scales[s], detail, sp.beta, sp.beta_coarse,
                            look_band_fine(&sp) / look_band_fine(&ref), look_band_coarse(&sp) / look_band_coarse(&ref),
                            {0}, (double)sp.mask_pixels, r->particle_ms, NAN, NAN, NAN};
            memcpy(row.e, sp.energy, sizeof row.e);
            if (fire) measure_fire(r, &shot, frame, fire_mask, &row);
            if (detail && s == 0) fire = row.fire_pixels > 0;
            write_row(csv, &row);
            fflush(csv);
            printf("look: %-10s %-8s t=%.2f scale %d detail %-3s beta %.2f (8-32 px %.2f) bands 2-8 %.2f 8-32 %.2f "
                   "mask %zu (%zu at 32 px)  %.0f ms  fire / sky %.2f p90 %.2f\n", p->scene, v->name, t, scales[s],
                   detail ? "on" : "off", sp.beta, sp.beta_coarse, row.band_2_8, row.band_8_32, sp.mask_pixels,
                   sp.pixels[LOOK_SCALES - 1], row.render_ms, row.fire_median_ratio, row.fire_p90_ratio);
            fflush(stdout);
            if (o->png) save_png(o, r, &row);
        }
    free(mask);
    free(fire_mask);
    free(frame);
    free(y);
}

/* What the detail costs: the default target (scale 4) and full resolution, the explosion at its
 * first time, sbfx_render's wall time (median of 7, after one warm-up) with the detail and with
 * programs built without it (strengths 0, reloaded). llvmpipe: CPU time, not a GPU's. */
static void run_cost(look_renderer *r, FILE *f)
{
    static const int scales[] = {4, 1};
    char err[512];
    for (int s = 0; s < 2; s++) {
        double ms[2];
        for (int unloaded = 0; unloaded < 2; unloaded++) {
            look_shot shot = {"scenes/explosion.cfg", plans[0].times[0], 0.0f, scales[s], false, NULL, unloaded != 0, 8,
                              false};
            if (look_render(r, &shot, err, sizeof err) != 0) die("cost", err);
            ms[unloaded] = r->particle_ms;
        }
        fprintf(f, "detail cost: explosion t=%.2f scale %d: sbfx_render %.1f ms with detail, %.1f ms without: "
                   "the detail's share %.0f %%\n", plans[0].times[0], scales[s], ms[0], ms[1],
                100.0 * (ms[0] - ms[1]) / ms[0]);
    }
}

int main(int argc, char **argv)
{
    options o = parse(argc, argv);
    struct egl_headless egl;
    char err[512];
    if (egl_headless_open(&egl, err, sizeof err) != 0) die("EGL", err);
    look_renderer r;
    if (look_renderer_open(&r, o.width, o.height, err, sizeof err) != 0) die("renderer", err);
    char path[1024];
    snprintf(path, sizeof path, "%s/look.csv", o.out);
    FILE *csv = fopen(path, "w");
    if (!csv) die(path, "cannot write");
    write_header(csv);
    for (size_t p = 0; p < sizeof plans / sizeof plans[0]; p++) {
        if (!wanted(&o, plans[p].scene)) continue;
        int nviews = o.quick ? 1 : (int)(sizeof views / sizeof views[0]);
        for (int v = 0; v < nviews; v++)
            for (int k = 0; k < (o.quick ? 1 : 2); k++) run_shot(&o, &r, csv, &plans[p], &views[v], plans[p].times[k]);
    }
    fclose(csv);
    snprintf(path, sizeof path, "%s/look.txt", o.out);
    FILE *txt = fopen(path, "w");
    if (!txt) die(path, "cannot write");
    if (!o.only_count || wanted(&o, "explosion")) run_cost(&r, txt);
    fclose(txt);
    snprintf(path, sizeof path, "%s/look.csv", o.out);
    look_renderer_close(&r);
    egl_headless_close(&egl);
    printf("bench_look: %s\n", path);
    return 0;
}
