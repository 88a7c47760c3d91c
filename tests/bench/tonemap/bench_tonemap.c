/* make bench, display block (issue 12): what each tone map (sbfx_tone_map) does to the particles'
 * light on an 8-bit display, on the explosion and barrage scenes seen from their cameras.
 *
 * Every frame is composited into a half-float host framebuffer, so the value an RGBA8
 * framebuffer would have clamped is still there, over the test scene (and over black, where the
 * composite shows the particles' light alone):
 *   - particle pixels: those the composite changed by more than half an 8-bit level;
 *   - clipped: particle pixels with a channel above 1 (+ half a level): the display clamps it,
 *     one channel on its own;
 *   - fire pixels: where the fire's own emission is at least a third of the light on display
 *     (over black, `none` with and without the fire's emission gives it; in these scenes the fire
 *     rarely makes half of a pixel's light: the scene shows through it, and dust and smoke lit by
 *     the blasts' flashes, the brightest light here, lie in front) and the displayed luminance
 *     is above 0.05;
 *   - their chromaticity distance: the displayed colour (clamped, 8-bit) read as linear sRGB
 *     (the module's convention: README "Colour on the display"), to CIE 1976 u'v', the shortest
 *     distance to the Planckian locus (CIE 1931 2° CMFs, 500..25000 K); mean, median, 95th
 *     percentile. The row "unclamped" is the same for the light before any display, the best a
 *     display could show (the fire's light mixed with what lies in front of it and behind).
 *
 *   bench_tonemap [--out DIR] [--size WxH]     writes DIR/tonemap.csv and DIR/tonemap.txt */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "egl/egl_headless.h"
#include "internal.h"
#include "host/test_scene.h"

#define LOCUS_POINTS 4096
#define FIRE_SHARE (1.0 / 3.0)
#define MIN_LUMINANCE 0.05
#define OPERATORS 3

static const sbfx_tone_map operators[OPERATORS] = {SBFX_TONE_MAP_NONE, SBFX_TONE_MAP_HUE_PRESERVING,
                                                   SBFX_TONE_MAP_PER_CHANNEL};
static const char *const operator_names[OPERATORS] = {"none", "hue-preserving", "per-channel"};

typedef struct scene_plan {
    const char *name;
    double times[4];
    int frames;
} scene_plan;

static const scene_plan plans[] = {
    {"explosion", {0.15, 0.3, 0.6, 1.0}, 4},
    {"barrage", {0.6, 1.2, 1.8, 2.4}, 4},
};

typedef struct stats {
    long particle_pixels, clipped, fire_pixels;
    double *duv;           /* one per fire pixel */
    double luminance_sum;  /* of the fire pixels as displayed: how bright the fire looks */
} stats;

typedef struct bench {
    int width, height;
    double locus[LOCUS_POINTS][2];
    GLuint out_fbo, out_texture;
    struct test_scene scene;
    float *over_scene[OPERATORS + 1]; /* per operator, then the scene alone */
    float *over_black[OPERATORS + 1]; /* per operator, then `none` without the fire's emission */
} bench;

static void die(const char *what, const char *why)
{
    fprintf(stderr, "bench_tonemap: %s: %s\n", what, why);
    exit(1);
}

static void *xcalloc(size_t n, size_t size)
{
    void *p = calloc(n, size);
    if (!p) die("memory", "out of memory");
    return p;
}

/* ---- colour ----------------------------------------------------------------------------- */

static void xyz_to_uv(const double xyz[3], double uv[2])
{
    double d = xyz[0] + 15.0 * xyz[1] + 3.0 * xyz[2];
    uv[0] = d > 0 ? 4.0 * xyz[0] / d : 0.0;
    uv[1] = d > 0 ? 9.0 * xyz[1] / d : 0.0;
}

static void srgb_to_uv(const double rgb[3], double uv[2])
{
    /* IEC 61966-2-1 linear sRGB -> XYZ */
    double xyz[3] = {0.4124 * rgb[0] + 0.3576 * rgb[1] + 0.1805 * rgb[2],
                     0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2],
                     0.0193 * rgb[0] + 0.1192 * rgb[1] + 0.9505 * rgb[2]};
    xyz_to_uv(xyz, uv);
}

static double luminance(const double rgb[3]) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

/* The Planckian locus, uniform in 1/T from 500 to 25000 K. */
static void make_locus(bench *b)
{
    static sbfx_cmf cmf;
    char err[256];
    if (sbfx_cmf_load(SBFX_CMF_DEFAULT_PATH, &cmf, err, sizeof(err)) != SBFX_OK) die("CIE tables", err);
    for (int i = 0; i < LOCUS_POINTS; i++) {
        double w = 1.0 / 25000.0 + (1.0 / 500.0 - 1.0 / 25000.0) * i / (LOCUS_POINTS - 1), xyz[3];
        sbfx_blackbody_xyz(&cmf, 1.0 / w, xyz);
        xyz_to_uv(xyz, b->locus[i]);
    }
}

static double locus_distance(const bench *b, const double uv[2])
{
    double best = INFINITY;
    for (int i = 0; i + 1 < LOCUS_POINTS; i++) { /* to each segment of the polyline */
        const double *p = b->locus[i], *q = b->locus[i + 1];
        double dx = q[0] - p[0], dy = q[1] - p[1], len2 = dx * dx + dy * dy;
        double t = len2 > 0 ? ((uv[0] - p[0]) * dx + (uv[1] - p[1]) * dy) / len2 : 0.0;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        double ex = uv[0] - p[0] - t * dx, ey = uv[1] - p[1] - t * dy;
        best = fmin(best, ex * ex + ey * ey);
    }
    return sqrt(best);
}

/* ---- rendering -------------------------------------------------------------------------- */

static void open_target(bench *b)
{
    glGenTextures(1, &b->out_texture);
    glBindTexture(GL_TEXTURE_2D, b->out_texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, b->width, b->height, 0, GL_RGBA, GL_HALF_FLOAT, NULL);
    glGenFramebuffers(1, &b->out_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, b->out_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, b->out_texture, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        die("GL", "RGBA16F is not colour-renderable here (GL_EXT_color_buffer_half_float): the unclamped "
                  "composite cannot be read");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

static void log_warning(sbfx_log_level level, const char *message, void *user)
{
    (void)user;
    if (level != SBFX_LOG_INFO) fprintf(stderr, "bench_tonemap: sbfx: %s\n", message);
}

static sbfx *create(const sbfx_scene *scene, sbfx_tone_map op)
{
    sbfx *fx = NULL;
    sbfx_desc desc = {.scene = scene, .tone_map = op, .log = log_warning};
    sbfx_result r = sbfx_create(&desc, &fx);
    if (r != SBFX_OK) die("sbfx_create", sbfx_result_string(r));
    return fx;
}

static void advance_to(sbfx *fx, double t)
{
    const double step = (double)(1.0f / 120.0f);
    while (sbfx_time(fx) < t - 1e-9) sbfx_update(fx, step);
}

static void read_out(const bench *b, float *out)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, b->out_fbo);
    glReadPixels(0, 0, b->width, b->height, GL_RGBA, GL_FLOAT, out);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

/* The scene's picture (or black) into the host target, then sbfx over it (or nothing). */
static void composite(bench *b, sbfx *fx, const sbfx_frame *frame, bool over_scene, float *out)
{
    if (over_scene) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, b->scene.framebuffer);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, b->out_fbo);
        glBlitFramebuffer(0, 0, b->width, b->height, 0, 0, b->width, b->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    } else {
        glBindFramebuffer(GL_FRAMEBUFFER, b->out_fbo);
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (fx && sbfx_render(fx, frame) != SBFX_OK) die("sbfx_render", sbfx_last_error(fx));
    read_out(b, out);
}

/* ---- measuring -------------------------------------------------------------------------- */

static double displayed(float v) { return round(fmin(fmax(v, 0.0f), 1.0f) * 255.0) / 255.0; }

/* Over the scene: which pixels the particles change, which of them clip. */
static void measure_clipping(const bench *b, stats st[OPERATORS + 1])
{
    const float *scene = b->over_scene[OPERATORS];
    for (size_t i = 0; i < (size_t)b->width * b->height; i++) {
        double change = 0;
        for (int k = 0; k < 3; k++) change = fmax(change, fabs(b->over_scene[0][4 * i + k] - scene[4 * i + k]));
        if (change <= 0.5 / 255.0) continue;
        for (int o = 0; o < OPERATORS; o++) {
            const float *px = b->over_scene[o] + 4 * i;
            st[o].particle_pixels++;
            st[o].clipped += px[0] > 1.0f + 0.5f / 255.0f || px[1] > 1.0f + 0.5f / 255.0f || px[2] > 1.0f + 0.5f / 255.0f;
        }
    }
}

/* The fire pixels: where the fire's own emission (over black the composite shows the particles'
 * light alone: `none` with and without the fire's emission) is at least FIRE_SHARE of the light
 * displayed over the scene; their displayed colour's distance from the locus. */
static void measure_fire(const bench *b, stats st[OPERATORS + 1])
{
    const float *shown = b->over_scene[0], *with_fire = b->over_black[0], *no_fire = b->over_black[OPERATORS];
    for (size_t i = 0; i < (size_t)b->width * b->height; i++) {
        double light[3], fire[3];
        for (int k = 0; k < 3; k++) light[k] = shown[4 * i + k], fire[k] = with_fire[4 * i + k] - no_fire[4 * i + k];
        if (!(luminance(fire) >= FIRE_SHARE * luminance(light))) continue;
        for (int o = 0; o <= OPERATORS; o++) {
            const float *px = b->over_scene[o < OPERATORS ? o : 0] + 4 * i;
            double rgb[3], uv[2];
            for (int k = 0; k < 3; k++) rgb[k] = o < OPERATORS ? displayed(px[k]) : px[k]; /* the last: unclamped */
            if (luminance(rgb) <= MIN_LUMINANCE) continue;
            srgb_to_uv(rgb, uv);
            st[o].luminance_sum += luminance(rgb);
            st[o].duv[st[o].fire_pixels++] = locus_distance(b, uv);
        }
    }
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void report(const char *scene, const char *name, stats *s, FILE *csv, FILE *txt)
{
    qsort(s->duv, (size_t)s->fire_pixels, sizeof(double), compare_doubles);
    double sum = 0;
    for (long i = 0; i < s->fire_pixels; i++) sum += s->duv[i];
    long n = s->fire_pixels;
    double mean = n ? sum / n : NAN, median = n ? s->duv[n / 2] : NAN, p95 = n ? s->duv[(long)(0.95 * (n - 1))] : NAN;
    double share = s->particle_pixels ? (double)s->clipped / s->particle_pixels : NAN;
    double fire_y = n ? s->luminance_sum / n : NAN;
    fprintf(csv, "%s,%s,%ld,%ld,%.4f,%ld,%.5f,%.5f,%.5f,%.4f\n", scene, name, s->particle_pixels, s->clipped, share, n,
            mean, median, p95, fire_y);
    char clipped[48] = "light before display:     ";
    if (strcmp(name, "unclamped") != 0) snprintf(clipped, sizeof(clipped), "clipped %5.1f %% of %7ld,", 100.0 * share,
                                                 s->particle_pixels);
    fprintf(txt, "  %-9s %-14s %s fire pixels %5ld: du'v' to the Planckian locus mean %.4f, median %.4f, 95th "
                 "percentile %.4f; mean luminance %.3f\n", scene, name, clipped, n, mean, median, p95, fire_y);
}

static void run_scene(bench *b, const scene_plan *plan, FILE *csv, FILE *txt)
{
    char path[256], err[512];
    snprintf(path, sizeof(path), "scenes/%s.cfg", plan->name);
    sbfx_scene *scene = NULL;
    if (sbfx_scene_load(path, &scene, err, sizeof(err)) != SBFX_OK) die(path, err);
    sbfx_scene_camera camera;
    sbfx_scene_camera_get(scene, &camera);
    sbfx *fx[OPERATORS + 1];
    for (int o = 0; o < OPERATORS; o++) fx[o] = create(scene, operators[o]);
    fx[OPERATORS] = create(scene, SBFX_TONE_MAP_NONE); /* its fire's emission is set to 0 */
    sbfx_media(fx[OPERATORS])[SBFX_FIRE].emission_scale = 0.0f;
    sbfx_scene_free(scene);
    stats st[OPERATORS + 1];
    size_t capacity = (size_t)b->width * b->height * plan->frames;
    for (int o = 0; o <= OPERATORS; o++) st[o] = (stats){.duv = xcalloc(capacity, sizeof(double))};
    for (int f = 0; f < plan->frames; f++) {
        double t = plan->times[f];
        sbfx_frame frame = {.scene_color_texture = b->scene.color_texture, .scene_depth_texture = b->scene.depth_texture,
                            .out_framebuffer = b->out_fbo, .width = b->width, .height = b->height};
        test_scene_camera(&camera, t, (float)b->width / b->height, frame.view, frame.projection);
        if (test_scene_draw(&b->scene, frame.view, frame.projection) != 0) die("test scene", "GL error");
        for (int o = 0; o <= OPERATORS; o++) {
            advance_to(fx[o], t);
            if (o < OPERATORS) composite(b, fx[o], &frame, true, b->over_scene[o]);
            composite(b, fx[o], &frame, false, b->over_black[o]);
        }
        composite(b, NULL, &frame, true, b->over_scene[OPERATORS]);
        measure_clipping(b, st);
        measure_fire(b, st);
    }
    for (int o = 0; o <= OPERATORS; o++) {
        report(plan->name, o < OPERATORS ? operator_names[o] : "unclamped", &st[o], csv, txt);
        free(st[o].duv);
        sbfx_destroy(fx[o]);
    }
}

int main(int argc, char **argv)
{
    const char *out = "build/bench";
    bench *b = xcalloc(1, sizeof(*b));
    b->width = 960, b->height = 540;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) out = argv[++i];
        else if (strcmp(argv[i], "--size") == 0 && i + 1 < argc && sscanf(argv[++i], "%dx%d", &b->width, &b->height) == 2) continue;
        else die("usage", "bench_tonemap [--out DIR] [--size WxH]");
    }
    struct egl_headless egl;
    char err[512], path[1024];
    if (egl_headless_open(&egl, err, sizeof(err)) != 0) die("EGL", err);
    make_locus(b);
    open_target(b);
    if (test_scene_create(&b->scene, b->width, b->height, err, sizeof(err)) != 0) die("test scene", err);
    for (int i = 0; i <= OPERATORS; i++) {
        b->over_scene[i] = xcalloc((size_t)b->width * b->height * 4, sizeof(float));
        b->over_black[i] = xcalloc((size_t)b->width * b->height * 4, sizeof(float));
    }
    snprintf(path, sizeof(path), "%s/tonemap.csv", out);
    FILE *csv = fopen(path, "w");
    snprintf(path, sizeof(path), "%s/tonemap.txt", out);
    FILE *txt = fopen(path, "w");
    if (!csv || !txt) die(out, strerror(errno));
    fprintf(csv, "scene,tone_map,particle_pixels,clipped,clipped_share,fire_pixels,duv_mean,duv_median,duv_p95,fire_luminance\n");
    fprintf(txt, "display: particle pixels with a clipped channel, and the displayed fire pixels' distance from the "
                 "black-body locus (CIE 1976 u'v'), %dx%d, each scene from its camera\n", b->width, b->height);
    for (size_t i = 0; i < sizeof(plans) / sizeof(plans[0]); i++) run_scene(b, &plans[i], csv, txt);
    fclose(csv);
    fclose(txt);
    for (int i = 0; i <= OPERATORS; i++) free(b->over_scene[i]), free(b->over_black[i]);
    test_scene_destroy(&b->scene);
    glDeleteFramebuffers(1, &b->out_fbo);
    glDeleteTextures(1, &b->out_texture);
    egl_headless_close(&egl);
    free(b);
    snprintf(path, sizeof(path), "%s/tonemap.txt", out);
    FILE *f = fopen(path, "r");
    for (int c; f && (c = fgetc(f)) != EOF;) putchar(c);
    if (f) fclose(f);
    return 0;
}
