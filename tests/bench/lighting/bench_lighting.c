/* make bench, lighting block: what per-pixel lit smoke (the lit-smoke seed) costs, and how the
 * ray march's step count trades time for accuracy.
 *
 * 1. A fixed arrangement of lit smoke particles (view space, four lights: points behind and in
 *    front, a sun, a backlight) is rendered for several step settings [nMin, nMax] and with the
 *    phase-function model. Each lit image (the particle target, RGBA32F) is compared with the
 *    CPU reference (ref/lit_ref.c, double) composited back to front the module's way:
 *    - mean_abs_err, max_abs_err: against the reference with 512 steps (the march's error plus
 *      the GPU's own), premultiplied radiance over the pixels some particle covers;
 *    - gpu_cpu_err: mean against the reference at the row's own steps (the GPU's own error:
 *      mostly llvmpipe returning filtered RGBA8 at 8-bit precision);
 *    - ref_mean: the reference's mean radiance over those pixels, the scale of the errors.
 * 2. scenes/lit-smoke.cfg over the test scene at 960x540, 1.5 s in, with its smoke lit and
 *    switched to "phase": the scene's frame cost, lit beside unlit.
 * Times are glFinish-bracketed wall time of one sbfx_render (median of --reps, with min and
 * max). Every configuration is built first and the repetitions go round robin, so that the load
 * of a shared machine falls on all of them alike.
 *
 *   bench_lighting [--out DIR] [--reps N]      writes DIR/lighting.csv (build/bench) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "egl/egl_headless.h"
#include "internal.h"
#include "lit_ref.h"
#include "reference.h"
#include "host/test_scene.h"

#define WIDTH 960
#define HEIGHT 540
#ifndef DIVISOR
#define DIVISOR 4
#endif
#ifndef PARTICLES
#define PARTICLES 40
#endif
#define REFERENCE_STEPS 512
#define SCENE_TIME 1.5

typedef struct bench {
    sbfx_frame frame;
    GLuint depth_texture, out_fbo, out_rb;
    sbfx_view_particle particles[PARTICLES];
    sbfx_view_light lights[4];
    float ambient[3];
    int reps;
} bench;

typedef struct timing { double median, min, max; } timing;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static timing summarise(double *ms, int n)
{
    qsort(ms, (size_t)n, sizeof(*ms), compare_doubles);
    return (timing){ms[n / 2], ms[0], ms[n - 1]};
}

/* ---- set-up ---------------------------------------------------------------------------- */

static void make_targets(bench *b)
{
    const float far_depth = 1.0f;
    float *depth = malloc(sizeof(float) * WIDTH * HEIGHT);
    for (int i = 0; i < WIDTH * HEIGHT; i++) depth[i] = far_depth; /* nothing opaque: far */
    glGenTextures(1, &b->depth_texture);
    glBindTexture(GL_TEXTURE_2D, b->depth_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, WIDTH, HEIGHT, 0, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    free(depth);
    glGenRenderbuffers(1, &b->out_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, b->out_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, WIDTH, HEIGHT);
    glGenFramebuffers(1, &b->out_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, b->out_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, b->out_rb);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    b->frame = (sbfx_frame){.scene_depth_texture = b->depth_texture, .out_framebuffer = b->out_fbo,
                            .width = WIDTH, .height = HEIGHT};
    b->frame.view[0] = b->frame.view[5] = b->frame.view[10] = b->frame.view[15] = 1.0f;
    sbfx_perspective(b->frame.projection, 50.0f * (float)M_PI / 180.0f, (float)WIDTH / HEIGHT, 0.1f, 200.0f);
}

/* A column of smoke 6-9 m away, lit from behind-left, front-right, above and straight behind. */
static void make_arrangement(bench *b)
{
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 2026);
    for (int i = 0; i < PARTICLES; i++)
        b->particles[i] = (sbfx_view_particle){
            .center = {(float)sbfx_rng_range(&rng, -1.4, 1.4), (float)sbfx_rng_range(&rng, -1.6, 1.8),
                       (float)sbfx_rng_range(&rng, -9.0, -6.0)},
            .radius = (float)sbfx_rng_range(&rng, 0.7, 1.4),
            .detail = {(float)sbfx_rng_uniform(&rng), 0.0f, 0.0f},
            .intensity = (float)sbfx_rng_range(&rng, 0.6, 1.0), .medium = SBFX_SMOKE};
    const sbfx_view_light lights[4] = {{{-2.5f, 1.0f, -11.0f, 1.0f}, {30.0f, 22.0f, 14.0f}},
                                       {{2.5f, 0.5f, -3.5f, 1.0f}, {6.0f, 6.0f, 7.0f}},
                                       {{-0.3f, -0.9f, -0.3f, 0.0f}, {0.4f, 0.4f, 0.45f}},
                                       {{0.0f, 0.0f, 1.0f, 0.0f}, {0.5f, 0.45f, 0.4f}}};
    memcpy(b->lights, lights, sizeof(lights));
    b->ambient[0] = 0.15f, b->ambient[1] = 0.16f, b->ambient[2] = 0.2f;
}

static sbfx *module_for(const char *scene_text, sbfx_target_format format)
{
    char err[512];
    sbfx_scene *scene = NULL;
    if (sbfx_scene_parse(scene_text, "bench-lighting", &scene, err, sizeof(err)) != SBFX_OK) {
        fprintf(stderr, "bench_lighting: %s\n", err);
        exit(1);
    }
    sbfx *fx = NULL;
    /* the reference's alpha is the spherical model's: the GPU's the same (the lighting is measured) */
    sbfx_desc desc = {.scene = scene, .target_divisor = DIVISOR, .target_format = format, .max_particles = 64,
                      .opacity = SBFX_OPACITY_SPHERICAL};
    sbfx_result r = sbfx_create(&desc, &fx);
    sbfx_scene_free(scene);
    if (r != SBFX_OK) {
        fprintf(stderr, "bench_lighting: sbfx_create: %s\n", sbfx_result_string(r));
        exit(1);
    }
    return fx;
}

/* The arrangement's medium: detail off, so the CPU needs no detail volume. */
static void arrangement_scene(char *out, size_t n, bool lit, int nmin, int nmax)
{
    snprintf(out, n,
             "media = { smoke = { albedo = 0.85; density = 0.6; color = [1.0, 1.0, 1.0];\n"
             "  lighting = \"%s\"; wrap = 0.6; translucency = 2.0; dampening = 0.0; steps = [%d, %d];\n"
             "  texture = { size = 128; variants = 4; }; detail = { strength = 0.0; }; }; };\n"
             "effects = { e = { steps = ( { type = \"emitter\"; medium = \"smoke\"; count = 1; } ); }; };\n",
             lit ? "lit" : "phase", nmin, nmax);
}

/* ---- CPU reference of the arrangement -------------------------------------------------- */

typedef struct cpu_texture {
    uint8_t *texels;
    sbfx_smoke_texture tex;
} cpu_texture;

static cpu_texture cpu_smoke(const sbfx_medium_params *m, uint32_t seed)
{
    cpu_texture t = {malloc(sbfx_smoke_texture_bytes(m->texture_size, m->texture_variants)), {0}};
    float *scratch = malloc(sizeof(float) * sbfx_smoke_scratch_floats(m->texture_size));
    sbfx_smoke_texture_generate(m->texture_size, m->texture_variants, sbfx_smoke_texture_seed(seed, SBFX_SMOKE),
                                t.texels, scratch);
    free(scratch);
    t.tex = (sbfx_smoke_texture){m->texture_size, 2 * m->texture_variants, sbfx_smoke_texture_levels(m->texture_size),
                                 t.texels};
    return t;
}

/* Back to front as src/sim/sort.c orders them: by float distance, far first, stable. */
static void cpu_order(const bench *b, int order[PARTICLES])
{
    float key[PARTICLES];
    for (int i = 0; i < PARTICLES; i++) {
        const float *c = b->particles[i].center;
        key[i] = sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        order[i] = i;
    }
    for (int i = 1; i < PARTICLES; i++) /* insertion sort: stable, 40 items */
        for (int j = i; j > 0 && key[order[j - 1]] < key[order[j]]; j--) {
            int t = order[j];
            order[j] = order[j - 1], order[j - 1] = t;
        }
}

/* Premultiplied radiance of the target (tw x th, RGB) at the given steps. */
static void cpu_render(const bench *b, const sbfx_medium_params *mp, const sbfx_smoke_texture *tex, int nmin,
                       int nmax, int tw, int th, double *rgb_out)
{
    const float *p = b->frame.projection;
    double near = p[14] / (p[10] - 1.0), slope = 2.0 / (tw * p[0]);
    sbfx_lit_light lights[4];
    for (int i = 0; i < 4; i++) {
        double len = b->lights[i].vector[3] > 0.5f ? 1.0 : sqrt(pow(b->lights[i].vector[0], 2) +
                                                               pow(b->lights[i].vector[1], 2) +
                                                               pow(b->lights[i].vector[2], 2));
        for (int k = 0; k < 3; k++) lights[i].vector[k] = (float)(b->lights[i].vector[k] / len);
        lights[i].vector[3] = b->lights[i].vector[3];
        for (int k = 0; k < 3; k++) lights[i].color[k] = b->lights[i].color[k];
    }
    const double ambient[3] = {b->ambient[0], b->ambient[1], b->ambient[2]};
    int order[PARTICLES];
    cpu_order(b, order);
    for (int y = 0; y < th; y++)
        for (int x = 0; x < tw; x++) {
            sbfx_ref_pixel px = {{((x + 0.5) / tw * 2 - 1 + p[8]) / p[0], ((y + 0.5) / th * 2 - 1 + p[9]) / p[5], -1},
                                 INFINITY, near, 0}; /* nothing opaque: no surface */
            double sum[3] = {0, 0, 0};
            for (int i = 0; i < PARTICLES; i++) {
                const sbfx_view_particle *v = &b->particles[order[i]];
                double tau = mp->tau * v->intensity, c[3] = {v->center[0], v->center[1], v->center[2]};
                sbfx_ref_particle rp = {{c[0], c[1], c[2]}, v->radius, tau};
                double alpha = sbfx_ref_opacity(SBFX_OPACITY_SPHERICAL, &rp, &px), l[3];
                if (alpha <= 0.0) continue;
                sbfx_lit_medium m = {{mp->albedo * mp->color[0], mp->albedo * mp->color[1], mp->albedo * mp->color[2]},
                                     tau, mp->wrap, mp->translucency, mp->dampening, nmin, nmax};
                sbfx_lit_radiance(&m, tex, sbfx_lit_variant(v->detail[0], mp->texture_variants),
                                  sbfx_lit_lod(tex->size, v->radius, -c[2], slope), c, v->radius, px.ray, lights, 4,
                                  ambient, l);
                for (int k = 0; k < 3; k++) sum[k] = alpha * l[k] + sum[k] * (1.0 - alpha);
            }
            memcpy(&rgb_out[3 * (y * tw + x)], sum, sizeof(sum));
        }
}

/* ---- timing: every configuration built first, repetitions interleaved ------------------ */

/* One timed configuration: the arrangement in one lighting setting, or the example scene. */
typedef struct job {
    const char *name, *model;
    int steps[2];
    sbfx *fx;
    bool scene;          /* sbfx_render of a simulated scene, else the fixed arrangement */
    sbfx_frame frame;    /* scene jobs */
    double ms[256];
    timing t;
} job;

static void render_job(bench *b, job *j)
{
    if (j->scene) sbfx_render(j->fx, &j->frame);
    else sbfx_render_view_particles(j->fx, &b->frame, b->particles, PARTICLES);
}

/* Round robin, so that the load of a shared machine falls on every configuration alike. */
static void time_jobs(bench *b, job *jobs, int count)
{
    for (int j = 0; j < count; j++)
        for (int i = 0; i < 3; i++) render_job(b, &jobs[j]); /* warm: first-use compiles, caches */
    for (int rep = 0; rep < b->reps; rep++)
        for (int j = 0; j < count; j++) {
            glFinish();
            double t0 = now_ms();
            render_job(b, &jobs[j]);
            glFinish();
            jobs[j].ms[rep] = now_ms() - t0;
        }
    for (int j = 0; j < count; j++) jobs[j].t = summarise(jobs[j].ms, b->reps);
}

typedef struct errors { double mean, max, reference; int pixels; } errors;

static errors compare(const float *gpu, const double *cpu, int n)
{
    errors e = {0, 0, 0, 0};
    for (int i = 0; i < n; i++) {
        double d = 0.0, covered = 1.0 - gpu[4 * i + 3];
        if (covered < 1e-4) continue;
        for (int k = 0; k < 3; k++) d = fmax(d, fabs(gpu[4 * i + k] - cpu[3 * i + k]));
        e.mean += d, e.max = fmax(e.max, d), e.pixels++;
        e.reference += (cpu[3 * i] + cpu[3 * i + 1] + cpu[3 * i + 2]) / 3.0;
    }
    e.mean /= e.pixels ? e.pixels : 1;
    e.reference /= e.pixels ? e.pixels : 1;
    return e;
}

/* ---- the example scene, lit and unlit ---------------------------------------------------- */

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *text = calloc((size_t)n + 1, 1);
    if (text && fread(text, 1, (size_t)n, f) != (size_t)n) text[0] = 0;
    fclose(f);
    return text;
}

/* The text with its first `from` replaced by `to` (malloc'ed), or NULL if it has none. */
static char *replace_once(const char *text, const char *from, const char *to)
{
    const char *at = strstr(text, from);
    if (!at) return NULL;
    size_t n = strlen(text) - strlen(from) + strlen(to) + 1;
    char *out = malloc(n);
    snprintf(out, n, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
    return out;
}

/* The example scene SCENE_TIME seconds in, over the test scene (drawn once: its colour and
 * depth textures stay as they are). */
static job scene_job(bench *b, struct test_scene *ts, const char *text, const char *model)
{
    job j = {.name = "scene lit-smoke", .model = model, .fx = module_for(text, SBFX_FORMAT_DEFAULT), .scene = true};
    j.frame = (sbfx_frame){.scene_color_texture = ts->color_texture, .scene_depth_texture = ts->depth_texture,
                           .out_framebuffer = b->out_fbo, .width = WIDTH, .height = HEIGHT};
    test_scene_orbit_camera(SCENE_TIME, (float)WIDTH / HEIGHT, j.frame.view, j.frame.projection);
    for (int i = 0; i < 18; i++) sbfx_update(j.fx, SCENE_TIME / 18);
    const sbfx_medium_params *m = &sbfx_media(j.fx)[SBFX_SMOKE];
    j.steps[0] = m->lit ? m->steps_min : 0, j.steps[1] = m->lit ? m->steps_max : 0;
    return j;
}

static int add_scene_jobs(bench *b, struct test_scene *ts, job *jobs)
{
    char err[512];
    char *lit = read_text("scenes/lit-smoke.cfg"), *unlit = lit ? replace_once(lit, "lighting = \"lit\"",
                                                                               "lighting = \"phase\"") : NULL;
    int n = 0;
    if (unlit && test_scene_create(ts, WIDTH, HEIGHT, err, sizeof(err)) == 0) {
        jobs[n] = scene_job(b, ts, lit, "lit");
        test_scene_draw(ts, jobs[n].frame.view, jobs[n].frame.projection);
        n++;
        jobs[n++] = scene_job(b, ts, unlit, "phase");
    } else {
        fprintf(stderr, "bench_lighting: scenes/lit-smoke.cfg or the test scene unavailable: scene rows left out\n");
    }
    free(lit), free(unlit);
    return n;
}

/* ---- main -------------------------------------------------------------------------------- */

static const int settings[][2] = {{0, 0}, {2, 4}, {4, 8}, {4, 16}, {8, 32}, {16, 64}};
#define SETTINGS ((int)ARRAY_SIZE(settings))

static int arrangement_jobs(bench *b, job *jobs)
{
    char text[2048];
    arrangement_scene(text, sizeof(text), false, 0, 0);
    jobs[0] = (job){.name = "arrangement", .model = "phase", .fx = module_for(text, SBFX_FORMAT_RGBA32F)};
    for (int s = 0; s < SETTINGS; s++) {
        arrangement_scene(text, sizeof(text), true, settings[s][0], settings[s][1]);
        jobs[1 + s] = (job){.name = "arrangement", .model = "lit", .steps = {settings[s][0], settings[s][1]},
                            .fx = module_for(text, SBFX_FORMAT_RGBA32F)};
    }
    for (int j = 0; j <= SETTINGS; j++) sbfx_set_lights(jobs[j].fx, b->lights, 4, b->ambient);
    return 1 + SETTINGS;
}

/* Errors of each lit arrangement job against the many-step reference and against the
 * reference at its own steps; writes every row. */
static void report(bench *b, job *jobs, int count, FILE *csv)
{
    const int tw = WIDTH / DIVISOR, th = HEIGHT / DIVISOR;
    float *gpu = malloc(sizeof(float) * 4 * tw * th);
    double *reference = malloc(sizeof(double) * 3 * tw * th), *own = malloc(sizeof(double) * 3 * tw * th);
    const sbfx_medium_params *medium = &sbfx_media(jobs[1].fx)[SBFX_SMOKE];
    cpu_texture tex = cpu_smoke(medium, 1);
    cpu_render(b, medium, &tex.tex, REFERENCE_STEPS, REFERENCE_STEPS, tw, th, reference);
    fprintf(csv, "case,model,steps,steps_min,steps_max,ms,ms_min,ms_max,mean_abs_err,max_abs_err,gpu_cpu_err,"
                 "ref_mean,pixels\n");
    for (int j = 0; j < count; j++) {
        job *jb = &jobs[j];
        errors e = {NAN, NAN, NAN, 0}, self = {NAN, NAN, NAN, 0};
        if (!jb->scene && !strcmp(jb->model, "lit")) {
            int w, h;
            sbfx_render_view_particles(jb->fx, &b->frame, b->particles, PARTICLES);
            sbfx_read_particle_target(jb->fx, gpu, (size_t)4 * tw * th, &w, &h);
            cpu_render(b, medium, &tex.tex, jb->steps[0], jb->steps[1], tw, th, own);
            e = compare(gpu, reference, tw * th), self = compare(gpu, own, tw * th);
        }
        fprintf(csv, "%s,%s,%d,%d,%d,%.3f,%.3f,%.3f,%.6f,%.6f,%.6f,%.4f,%d\n", jb->name, jb->model, jb->steps[1],
                jb->steps[0], jb->steps[1], jb->t.median, jb->t.min, jb->t.max, e.mean, e.max, self.mean, e.reference,
                e.pixels);
        printf("  %-16s %-5s steps [%2d,%2d] %8.3f ms (%.3f .. %.3f)  mean |err| %.5f  max %.4f  GPU vs CPU %.2g\n",
               jb->name, jb->model, jb->steps[0], jb->steps[1], jb->t.median, jb->t.min, jb->t.max, e.mean, e.max,
               self.mean);
    }
    free(gpu), free(reference), free(own), free(tex.texels);
}

int main(int argc, char **argv)
{
    const char *out_dir = "build/bench";
    bench b = {.reps = 15};
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--out")) out_dir = argv[i + 1];
        else if (!strcmp(argv[i], "--reps")) b.reps = atoi(argv[i + 1]);
    }
    if (b.reps < 1 || b.reps > 256) b.reps = 15;
    char err[512], path[512];
    struct egl_headless egl;
    if (egl_headless_open(&egl, err, sizeof(err))) {
        fprintf(stderr, "bench_lighting: %s\n", err);
        return 1;
    }
    mkdir(out_dir, 0755);
    snprintf(path, sizeof(path), "%s/lighting.csv", out_dir);
    FILE *csv = fopen(path, "w");
    if (!csv) {
        fprintf(stderr, "bench_lighting: cannot write %s\n", path);
        return 1;
    }
    make_targets(&b);
    make_arrangement(&b);
    static job jobs[SETTINGS + 3];
    struct test_scene ts = {0};
    int count = arrangement_jobs(&b, jobs);
    count += add_scene_jobs(&b, &ts, jobs + count);
    printf("bench_lighting: %d lit smoke particles, %dx%d at 1/%d, 4 lights, %d interleaved repetitions; "
           "error vs a %d-step CPU reference\n", PARTICLES, WIDTH, HEIGHT, DIVISOR, b.reps, REFERENCE_STEPS);
    time_jobs(&b, jobs, count);
    report(&b, jobs, count, csv);
    fclose(csv);
    printf("bench_lighting: wrote %s\n", path);
    for (int j = 0; j < count; j++) sbfx_destroy(jobs[j].fx);
    if (ts.framebuffer) test_scene_destroy(&ts);
    egl_headless_close(&egl);
    return 0;
}
