/* make bench: what accuracy costs (issue #4, docs/design.md §4).
 *
 * Renders three frames of the built-in explosion (t = 0.45 s with the flash's point light still
 * on, 1.2 s, 2.0 s) over the opaque test scene in every accuracy configuration that matters,
 * times each (GPU timer query where available, else glFinish-bracketed wall time; several
 * repetitions, median with min and max; the whole frame and, separately, the particle pass
 * alone) and compares each image with the CPU reference: the `exact` model per full-resolution
 * pixel in double precision (ref/reference_frame.c) composited over the same scene.
 *
 *   bench_accuracy [--out DIR] [--size WxH] [--reps N] [--quick] [--match LABEL]
 *
 * --quick runs a subset; --match only the configurations whose plot label ("sph/4 nd",
 * "exa/1 nd aBB", "flo/8 nd"...) contains LABEL (for profiling one of them); several labels
 * separated by commas run the configurations that contain any of them.
 *
 * The rows with a `lod` (issue 11, the quality ladder's last resort: src/sim/lod.h) draw at most
 * that many particles, merged by lod_reduce from the frame's particles, and are compared with the
 * same reference of all of them: their error is what the level of detail costs.
 *
 * Every configuration runs twice (issue 25): at precision `float` (llvmpipe as it is: float
 * filtering, mediump as highp) and `gpu` (SBFX_MEDIUMP=native SBFX_FILTER_BITS=8: what a GPU
 * computes), accuracy.csv's last column. A gpu row is not timed: it carries its float twin's
 * time, since a GPU runs the default programs either way. The Pareto front, the plot's points,
 * the verdicts and the ladder (tools/ladder.sh) are chosen at `gpu` precision.
 *
 * Writes DIR/accuracy.csv, DIR/points.dat and DIR/pareto.dat (for tests/bench/accuracy.gp),
 * DIR/summary.txt (the verdicts of docs/design.md §4) and a few PNGs (reference and GPU frames).
 *
 * DIR/fragments.csv: the fragments each configuration's shader variants shade per frame,
 * counted on the GPU (bench_fragments.h), for the Mali estimate of tests/bench/run.sh.
 * --shaders builds every configuration's module and draws one frame, nothing else (no reference,
 * timing or files): run under Mesa's drm-shims, the driver's statistics of every variant the
 * configurations use (SBFX_SHADER_LOG names them; docs/gpus.md). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "bench_fragments.h"
#include "bench_gl.h"
#include "bench_metrics.h"
#include "bench_programs.h"
#include "bench_reference.h"
#include "egl/egl_headless.h"
#include "internal.h"
#include "sim/lod.h"
#include "look_metrics.h"
#include "module.h" /* the pool's capacity: the level of detail's work memory */
#include "image/png_io.h"
#include "reference_frame.h"
#include "host/test_scene.h"

#define FRAME_COUNT 3
#define MAX_CONFIGS 320 /* every configuration twice: float and gpu precision */
#define EDGE_RELATIVE 0.01 /* second difference of 1/z above 1 % of 1/z: a silhouette */
#define EDGE_DILATE 3      /* pixels around it */

static const double frame_times[FRAME_COUNT] = {0.45, 1.2, 2.0};

typedef struct options {
    const char *out;
    const char *match; /* only configurations whose plot label contains this */
    int width, height, reps;
    bool quick;
    bool shaders; /* --shaders: build and draw once, for the driver's shader statistics */
} options;

typedef struct ref_frame {
    double t;
    struct test_scene scene;
    sbfx_frame frame;
    double *distance;   /* full-res opaque view distance (INFINITY where nothing was drawn) */
    uint8_t *scene_rgba;
    double *ref_rgb;    /* the reference image, 0..255 */
    uint8_t *edge;      /* near a silhouette and inside some particle's footprint */
    uint64_t state_hash;
    int particles, edge_pixels;
    uint8_t *look_mask;          /* issue 17: the reference's effect mask (look_metrics.h) */
    look_spectrum look;          /* the reference's E(s) over it */
} ref_frame;

typedef struct config {
    sbfx_opacity_mode opacity;
    int divisor;
    sbfx_target_format format;
    sbfx_upsample upsample;
    bool analytic_blackbody, table_phase;   /* the phase is analytic unless table_phase (the default) */
    sbfx_detail_format detail;
    bool light_per_particle; /* in-scattering once per particle (desc.light_per_particle) */
    bool density_matched; /* every medium's density halved: the exact model's optical depth
                             through a particle's centre in the cheaper models (docs/design.md §2.1) */
    bool keep; /* keep the GPU images (LUT comparisons) */
    int lod; /* at most this many particles drawn (src/sim/lod.h), 0: all */
    bool gpu; /* precision `gpu`: SBFX_MEDIUMP=native SBFX_FILTER_BITS=8 (issue 25), else `float` */
} config;

#define MAX_VARIANTS 12
/* Fragments per frame each of a configuration's programs shades (bench_fragments.h): its
 * particle variants, the depth downsample, the low-res corners, the composite. */
typedef struct variant_fragments {
    int count;
    char name[MAX_VARIANTS][256]; /* "VERT FRAG | DEFINES" (SBFX_SHADER_LOG) */
    double fragments[MAX_VARIANTS];
    double refined;        /* mixed resolution: the particle fragments the refinement shades */
    bool failed;
} variant_fragments;

typedef struct result {
    config c;
    bool ok;
    sbfx_target_format used_format;
    double ms, ms_min, ms_max, wall_ms;
    double part_ms, part_min, part_max, part_wall_ms;
    bool part_ok;
    bench_error err;
    bool pareto;
    uint8_t *images[FRAME_COUNT];
    double look_energy[LOOK_SCALES], look_ref_energy[LOOK_SCALES]; /* summed over frames, per scale */
    variant_fragments frags;
} result;

typedef struct bench {
    options opt;
    struct egl_headless egl;
    bench_timer timer;
    bench_target target;
    sbfx_cmf cmf;
    float *detail;
    int detail_size, detail_frames;
    ref_frame frames[FRAME_COUNT];
    result results[MAX_CONFIGS];
    int result_count;
    double reference_seconds;
} bench;

static const char *const mode_names[SBFX_OPACITY_COUNT] = {
    [SBFX_OPACITY_PLANAR] = "planar", [SBFX_OPACITY_SOFT] = "soft", [SBFX_OPACITY_SPHERICAL] = "spherical",
    [SBFX_OPACITY_EXACT] = "exact", [SBFX_OPACITY_FLOOR] = "floor"};
static const char *const format_names[SBFX_FORMAT_COUNT] = {
    [SBFX_FORMAT_RGBA8] = "RGBA8", [SBFX_FORMAT_RGBA16F] = "RGBA16F", [SBFX_FORMAT_RGBA32F] = "RGBA32F"};

static double seconds_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec / 1e9;
}

static void *xcalloc(size_t n, size_t size)
{
    void *p = calloc(n, size);
    if (!p) {
        fprintf(stderr, "bench: out of memory\n");
        exit(1);
    }
    return p;
}

static void die(const char *what, const char *why)
{
    fprintf(stderr, "bench: %s: %s\n", what, why);
    exit(1);
}

/* ---- options ------------------------------------------------------------------------- */

static options parse_options(int argc, char **argv)
{
    options o = {"build/bench", NULL, 960, 540, 7, false, false};
    for (int i = 1; i < argc; i++) {
        bool more = i + 1 < argc;
        if (!strcmp(argv[i], "--out") && more) o.out = argv[++i];
        else if (!strcmp(argv[i], "--size") && more && sscanf(argv[++i], "%dx%d", &o.width, &o.height) == 2) {}
        else if (!strcmp(argv[i], "--reps") && more) o.reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--quick")) o.quick = true;
        else if (!strcmp(argv[i], "--shaders")) o.shaders = true;
        else if (!strcmp(argv[i], "--match") && more) o.match = argv[++i];
        else die("usage", "bench_accuracy [--out DIR] [--size WxH] [--reps N] [--quick] [--match LABEL] [--shaders]");
    }
    if (o.width < 16 || o.height < 16 || o.width > 4096 || o.height > 4096 || o.reps < 1 || o.reps > 50)
        die("options", "--size must be 16x16..4096x4096 and --reps 1..50");
    return o;
}

/* ---- simulation ---------------------------------------------------------------------- */

static bool print_shader_builds; /* --shaders: tools/shader-stats.sh reads them */

static void log_warning(sbfx_log_level level, const char *message, void *user)
{
    (void)user;
    if (level != SBFX_LOG_INFO) fprintf(stderr, "bench: sbfx: %s\n", message);
    else if (strncmp(message, "shader build ", 13) == 0) {
        bench_programs_note(message);
        if (print_shader_builds) fprintf(stderr, "bench: sbfx: info: %s\n", message);
    }
}

/* GPU precision (docs/testing.md, "Precision diagnostics"): mediump as written and 8-bit filter
 * weights, what a GPU computes; the variables are read by sbfx_create only. */
static void set_precision(bool gpu)
{
    if (gpu) {
        setenv("SBFX_MEDIUMP", "native", 1);
        setenv("SBFX_FILTER_BITS", "8", 1);
    } else {
        unsetenv("SBFX_MEDIUMP");
        unsetenv("SBFX_FILTER_BITS");
    }
}

static sbfx *create_module(const config *c)
{
    sbfx_desc d = {.target_divisor = c->divisor, .target_format = c->format, .upsample = c->upsample,
                   .opacity = c->opacity, .analytic_blackbody = c->analytic_blackbody,
                   .table_phase = c->table_phase, .detail_format = c->detail,
                   .light_per_particle = c->light_per_particle, .log = log_warning};
    sbfx *fx = NULL;
    set_precision(c->gpu);
    sbfx_result r = sbfx_create(&d, &fx);
    set_precision(false);
    if (r != SBFX_OK) die("sbfx_create", sbfx_result_string(r));
    return fx;
}

/* Whole fixed steps of the default 1/120 s, one per update: every module of the bench then goes
 * through bit-identical simulation states (checked with sbfx_state_hash). */
static void advance_to(sbfx *fx, double t)
{
    const double step = (double)(1.0f / 120.0f);
    while (sbfx_time(fx) < t - 1e-9) sbfx_update(fx, step);
}

/* ---- the reference ------------------------------------------------------------------- */

static void read_distances(ref_frame *rf, int w, int h)
{
    float *window = xcalloc((size_t)w * h, sizeof(float));
    char err[256];
    if (bench_read_depth(rf->scene.depth_texture, w, h, window, err, sizeof(err)) != 0) die("depth", err);
    /* as the shaders read it; the clear value is no surface (INFINITY) */
    for (size_t i = 0; i < (size_t)w * h; i++) rf->distance[i] = sbfx_window_distance(&rf->frame, window[i]);
    free(window);
}

/* The exact model per full-resolution pixel, composited over the scene. */
static void render_reference(bench *b, sbfx *fx, ref_frame *rf)
{
    int w = b->opt.width, h = b->opt.height;
    uint8_t *footprint = xcalloc((size_t)w * h, 1);
    bench_reference r = {b->detail, b->detail_size, b->detail_frames, &b->cmf};
    rf->particles = bench_reference_render(&r, fx, &rf->frame, rf->distance, rf->scene_rgba, rf->ref_rgb, footprint);
    if (rf->particles < 0) die("reference", "out of memory");
    bench_edge_mask(rf->distance, w, h, EDGE_RELATIVE, EDGE_DILATE, rf->edge);
    rf->edge_pixels = 0;
    for (size_t i = 0; i < (size_t)w * h; i++) {
        rf->edge[i] = rf->edge[i] && footprint[i];
        rf->edge_pixels += rf->edge[i];
    }
    free(footprint);
}

static void write_png(const bench *b, const char *name, const uint8_t *rgba)
{
    char path[1024], err[256];
    snprintf(path, sizeof(path), "%s/%s", b->opt.out, name);
    if (png_write_rgba(path, rgba, b->opt.width, b->opt.height, true, err, sizeof(err)) != 0)
        fprintf(stderr, "bench: %s\n", err);
}

static void write_reference_png(const bench *b, const ref_frame *rf, int index)
{
    size_t n = (size_t)b->opt.width * b->opt.height;
    uint8_t *rgba = xcalloc(n, 4);
    for (size_t i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) rgba[4 * i + k] = (uint8_t)lround(rf->ref_rgb[3 * i + k]);
        rgba[4 * i + 3] = 255;
    }
    char name[64];
    snprintf(name, sizeof(name), "reference-%d.png", index);
    write_png(b, name, rgba);
    free(rgba);
}

static void prepare_frame(bench *b, ref_frame *rf, double t)
{
    int w = b->opt.width, h = b->opt.height;
    char err[256];
    rf->t = t;
    if (test_scene_create(&rf->scene, w, h, err, sizeof(err)) != 0) die("test scene", err);
    test_scene_orbit_camera(t, (float)w / (float)h, rf->frame.view, rf->frame.projection);
    if (test_scene_draw(&rf->scene, rf->frame.view, rf->frame.projection) != 0) die("test scene", "GL error");
    rf->frame.scene_color_texture = rf->scene.color_texture;
    rf->frame.scene_depth_texture = rf->scene.depth_texture;
    rf->frame.out_framebuffer = b->target.fbo;
    rf->frame.width = w;
    rf->frame.height = h;
    rf->distance = xcalloc((size_t)w * h, sizeof(double));
    rf->scene_rgba = xcalloc((size_t)w * h, 4);
    rf->ref_rgb = xcalloc((size_t)w * h * 3, sizeof(double));
    rf->edge = xcalloc((size_t)w * h, 1);
    bench_read_rgba8(rf->scene.framebuffer, w, h, rf->scene_rgba);
    read_distances(rf, w, h);
}

/* issue 17: the reference's fine structure, over its own effect mask (docs/look.md) */
static void reference_look(bench *b, ref_frame *rf)
{
    size_t n = (size_t)b->opt.width * b->opt.height;
    uint8_t *rgba = xcalloc(n, 4);
    double *y = xcalloc(n, sizeof(double));
    for (size_t i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) rgba[4 * i + k] = (uint8_t)lround(fmin(fmax(rf->ref_rgb[3 * i + k], 0.0), 255.0));
        rgba[4 * i + 3] = 255;
    }
    rf->look_mask = xcalloc(n, 1);
    look_effect_mask(rgba, rf->scene_rgba, b->opt.width, b->opt.height, rf->look_mask);
    look_luminance(rgba, n, y);
    if (look_measure(y, rf->look_mask, b->opt.width, b->opt.height, &rf->look) != 0) die("look", "out of memory");
    free(rgba);
    free(y);
}

/* The GPU image's E(s) over the reference's mask, added to the configuration's sums (scales
 * whose eroded mask is empty in this frame are left out of both sums). */
static void accumulate_look(const bench *b, result *res, const ref_frame *rf, const uint8_t *gpu)
{
    size_t n = (size_t)b->opt.width * b->opt.height;
    double *y = xcalloc(n, sizeof(double));
    look_spectrum sp;
    look_luminance(gpu, n, y);
    if (look_measure(y, rf->look_mask, b->opt.width, b->opt.height, &sp) != 0) die("look", "out of memory");
    for (int s = 0; s < LOOK_SCALES; s++)
        if (sp.pixels[s] > 0 && isfinite(sp.energy[s]) && isfinite(rf->look.energy[s])) {
            res->look_energy[s] += sp.energy[s];
            res->look_ref_energy[s] += rf->look.energy[s];
        }
    free(y);
}

/* --shaders: the frames' scene and camera, no read-backs or reference (the drm-shims draw
 * nothing). */
static void prepare_frames_only(bench *b)
{
    char err[256];
    for (int i = 0; i < FRAME_COUNT; i++) {
        ref_frame *rf = &b->frames[i];
        int w = b->opt.width, h = b->opt.height;
        rf->t = frame_times[i];
        if (test_scene_create(&rf->scene, w, h, err, sizeof(err)) != 0) die("test scene", err);
        test_scene_orbit_camera(rf->t, (float)w / (float)h, rf->frame.view, rf->frame.projection);
        if (test_scene_draw(&rf->scene, rf->frame.view, rf->frame.projection) != 0) die("test scene", "GL error");
        rf->frame.scene_color_texture = rf->scene.color_texture;
        rf->frame.scene_depth_texture = rf->scene.depth_texture;
        rf->frame.out_framebuffer = b->target.fbo;
        rf->frame.width = w;
        rf->frame.height = h;
    }
}

static void prepare_references(bench *b)
{
    if (b->opt.shaders) {
        prepare_frames_only(b);
        return;
    }
    config c = {.opacity = SBFX_OPACITY_EXACT, .divisor = 4};
    sbfx *fx = create_module(&c);
    sbfx_detail_dimensions(fx, &b->detail_size, &b->detail_frames);
    b->detail = xcalloc((size_t)b->detail_size * b->detail_size * b->detail_frames, sizeof(float));
    sbfx_detail_generate(b->detail_size, b->detail_frames, 1, b->detail); /* desc.seed default 1 */
    double start = seconds_now();
    for (int i = 0; i < FRAME_COUNT; i++) {
        ref_frame *rf = &b->frames[i];
        prepare_frame(b, rf, frame_times[i]);
        advance_to(fx, frame_times[i]);
        rf->state_hash = sbfx_state_hash(fx);
        render_reference(b, fx, rf);
        write_reference_png(b, rf, i);
        reference_look(b, rf);
        printf("bench: reference frame t=%.2f s: %d particles, %d edge pixels\n", rf->t, rf->particles,
               rf->edge_pixels);
        fflush(stdout);
    }
    b->reference_seconds = seconds_now() - start;
    sbfx_destroy(fx);
}

/* ---- GPU runs ------------------------------------------------------------------------ */

typedef struct render_call {
    sbfx *fx;
    const sbfx_frame *frame;
    bool failed;
    int lod;                   /* config.lod */
    particle_lod *lod_state;   /* its work memory, sized for the pool */
    sbfx_view_particle *lod_view;
} render_call;

/* With a level of detail: the frame's particles, reduced, drawn as view particles (the same
 * passes as sbfx_render; the scene has no post effects, so no velocities are lost). */
static void render_once(void *user)
{
    render_call *rc = user;
    if (!rc->lod) {
        if (sbfx_render(rc->fx, rc->frame) != SBFX_OK) rc->failed = true;
        return;
    }
    const sbfx_view_particle *v;
    int n = sbfx_frame_particles(rc->fx, rc->frame->view, &v);
    memcpy(rc->lod_view, v, (size_t)n * sizeof(*v));
    n = lod_reduce(rc->lod_state, rc->lod_view, n, rc->lod);
    if (sbfx_render_view_particles(rc->fx, rc->frame, rc->lod_view, n) != SBFX_OK) rc->failed = true;
}

typedef struct samples {
    double total_gpu[50], total_wall[50], part_gpu[50], part_wall[50];
    bool part_ok;
} samples;

/* One frame, reps times: the particle pass alone, then the whole frame over a fresh copy of
 * the scene (whose image is the one compared). Times are summed over frames per repetition. */
static void time_frame(bench *b, render_call *rc, const ref_frame *rf, samples *s)
{
    for (int r = 0; r < b->opt.reps; r++) {
        bench_sample part, total;
        if (!bench_time_particle_pass(&b->timer, render_once, rc, &part)) s->part_ok = false;
        bench_target_fill_from(&b->target, rf->scene.framebuffer);
        total = bench_time_call(&b->timer, render_once, rc);
        s->total_gpu[r] += total.gpu_ms / FRAME_COUNT;
        s->total_wall[r] += total.wall_ms / FRAME_COUNT;
        s->part_gpu[r] += part.gpu_ms / FRAME_COUNT;
        s->part_wall[r] += part.wall_ms / FRAME_COUNT;
    }
}

static void summarise(bench *b, result *res, samples *s)
{
    int n = b->opt.reps;
    double med, lo, hi;
    bool gpu = b->timer.has_query;
    bench_stats(s->total_wall, n, &med, &lo, &hi);
    res->wall_ms = med;
    if (!gpu) res->ms = med, res->ms_min = lo, res->ms_max = hi;
    else bench_stats(s->total_gpu, n, &res->ms, &res->ms_min, &res->ms_max);
    bench_stats(s->part_wall, n, &med, &lo, &hi);
    res->part_wall_ms = med;
    if (!gpu) res->part_ms = med, res->part_min = lo, res->part_max = hi;
    else bench_stats(s->part_gpu, n, &res->part_ms, &res->part_min, &res->part_max);
    res->part_ok = s->part_ok;
}

static void compare_frame(bench *b, result *res, int index, uint8_t *gpu)
{
    const ref_frame *rf = &b->frames[index];
    size_t n = (size_t)b->opt.width * b->opt.height;
    bench_read_rgba8(b->target.fbo, b->opt.width, b->opt.height, gpu);
    bench_error_add(&res->err, gpu, rf->ref_rgb, rf->edge, n);
    accumulate_look(b, res, rf, gpu);
    if (res->c.keep) {
        res->images[index] = xcalloc(n, 4);
        memcpy(res->images[index], gpu, n * 4);
    }
}

/* planar, soft and spherical integrate the centre's ray to 2 tau r, exact to tau r: with half the
 * density they put the exact model's optical depth through the centre. Uniforms: no reload. */
static void match_density(sbfx *fx)
{
    sbfx_medium_params *m = sbfx_media(fx);
    for (int i = 0; i < SBFX_MEDIUM_COUNT; i++) m[i].tau *= 0.5f;
}

/* One more draw of the frame with the fragment counter armed; per variant, summed. */
static void count_fragments(render_call *rc, variant_fragments *vf)
{
    bench_fragment_tally t;
    bench_fragments_begin(&t);
    render_once(rc);
    bench_fragments_end();
    vf->failed = vf->failed || t.failed;
    vf->refined += t.masked_fragments / FRAME_COUNT;
    for (int d = 0; d < t.draws; d++) {
        const char *name = bench_program_name(t.program[d]);
        int k = 0;
        while (k < vf->count && strcmp(vf->name[k], name) != 0) k++;
        if (k == vf->count) {
            if (vf->count == MAX_VARIANTS) continue;
            snprintf(vf->name[vf->count++], sizeof(vf->name[0]), "%s", name);
        }
        vf->fragments[k] += t.fragments[d] / FRAME_COUNT;
    }
}

/* --shaders: the module is made (its variants compiled) and one frame drawn. */
static void build_config(bench *b, result *res)
{
    sbfx *fx = create_module(&res->c);
    render_call rc = {fx, &b->frames[0].frame, false, 0, NULL, NULL};
    advance_to(fx, b->frames[0].t);
    render_once(&rc);
    res->ok = !rc.failed;
    if (rc.failed) fprintf(stderr, "bench: render failed: %s\n", sbfx_last_error(fx));
    sbfx_destroy(fx);
}

static void run_config(bench *b, result *res)
{
    if (b->opt.shaders) {
        build_config(b, res);
        return;
    }
    sbfx *fx = create_module(&res->c);
    if (res->c.density_matched) match_density(fx);
    samples s = {.part_ok = true};
    uint8_t *gpu = xcalloc((size_t)b->opt.width * b->opt.height, 4);
    render_call rc = {fx, NULL, false, res->c.lod, NULL, NULL};
    particle_lod lod;
    void *lod_work = NULL;
    if (rc.lod) {
        int capacity = fx->sim->pool.capacity;
        lod_work = xcalloc(1, lod_work_size(capacity));
        lod_init(&lod, lod_work, capacity);
        rc.lod_state = &lod;
        rc.lod_view = xcalloc((size_t)capacity, sizeof(*rc.lod_view));
    }
    for (int i = 0; i < FRAME_COUNT && !rc.failed; i++) {
        const ref_frame *rf = &b->frames[i];
        advance_to(fx, rf->t);
        if (sbfx_state_hash(fx) != rf->state_hash) die("simulation", "state differs from the reference's");
        rc.frame = &rf->frame;
        if (i == 0) render_once(&rc); /* first draw compiles the shader variants: not timed */
        if (res->c.gpu) { /* its error only: the GPU runs the default programs (float's time) */
            bench_target_fill_from(&b->target, rf->scene.framebuffer);
            render_once(&rc);
        } else {
            time_frame(b, &rc, rf, &s);
        }
        compare_frame(b, res, i, gpu);
        if (!res->c.gpu) count_fragments(&rc, &res->frags);
    }
    sbfx_counters counters;
    sbfx_stats(fx, &counters);
    res->used_format = counters.target_format;
    res->ok = !rc.failed;
    if (rc.failed) fprintf(stderr, "bench: render failed: %s\n", sbfx_last_error(fx));
    if (!res->c.gpu) summarise(b, res, &s);
    free(gpu);
    free(lod_work);
    free(rc.lod_view);
    sbfx_destroy(fx);
}

/* ---- the configurations -------------------------------------------------------------- */

static config make_config(sbfx_opacity_mode m, int divisor, sbfx_target_format f, sbfx_upsample u)
{
    return (config){.opacity = m, .divisor = divisor, .format = f, .upsample = u, .detail = SBFX_DETAIL_R16F};
}

static bool is_lut_base(sbfx_opacity_mode m, int divisor)
{
    return (m == SBFX_OPACITY_SPHERICAL && divisor == 4) || (m == SBFX_OPACITY_EXACT && divisor == 1);
}

/* Scales x (floor, modes x upsampling) (RGBA16F, tables): the main grid. Each scale's floor is
 * measured right before its modes, so that a ratio to the floor compares runs made under the
 * same load on a shared machine. */
static int grid_configs(const options *o, config *out)
{
    static const sbfx_opacity_mode modes[] = {SBFX_OPACITY_PLANAR, SBFX_OPACITY_SOFT, SBFX_OPACITY_SPHERICAL,
                                              SBFX_OPACITY_EXACT};
    static const int scales[] = {1, 2, 4, 8};
    static const sbfx_upsample ups[] = {SBFX_UPSAMPLE_NEAREST_DEPTH, SBFX_UPSAMPLE_BILINEAR};
    int n = 0;
    for (size_t s = 0; s < 4; s++) {
        if (o->quick && (scales[s] == 2 || scales[s] == 8)) continue;
        out[n++] = make_config(SBFX_OPACITY_FLOOR, scales[s], SBFX_FORMAT_RGBA16F, ups[0]);
        for (size_t m = 0; m < 4; m++)
            for (size_t u = 0; u < (o->quick ? 1u : 2u); u++) {
                out[n] = make_config(modes[m], scales[s], SBFX_FORMAT_RGBA16F, ups[u]);
                out[n].keep = u == 0 && (is_lut_base(modes[m], scales[s]) ||
                                         (modes[m] == SBFX_OPACITY_PLANAR && scales[s] == 1));
                n++;
            }
        /* mixed resolution (refined at full resolution where the coarse target fails): every
         * mode below full resolution; --quick the exact model at 1/4 */
        for (size_t m = 0; m < 4 && scales[s] > 1; m++)
            if (!o->quick || (modes[m] == SBFX_OPACITY_EXACT && scales[s] == 4))
                out[n++] = make_config(modes[m], scales[s], SBFX_FORMAT_RGBA16F, SBFX_UPSAMPLE_MIXED);
    }
    return n;
}

/* Target formats (full and quarter resolution), the analytic alternatives to the tables and
 * the R32F detail volume. */
static int variant_configs(const options *o, config *out)
{
    static const sbfx_opacity_mode modes[] = {SBFX_OPACITY_PLANAR, SBFX_OPACITY_SOFT, SBFX_OPACITY_SPHERICAL,
                                              SBFX_OPACITY_EXACT};
    static const sbfx_target_format formats[] = {SBFX_FORMAT_RGBA8, SBFX_FORMAT_RGBA32F};
    const sbfx_upsample nd = SBFX_UPSAMPLE_NEAREST_DEPTH;
    int n = 0;
    for (size_t m = 0; m < 4 && !o->quick; m++)
        for (int s = 1; s <= 4; s *= 4)
            for (size_t f = 0; f < 2; f++) out[n++] = make_config(modes[m], s, formats[f], nd);
    const struct { sbfx_opacity_mode m; int s; } bases[] = {{SBFX_OPACITY_SPHERICAL, 4}, {SBFX_OPACITY_EXACT, 1}};
    for (size_t i = 0; i < 2; i++) {
        for (int lut = 1; lut <= 3; lut++) {
            out[n] = make_config(bases[i].m, bases[i].s, SBFX_FORMAT_RGBA16F, nd);
            out[n].analytic_blackbody = lut & 1;
            out[n].table_phase = lut & 2;
            out[n++].keep = true;
        }
        out[n] = make_config(bases[i].m, bases[i].s, SBFX_FORMAT_RGBA16F, nd);
        out[n++].detail = SBFX_DETAIL_R32F;
    }
    /* lighting once per particle instead of per fragment, at every scale: the floor ratio's
     * largest lever (the light loop is about half of the particle pass on llvmpipe) */
    for (int s = 1; s <= 8; s *= 2)
        for (int e = 0; e < 2; e++) {
            out[n] = make_config(e ? SBFX_OPACITY_EXACT : SBFX_OPACITY_SPHERICAL, s, SBFX_FORMAT_RGBA16F, nd);
            out[n++].light_per_particle = true;
        }
    /* the ladder's last resort (issue 11): at most N particles, at 1/8 (the cheapest scale),
     * with light per pixel (both upsamplings) and per particle: below whichever is cheapest */
    for (size_t m = 0; m < 4 && !o->quick; m++)
        for (int u = 0; u < 3; u++)
            for (int lod = 256; lod >= 16 && (u < 2 || m >= 2); lod /= 4) {
                out[n] = make_config(modes[m], 8, SBFX_FORMAT_RGBA16F,
                                     u == 1 ? SBFX_UPSAMPLE_BILINEAR : SBFX_UPSAMPLE_NEAREST_DEPTH);
                out[n].light_per_particle = u == 2;
                out[n++].lod = lod;
            }
    /* model against shape: the cheaper models with the density that matches the exact model's
     * optical depth through the centre, at full and quarter resolution */
    for (int s = 1; s <= 4; s *= 4)
        for (size_t m = 0; m < 3; m++) {
            out[n] = make_config(modes[m], s, SBFX_FORMAT_RGBA16F, nd);
            out[n++].density_matched = true;
        }
    return n;
}

/* ---- names --------------------------------------------------------------------------- */

static const char *scale_fraction(int divisor)
{
    return divisor == 1 ? "1" : divisor == 2 ? "0.5" : divisor == 4 ? "0.25" : "0.125";
}

static const char *upsample_name(sbfx_upsample u)
{
    return u == SBFX_UPSAMPLE_BILINEAR ? "bilinear" : u == SBFX_UPSAMPLE_MIXED ? "mixed" : "nearest-depth";
}

static const char *lut_name(const config *c)
{
    if (c->light_per_particle) return "light-per-particle";
    /* what the black body and the phase function use: the default (issue 43) is "analytic-phase" */
    if (c->analytic_blackbody && !c->table_phase) return "analytic";
    if (c->analytic_blackbody) return "analytic-bb";
    if (!c->table_phase) return "analytic-phase";
    return "table";
}

static const char *format_name(sbfx_target_format f)
{
    return (unsigned)f < SBFX_FORMAT_COUNT && format_names[f] ? format_names[f] : "?";
}

/* A short label for the plot: "sph/4 nd", "exa/1 nd aBB", "pla/1 nd 8"... */
static void short_label(const result *r, char *out, size_t n)
{
    const config *c = &r->c;
    const char *lut = c->analytic_blackbody && c->table_phase ? " aBB tPh"
                      : c->analytic_blackbody ? " aBB" : c->table_phase ? " tPh" : "";
    const char *fmt = r->used_format == SBFX_FORMAT_RGBA8 ? " 8" : r->used_format == SBFX_FORMAT_RGBA32F ? " 32F" : "";
    char lod[16] = "";
    if (c->lod) snprintf(lod, sizeof(lod), " lod%d", c->lod);
    snprintf(out, n, "%.3s/%d %s%s%s%s%s%s%s", mode_names[c->opacity], c->divisor,
             c->upsample == SBFX_UPSAMPLE_BILINEAR ? "bl" : c->upsample == SBFX_UPSAMPLE_MIXED ? "mx" : "nd", fmt, lut,
             c->detail == SBFX_DETAIL_R32F ? " d32" : "", c->light_per_particle ? " lpp" : "",
             c->density_matched ? " tau/2" : "", lod);
}

static bool is_grid_point(const result *r)
{
    const config *c = &r->c;
    return c->format == SBFX_FORMAT_RGBA16F && !c->analytic_blackbody && !c->table_phase &&
           c->detail == SBFX_DETAIL_R16F && c->opacity != SBFX_OPACITY_FLOOR && !c->light_per_particle &&
           !c->density_matched && !c->lod;
}

/* ---- output -------------------------------------------------------------------------- */

static FILE *open_out(const bench *b, const char *name) { return bench_open_out(b->opt.out, name); }

static void write_csv(const bench *b)
{
    FILE *f = open_out(b, "accuracy.csv");
    fprintf(f, "mode,scale,format,upsample,lut,detail,ms,ms_min,ms_max,wall_ms,particle_ms,particle_ms_min,"
               "particle_ms_max,particle_wall_ms,mean_abs_err,max_abs_err,psnr,edge_mean_abs_err,"
               "edge_max_abs_err,edge_psnr,pareto,density,lod,beta,beta_8_32,band_2_8,band_8_32,ref_beta,beta_4_16,"
               "precision\n");
    for (int i = 0; i < b->result_count; i++) {
        const result *r = &b->results[i];
        const config *c = &r->c;
        fprintf(f, "%s,%s,%s,%s,%s,%s,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.4f,%.2f,%.2f,%.4f,%.2f,%.2f,%d,%s,%d",
                mode_names[c->opacity], scale_fraction(c->divisor), format_name(r->used_format),
                upsample_name(c->upsample), lut_name(c), c->detail == SBFX_DETAIL_R32F ? "R32F" : "R16F", r->ms,
                r->ms_min, r->ms_max, r->wall_ms, r->part_ms, r->part_min, r->part_max, r->part_wall_ms,
                bench_error_mean(&r->err), r->err.max_abs, bench_psnr(r->err.sum_sq, r->err.count),
                bench_error_edge_mean(&r->err), r->err.edge_max_abs,
                bench_psnr(r->err.edge_sum_sq, r->err.edge_count), r->pareto, c->density_matched ? "matched" : "scene",
                c->lod);
        const double *e = r->look_energy, *re = r->look_ref_energy;
        /* beta_4_16: the same fit over 4..16 px, for clouds too small for the 32 px scale (the
         * built-in explosion from the bench's orbit camera): not the beta, a stand-in */
        fprintf(f, ",%.3f,%.3f,%.4f,%.4f,%.3f,%.3f,%s\n", look_beta_fit(e, 1, LOOK_SCALES - 1),
                look_beta_fit(e, 2, LOOK_SCALES - 1), (e[1] + e[2]) / (re[1] + re[2]),
                (e[3] + e[4]) / (re[3] + re[4]), look_beta_fit(re, 1, LOOK_SCALES - 1), look_beta_fit(e, 1, 3),
                c->gpu ? "gpu" : "float");
    }
    fclose(f);
}

/* fragments.csv: the configuration's key (accuracy.csv's columns) and each of its programs'
 * fragments per frame, counted: the particle variants, the depth downsample and the low-res
 * corners, the composite (over the particles' tiles: render/tiles.h). */
static void write_fragments(const bench *b)
{
    FILE *f = open_out(b, "fragments.csv");
    fprintf(f, "mode,scale,format,upsample,lut,detail,density,lod,shader,variant,fragments\n");
    for (int i = 0; i < b->result_count; i++) {
        const result *r = &b->results[i];
        const config *c = &r->c;
        char key[256];
        snprintf(key, sizeof(key), "%s,%s,%s,%s,%s,%s,%s,%d", mode_names[c->opacity], scale_fraction(c->divisor),
                 format_name(r->used_format), upsample_name(c->upsample), lut_name(c),
                 c->detail == SBFX_DETAIL_R32F ? "R32F" : "R16F", c->density_matched ? "matched" : "scene", c->lod);
        if (r->frags.failed || c->gpu) continue; /* the gpu twin runs the same default programs */
        for (int k = 0; k < r->frags.count; k++) {
            char shader[64] = "?";
            const char *bar = strstr(r->frags.name[k], " | ");
            sscanf(r->frags.name[k], "%*s %63s", shader);
            fprintf(f, "%s,%s,%s,%.0f\n", key, shader, bar && bar[3] ? bar + 3 : "-", r->frags.fragments[k]);
        }
    }
    fclose(f);
}

/* refined.csv: per mixed-resolution configuration, the particle fragments its refinement
 * shades per frame (at full resolution, where the mark passed; bench_fragments.h), and all the
 * particle fragments (coarse and refined) for comparison. */
static void write_refined(const bench *b)
{
    FILE *f = open_out(b, "refined.csv");
    fprintf(f, "mode,scale,format,upsample,lod,particle_fragments,refined_fragments\n");
    for (int i = 0; i < b->result_count; i++) {
        const result *r = &b->results[i];
        const config *c = &r->c;
        if (r->frags.failed || c->gpu || c->upsample != SBFX_UPSAMPLE_MIXED) continue;
        double particles = 0.0;
        for (int k = 0; k < r->frags.count; k++)
            if (strstr(r->frags.name[k], "particle.frag")) particles += r->frags.fragments[k];
        fprintf(f, "%s,%s,%s,%s,%d,%.0f,%.0f\n", mode_names[c->opacity], scale_fraction(c->divisor),
                format_name(r->used_format), upsample_name(c->upsample), c->lod, particles, r->frags.refined);
    }
    fclose(f);
}

/* points.dat: every configuration but the floor; pareto.dat: the front, by time. Columns:
 * ms, mean abs error, label, group (0 = main grid, 1 = variant), opacity mode (1 planar ..
 * 4 exact), divisor, upsampling (0 nearest-depth, 1 bilinear, 2 mixed). */
static void write_plot_data(const bench *b)
{
    FILE *points = open_out(b, "points.dat"), *front = open_out(b, "pareto.dat");
    int order[MAX_CONFIGS], n = 0;
    for (int i = 0; i < b->result_count; i++) {
        const result *r = &b->results[i];
        if (r->c.opacity == SBFX_OPACITY_FLOOR || !r->c.gpu) continue; /* judged at GPU precision */
        char label[64];
        short_label(r, label, sizeof(label));
        fprintf(points, "%.4f %.5f \"%s\" %d %d %d %d\n", r->ms, bench_error_mean(&r->err), label,
                is_grid_point(r) ? 0 : 1, (int)r->c.opacity, r->c.divisor,
                r->c.upsample == SBFX_UPSAMPLE_BILINEAR ? 1 : r->c.upsample == SBFX_UPSAMPLE_MIXED ? 2 : 0);
        if (r->pareto) order[n++] = i;
    }
    for (int i = 1; i < n; i++) /* insertion sort by time */
        for (int j = i; j > 0 && b->results[order[j]].ms < b->results[order[j - 1]].ms; j--) {
            int t = order[j];
            order[j] = order[j - 1], order[j - 1] = t;
        }
    for (int i = 0; i < n; i++) {
        const result *r = &b->results[order[i]];
        char label[64];
        short_label(r, label, sizeof(label));
        fprintf(front, "%.4f %.5f \"%s\"\n", r->ms, bench_error_mean(&r->err), label);
    }
    fclose(points);
    fclose(front);
}

static void mark_pareto(bench *b)
{
    double ms[MAX_CONFIGS], err[MAX_CONFIGS];
    bool include[MAX_CONFIGS], front[MAX_CONFIGS];
    for (int i = 0; i < b->result_count; i++) {
        ms[i] = b->results[i].ms;
        err[i] = bench_error_mean(&b->results[i].err);
        /* a matched density is a re-tuned scene, not a quality the module offers */
        include[i] = b->results[i].ok && b->results[i].c.opacity != SBFX_OPACITY_FLOOR &&
                     !b->results[i].c.density_matched && !b->results[i].c.lod &&
                     b->results[i].c.gpu; /* the front at GPU precision (issue 25) */
    }
    bench_pareto(ms, err, include, b->result_count, front);
    for (int i = 0; i < b->result_count; i++) b->results[i].pareto = front[i];
}

/* ---- the verdicts of docs/design.md §4 ------------------------------------------------------- */

/* The verdicts are judged at GPU precision (DESIGN §9): the gpu rows, with their float twin's time. */
static const result *find(const bench *b, sbfx_opacity_mode m, int divisor, sbfx_upsample u, int lut,
                          sbfx_detail_format detail)
{
    for (int i = 0; i < b->result_count; i++) {
        const config *c = &b->results[i].c;
        if (c->gpu && c->opacity == m && c->divisor == divisor && c->upsample == u && c->format == SBFX_FORMAT_RGBA16F &&
            c->analytic_blackbody == (bool)(lut & 1) && c->table_phase == (bool)(lut & 2) && c->detail == detail &&
            c->light_per_particle == (bool)(lut & 4) && c->density_matched == (bool)(lut & 8))
            return &b->results[i];
    }
    return NULL;
}

static const result *find_main(const bench *b, sbfx_opacity_mode m, int divisor)
{
    return find(b, m, divisor, SBFX_UPSAMPLE_NEAREST_DEPTH, 0, SBFX_DETAIL_R16F);
}

static void cpu_model(char *out, size_t n)
{
    snprintf(out, n, "unknown CPU");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f) return;
    char line[512];
    while (fgets(line, sizeof(line), f)) {
        char *colon = strchr(line, ':');
        if (strncmp(line, "model name", 10) == 0 && colon) {
            snprintf(out, n, "%s", colon + 2);
            out[strcspn(out, "\n")] = '\0';
            break;
        }
    }
    fclose(f);
}

static const char *verdict(bool met) { return met ? "MET" : "MISSED"; }

static void summary_machine(const bench *b, FILE *f)
{
    char cpu[256];
    cpu_model(cpu, sizeof(cpu));
    fprintf(f, "machine   : %s, %ld cores; %s; %s\n", cpu, sysconf(_SC_NPROCESSORS_ONLN), bench_gl_renderer(),
            bench_gl_version());
    fprintf(f, "workload  : built-in explosion over the test scene, %dx%d output, frames at t = %.2f, %.2f, %.2f s,"
               " %d repetitions (median [min..max])\n", b->opt.width, b->opt.height, frame_times[0], frame_times[1],
            frame_times[2], b->opt.reps);
    fprintf(f, "clock     : %s\n", b->timer.has_query ? "GPU timer query (GL_EXT_disjoint_timer_query, TIME_ELAPSED)"
                                                       : "glFinish-bracketed wall time (no timer query)");
    fprintf(f, "reference : exact model per full-res pixel in double, %.1f s of CPU for %d frames\n",
            b->reference_seconds, FRAME_COUNT);
}

/* Ratios by medians, and by minima (the least disturbed repetitions on a shared machine). */
static void summary_floor(const bench *b, FILE *f)
{
    fprintf(f, "\nparticle pass vs fill-rate floor (same quads, trivial shader), RGBA16F, target <= 1.5x\n"
               "(median ms [min]; ratio by medians, by minima):\n");
    for (int s = 1; s <= 8; s *= 2) {
        const result *fl = find_main(b, SBFX_OPACITY_FLOOR, s), *sp = find_main(b, SBFX_OPACITY_SPHERICAL, s);
        if (!fl || !sp) continue;
        double ratio = sp->part_ms / fl->part_ms, ratio_min = sp->part_min / fl->part_min;
        fprintf(f, "  scale 1/%d: spherical %.2f [%.2f] / floor %.2f [%.2f] = %.2fx, %.2fx  %s", s, sp->part_ms,
                sp->part_min, fl->part_ms, fl->part_min, ratio, ratio_min, verdict(ratio <= 1.5));
        for (int m = SBFX_OPACITY_PLANAR; m <= SBFX_OPACITY_EXACT; m++) {
            const result *o = find_main(b, (sbfx_opacity_mode)m, s);
            if (o && m != SBFX_OPACITY_SPHERICAL) fprintf(f, "; %s %.2fx", mode_names[m], o->part_ms / fl->part_ms);
        }
        const result *lpp = find(b, SBFX_OPACITY_SPHERICAL, s, SBFX_UPSAMPLE_NEAREST_DEPTH, 4, SBFX_DETAIL_R16F);
        if (lpp) fprintf(f, "; spherical, light per particle %.2fx %s", lpp->part_ms / fl->part_ms,
                         verdict(lpp->part_ms / fl->part_ms <= 1.5));
        fprintf(f, "%s\n", sp->part_ok && fl->part_ok ? "" : "  (particle pass not isolated: whole frame)");
    }
}

static void summary_speedup(const bench *b, FILE *f)
{
    const result *planar = find_main(b, SBFX_OPACITY_PLANAR, 1), *sph = find_main(b, SBFX_OPACITY_SPHERICAL, 4);
    if (!planar || !sph) return;
    double speedup = planar->ms / sph->ms, by_min = planar->ms_min / sph->ms_min;
    double wall = planar->wall_ms / sph->wall_ms;
    fprintf(f, "\nwhole frame, planar at full resolution / spherical at 1/4 with nearest-depth, target >= 3x:\n");
    fprintf(f, "  %.2f ms [%.2f] / %.2f ms [%.2f] = %.2fx by medians, %.2fx by minima  %s   (wall clock: %.2fx)\n",
            planar->ms, planar->ms_min, sph->ms, sph->ms_min, speedup, by_min, verdict(speedup >= 3.0), wall);
}

static void distance_line(FILE *f, const char *name, const result *r)
{
    fprintf(f, "  %-26s mean %.3f, max %.0f, PSNR %.2f dB; near silhouettes mean %.3f, PSNR %.2f dB\n", name,
            bench_error_mean(&r->err), r->err.max_abs, bench_psnr(r->err.sum_sq, r->err.count),
            bench_error_edge_mean(&r->err), bench_psnr(r->err.edge_sum_sq, r->err.edge_count));
}

static void summary_distance(const bench *b, FILE *f)
{
    const result *planar = find_main(b, SBFX_OPACITY_PLANAR, 1), *sph = find_main(b, SBFX_OPACITY_SPHERICAL, 4);
    const result *sph1 = find_main(b, SBFX_OPACITY_SPHERICAL, 1), *exact1 = find_main(b, SBFX_OPACITY_EXACT, 1);
    fprintf(f, "\ndistance to the exact CPU reference (8-bit levels of the RGBA8 output):\n");
    if (planar) distance_line(f, "planar, full res", planar);
    if (sph) distance_line(f, "spherical, 1/4 nearest-depth", sph);
    if (sph1) distance_line(f, "spherical, full res", sph1);
    if (exact1) distance_line(f, "exact, full res (GPU)", exact1);
    if (planar && sph) {
        bool closer = bench_error_mean(&sph->err) < bench_error_mean(&planar->err);
        fprintf(f, "  spherical@1/4 is closer to the exact reference than planar@1: %s (mean %.3f vs %.3f)\n",
                closer ? "YES" : "NO", bench_error_mean(&sph->err), bench_error_mean(&planar->err));
    }
}

/* Mean and max |a - b| over the RGB bytes of the kept frames. */
static void image_difference(const bench *b, const result *x, const result *y, double *mean, double *max)
{
    size_t n = (size_t)b->opt.width * b->opt.height, count = 0;
    double sum = 0.0;
    *max = 0.0;
    for (int i = 0; i < FRAME_COUNT; i++)
        for (size_t p = 0; p < n && x->images[i] && y->images[i]; p++)
            for (int k = 0; k < 3; k++) {
                double d = fabs((double)x->images[i][4 * p + k] - y->images[i][4 * p + k]);
                sum += d, count++;
                *max = fmax(*max, d);
            }
    *mean = count ? sum / count : NAN;
}

static void summary_luts(const bench *b, FILE *f)
{
    static const char *const names[] = {"", "analytic black body", "phase table", "analytic black body, phase table"};
    fprintf(f, "\nthe tables against the default (GPU image with the default's black-body table and analytic phase\n"
               "vs the GPU image with the other form, 8-bit levels):\n");
    for (int base = 0; base < 2; base++) {
        sbfx_opacity_mode m = base ? SBFX_OPACITY_EXACT : SBFX_OPACITY_SPHERICAL;
        int s = base ? 1 : 4;
        const result *table = find_main(b, m, s);
        for (int lut = 1; lut <= 3 && table; lut++) {
            const result *a = find(b, m, s, SBFX_UPSAMPLE_NEAREST_DEPTH, lut, SBFX_DETAIL_R16F);
            if (!a) continue;
            double mean, max;
            image_difference(b, table, a, &mean, &max);
            fprintf(f, "  %s@1/%d, %-32s mean %.4f, max %.0f; time %.2f -> %.2f ms\n", mode_names[m], s,
                    names[lut], mean, max, table->ms, a->ms);
        }
    }
}

/* Each cheaper model with the scene's density and with the density that matches the exact
 * model's optical depth through the centre: what is left is the shape of the model. */
static void summary_shape(const bench *b, FILE *f)
{
    fprintf(f, "\nmodel vs shape: mean error (edge mean) with the scene's density and with half of it (the exact\n"
               "model's optical depth through a particle's centre), 8-bit levels:\n");
    for (int s = 1; s <= 4; s *= 4)
        for (int m = SBFX_OPACITY_PLANAR; m <= SBFX_OPACITY_SPHERICAL; m++) {
            const result *plain = find_main(b, (sbfx_opacity_mode)m, s);
            const result *matched = find(b, (sbfx_opacity_mode)m, s, SBFX_UPSAMPLE_NEAREST_DEPTH, 8, SBFX_DETAIL_R16F);
            if (!plain || !matched) continue;
            double e0 = bench_error_mean(&plain->err), e1 = bench_error_mean(&matched->err);
            fprintf(f, "  %-9s 1/%d: %.3f (%.2f) -> matched %.3f (%.2f): %.0f %% of the error is the density scale, "
                       "%.0f %% the shape\n", mode_names[m], s, e0, bench_error_edge_mean(&plain->err), e1,
                    bench_error_edge_mean(&matched->err), 100.0 * (e0 - e1) / e0, 100.0 * e1 / e0);
        }
    const result *exact = find_main(b, SBFX_OPACITY_EXACT, 1), *exact4 = find_main(b, SBFX_OPACITY_EXACT, 4);
    if (exact && exact4)
        fprintf(f, "  exact     1/1: %.3f, 1/4: %.3f (its own model: precision and resolution only)\n",
                bench_error_mean(&exact->err), bench_error_mean(&exact4->err));
}

/* A quality the module offers as a choice of opacity model, scale, upsampling and light rate
 * (default target format, tables, half-float detail, the scene's density). */
static bool is_quality(const result *r)
{
    const config *c = &r->c;
    return r->ok && c->gpu && c->format == SBFX_FORMAT_RGBA16F && !c->analytic_blackbody && !c->table_phase &&
           c->detail == SBFX_DETAIL_R16F && c->opacity != SBFX_OPACITY_FLOOR && !c->density_matched && !c->lod;
}

static void quality_line(FILE *f, const char *what, const result *r)
{
    char label[64];
    short_label(r, label, sizeof(label));
    fprintf(f, "  %-22s %-14s %6.2f ms [%.2f]  mean %.3f  near silhouettes %.2f%s\n", what, label, r->ms, r->ms_min,
            bench_error_mean(&r->err), bench_error_edge_mean(&r->err), r->pareto ? "  (Pareto)" : "");
}

/* The defaults from the data: of the qualities that cost no more than the seed's default
 * (spherical, 1/4, nearest-depth, light per pixel) plus 10 % (the noise of a shared machine, and
 * a little paid for accuracy), the one closest to the reference; mean errors within 5 % of each
 * other count as a tie, which the error near silhouettes (what the upsampling is for) decides. */
static void summary_defaults(const bench *b, FILE *f)
{
    const result *seed = find_main(b, SBFX_OPACITY_SPHERICAL, 4), *best = NULL, *choice = NULL;
    if (!seed) return;
    double budget = 1.10 * seed->ms;
    for (int i = 0; i < b->result_count; i++) {
        const result *r = &b->results[i];
        if (is_quality(r) && r->ms <= budget && (!best || bench_error_mean(&r->err) < bench_error_mean(&best->err)))
            best = r;
    }
    for (int i = 0; i < b->result_count && best; i++) {
        const result *r = &b->results[i];
        if (!is_quality(r) || r->ms > budget || bench_error_mean(&r->err) > 1.05 * bench_error_mean(&best->err)) continue;
        if (!choice || bench_error_edge_mean(&r->err) < bench_error_edge_mean(&choice->err)) choice = r;
    }
    fprintf(f, "\ndefaults from the data: the quality closest to the reference within the seed default's time "
               "(+10 %%);\nmean errors within 5 %% are a tie, decided near silhouettes:\n");
    quality_line(f, "the seed's default", seed);
    if (best) quality_line(f, "least mean error", best);
    if (choice) quality_line(f, "the choice", choice);
}

static void write_summary(const bench *b)
{
    FILE *f = open_out(b, "summary.txt");
    fprintf(f, "== What accuracy costs: verdicts (docs/design.md §4) ==\n");
    summary_machine(b, f);
    summary_floor(b, f);
    summary_speedup(b, f);
    summary_distance(b, f);
    summary_shape(b, f);
    summary_defaults(b, f);
    summary_luts(b, f);
    fclose(f);
}

static void write_kept_pngs(const bench *b)
{
    for (int i = 0; i < b->result_count; i++) {
        const result *r = &b->results[i];
        if (!r->images[1] || !is_grid_point(r)) continue;
        char name[64];
        snprintf(name, sizeof(name), "gpu-%s-%d.png", mode_names[r->c.opacity], r->c.divisor);
        write_png(b, name, r->images[1]);
    }
}

/* ---- main ---------------------------------------------------------------------------- */

static void open_gl(bench *b)
{
    char err[512];
    if (egl_headless_open(&b->egl, err, sizeof(err)) != 0) die("EGL", err);
    bench_timer_init(&b->timer);
    if (bench_target_create(&b->target, b->opt.width, b->opt.height) != 0) die("GL", "RGBA8 target incomplete");
    b->cmf = sbfx_cie1931_2deg;
    printf("bench: %s, %s; timer query: %s\n", bench_gl_renderer(), bench_gl_version(),
           b->timer.has_query ? "yes" : "no (wall clock)");
}

/* --match: any of the comma-separated parts is in the label */
static bool label_matches(const char *label, const char *match)
{
    char part[64];
    for (const char *p = match; *p;) {
        size_t len = strcspn(p, ",");
        snprintf(part, sizeof(part), "%.*s", (int)(len < sizeof(part) ? len : sizeof(part) - 1), p);
        if (len > 0 && strstr(label, part)) return true;
        p += len + (p[len] == ',');
    }
    return false;
}

/* A gpu row's time is its float twin's: on a GPU both run the default programs; the gpu
 * row's own variant (filtering in the shader, mediump emulated) costs only on llvmpipe. */
static void copy_timing(result *gpu, const result *twin)
{
    if (twin->c.gpu) return;
    gpu->ms = twin->ms, gpu->ms_min = twin->ms_min, gpu->ms_max = twin->ms_max, gpu->wall_ms = twin->wall_ms;
    gpu->part_ms = twin->part_ms, gpu->part_min = twin->part_min, gpu->part_max = twin->part_max;
    gpu->part_wall_ms = twin->part_wall_ms, gpu->part_ok = twin->part_ok;
}

static void run_all(bench *b)
{
    config configs[MAX_CONFIGS];
    int n = grid_configs(&b->opt, configs);
    n += variant_configs(&b->opt, configs + n);
    if (!b->opt.shaders) /* each at float, then its twin at gpu precision right after */
        for (int i = n - 1; i >= 0; i--) {
            configs[2 * i] = configs[i];
            configs[2 * i + 1] = configs[i];
            configs[2 * i + 1].gpu = true;
        }
    if (!b->opt.shaders) n *= 2;
    for (int i = 0; i < n; i++) {
        result *r = &b->results[b->result_count];
        r->c = configs[i];
        char label[64];
        short_label(r, label, sizeof(label));
        if (b->opt.match && !label_matches(label, b->opt.match)) continue;
        b->result_count++;
        double start = seconds_now();
        run_config(b, r);
        if (r->c.gpu && b->result_count >= 2) copy_timing(r, &b->results[b->result_count - 2]);
        short_label(r, label, sizeof(label)); /* now with the format actually used */
        printf("bench: [%2d/%d] %-18s %7.2f ms [%.2f..%.2f]  particles %7.2f ms [%.2f..%.2f]  mean err %.3f  (%.1f s)\n",
               i + 1, n, label, r->ms, r->ms_min, r->ms_max, r->part_ms, r->part_min, r->part_max,
               bench_error_mean(&r->err), seconds_now() - start);
        fflush(stdout);
    }
}

static void close_all(bench *b)
{
    for (int i = 0; i < b->result_count; i++)
        for (int k = 0; k < FRAME_COUNT; k++) free(b->results[i].images[k]);
    for (int i = 0; i < FRAME_COUNT; i++) {
        ref_frame *rf = &b->frames[i];
        test_scene_destroy(&rf->scene);
        free(rf->distance), free(rf->scene_rgba), free(rf->ref_rgb), free(rf->edge), free(rf->look_mask);
    }
    free(b->detail);
    bench_fragments_destroy();
    bench_target_destroy(&b->target);
    bench_timer_destroy(&b->timer);
    egl_headless_close(&b->egl);
}

int main(int argc, char **argv)
{
    bench *b = xcalloc(1, sizeof(*b));
    b->opt = parse_options(argc, argv);
    setenv("SBFX_SHADER_LOG", "1", 1); /* the variants' names, for fragments.csv */
    print_shader_builds = b->opt.shaders;
    if (mkdir(b->opt.out, 0777) != 0 && errno != EEXIST) die(b->opt.out, strerror(errno));
    open_gl(b);
    prepare_references(b);
    run_all(b);
    if (b->opt.shaders) {
        close_all(b);
        free(b);
        return 0;
    }
    write_fragments(b);
    write_refined(b);
    mark_pareto(b);
    write_csv(b);
    write_plot_data(b);
    write_summary(b);
    write_kept_pngs(b);
    close_all(b);
    free(b);
    return 0;
}
