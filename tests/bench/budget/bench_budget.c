/* make bench, frame budget (issue 11 item 5): the barrage scene (24 overlapping explosions, up
 * to ~3800 particles) from its camera at t = 0 over the test scene, FRAMES frames of 1/60 s,
 *   - at a fixed quality, every level of the budget's ladder (the top, desc's defaults with the
 *     scene's render settings, then the default ladder below it), and
 *   - with desc.frame_budget_ms = each budget, the governor choosing the level,
 * each frame's time measured as the glFinish-bracketed wall time of sbfx_render (on llvmpipe,
 * a CPU rasteriser, that is the GPU time; the bench cannot use a timer query of its own: sbfx's
 * own query would then skip the frame — gpu_timer.h), and every EVERY-th frame with particles
 * compared with the CPU reference (the exact model per full-resolution pixel, of all the
 * particles: bench_reference.h), so the error of what was shown is measured like every other
 * level's.
 *
 *   bench_budget [--out DIR] [--size WxH] [--frames N] [--every K] [--budgets MS,MS,...]
 *
 * Without --budgets: 3 x the top's slowest frame (generous: nothing may change), and 0.6, 0.3
 * and 0.15 of its 95th percentile (the peak of the load). Writes DIR/budget.csv (scene,budget_ms,frame,ms,quality,level,run,particles,
 * gpu_ms,error; run = fixed or budget; budget_ms 0 for fixed runs; error only on compared
 * frames), DIR/budget.txt (the summary) and, for tests/bench/budget.gp (DIR/budget.png):
 * DIR/budget_runs.dat (one block per budget: frame, ms, level, particles) and
 * DIR/budget_points.dat (median ms over loaded frames — for a budget run, of the fixed runs'
 * times of the levels it chose, frame by frame —, error, label, 0 fixed / 1 budget).
 * Costs compare by medians: the machine is shared, and other jobs' spikes move means. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_gl.h"
#include "bench_metrics.h"
#include "bench_reference.h"
#include "egl/egl_headless.h"
#include "module.h"
#include "host/test_scene.h"

#define SCENE_NAME "barrage"
#define MAX_FRAMES 2000
#define MAX_BUDGETS 8
#define SETTLE_FRAMES 60 /* the first second, while the first explosions build up, is not counted */

typedef struct options {
    const char *out;
    int width, height, frames, every;
    double budgets[MAX_BUDGETS];
    int budget_count;
} options;

/* One run: a fixed level (budget 0) or a budget. */
typedef struct run {
    double budget;
    int fixed_level;             /* -1 for a budget run */
    double ms[MAX_FRAMES], gpu_ms[MAX_FRAMES];
    int level[MAX_FRAMES], particles[MAX_FRAMES];
    double error[MAX_FRAMES];    /* NAN where not compared */
    bench_error err;             /* over the compared frames */
    int changes, frames_over;
    bool identical_to_top;       /* every compared frame equals the fixed top's, byte for byte */
} run;

typedef struct bench {
    options opt;
    struct egl_headless egl;
    struct test_scene scene;
    bench_target target;
    sbfx_cmf cmf;
    sbfx_scene *fx_scene;
    sbfx_frame frame;
    double *distance;
    uint8_t *scene_rgba, *gpu, **top_images;
    float *detail;
    int detail_size, detail_frames;
    double **ref_rgb;            /* per frame, NULL where not compared */
    sbfx_quality ladder[SBFX_LADDER_MAX];
    char names[SBFX_LADDER_MAX][64];
    int levels;
} bench;

static void die(const char *what, const char *why)
{
    fprintf(stderr, "bench_budget: %s: %s\n", what, why);
    exit(1);
}

static void *xcalloc(size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size);
    if (!p) die("memory", "out of memory");
    return p;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static options parse_options(int argc, char **argv)
{
    options o = {.out = "build/bench", .width = 480, .height = 270, .frames = 400, .every = 40};
    for (int i = 1; i < argc; i++) {
        bool more = i + 1 < argc;
        if (!strcmp(argv[i], "--out") && more) o.out = argv[++i];
        else if (!strcmp(argv[i], "--size") && more && sscanf(argv[++i], "%dx%d", &o.width, &o.height) == 2) {}
        else if (!strcmp(argv[i], "--frames") && more) o.frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--every") && more) o.every = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--budgets") && more) {
            char *p = argv[++i], *end;
            for (o.budget_count = 0; *p && o.budget_count < MAX_BUDGETS; p = *end ? end + 1 : end) {
                o.budgets[o.budget_count] = strtod(p, &end);
                if (end == p || !(o.budgets[o.budget_count] > 0)) die("--budgets", "positive milliseconds, e.g. 40,20,10");
                o.budget_count++;
            }
        } else
            die("usage", "bench_budget [--out DIR] [--size WxH] [--frames N] [--every K] [--budgets MS,MS,...]");
    }
    if (o.width < 16 || o.height < 16 || o.width > 4096 || o.height > 4096 || o.frames < 1 || o.frames > MAX_FRAMES ||
        o.every < 1)
        die("options", "--size 16x16..4096x4096, --frames 1..2000, --every >= 1");
    return o;
}

static sbfx *create(bench *b, double budget)
{
    sbfx_desc d = {.scene = b->fx_scene, .frame_budget_ms = (float)budget};
    sbfx *fx = NULL;
    sbfx_result r = sbfx_create(&d, &fx);
    if (r != SBFX_OK) die("sbfx_create", fx ? sbfx_last_error(fx) : sbfx_result_string(r));
    return fx;
}

/* The scene, its camera at t = 0, the opaque distances and colour under the particles. */
static void open_scene(bench *b)
{
    char err[512];
    int w = b->opt.width, h = b->opt.height;
    if (egl_headless_open(&b->egl, err, sizeof(err)) != 0) die("EGL", err);
    b->cmf = sbfx_cie1931_2deg;
    if (sbfx_scene_load("scenes/" SCENE_NAME ".cfg", &b->fx_scene, err, sizeof(err)) != SBFX_OK) die("scene", err);
    if (test_scene_create(&b->scene, w, h, err, sizeof(err)) != 0) die("test scene", err);
    if (bench_target_create(&b->target, w, h) != 0) die("GL", "RGBA8 target incomplete");
    sbfx_scene_camera camera;
    sbfx_scene_camera_get(b->fx_scene, &camera);
    b->frame = (sbfx_frame){.scene_color_texture = b->scene.color_texture,
                            .scene_depth_texture = b->scene.depth_texture, .out_framebuffer = b->target.fbo,
                            .width = w, .height = h};
    test_scene_camera(&camera, 0.0, (float)w / h, b->frame.view, b->frame.projection);
    if (test_scene_draw(&b->scene, b->frame.view, b->frame.projection) != 0) die("test scene", "GL error");
    size_t n = (size_t)w * h;
    b->distance = xcalloc(n, sizeof(double));
    b->scene_rgba = xcalloc(n, 4);
    b->gpu = xcalloc(n, 4);
    float *window = xcalloc(n, sizeof(float));
    if (bench_read_depth(b->scene.depth_texture, w, h, window, err, sizeof(err)) != 0) die("depth", err);
    for (size_t i = 0; i < n; i++) b->distance[i] = sbfx_window_distance(&b->frame, window[i]);
    free(window);
    bench_read_rgba8(b->scene.framebuffer, w, h, b->scene_rgba);
}

/* The references of the compared frames (every EVERY-th frame with particles), and the ladder
 * the budget walks (the module's, read back with the names it gives its levels). */
static void prepare(bench *b)
{
    sbfx *fx = create(b, 1e3);
    b->levels = fx->budget->count;
    for (int i = 0; i < b->levels; i++) {
        b->ladder[i] = fx->budget->ladder[i];
        sbfx_quality_name(&b->ladder[i], b->names[i], sizeof(b->names[i]));
    }
    sbfx_detail_dimensions(fx, &b->detail_size, &b->detail_frames);
    b->detail = xcalloc((size_t)b->detail_size * b->detail_size * b->detail_frames, sizeof(float));
    sbfx_detail_generate(b->detail_size, b->detail_frames, 1, b->detail); /* desc.seed default 1 */
    bench_reference r = {b->detail, b->detail_size, b->detail_frames, &b->cmf};
    b->ref_rgb = xcalloc((size_t)b->opt.frames, sizeof(double *));
    b->top_images = xcalloc((size_t)b->opt.frames, sizeof(uint8_t *));
    size_t n = (size_t)b->opt.width * b->opt.height;
    double start = now_ms();
    int compared = 0;
    for (int f = 0; f < b->opt.frames; f++) {
        sbfx_update(fx, 1.0 / 60.0);
        const sbfx_view_particle *v;
        if (f % b->opt.every != b->opt.every - 1 || sbfx_frame_particles(fx, b->frame.view, &v) == 0) continue;
        b->ref_rgb[f] = xcalloc(n * 3, sizeof(double));
        if (bench_reference_render(&r, fx, &b->frame, b->distance, b->scene_rgba, b->ref_rgb[f], NULL) < 0)
            die("reference", "out of memory");
        compared++;
    }
    printf("bench_budget: %d reference frames in %.1f s; ladder:", compared, (now_ms() - start) / 1e3);
    for (int i = 0; i < b->levels; i++) printf(" %s", b->names[i]);
    printf("\n");
    sbfx_destroy(fx);
}

static void compare(bench *b, run *r, int f)
{
    size_t n = (size_t)b->opt.width * b->opt.height;
    bench_read_rgba8(b->target.fbo, b->opt.width, b->opt.height, b->gpu);
    bench_error e = {0};
    bench_error_add(&e, b->gpu, b->ref_rgb[f], NULL, n);
    bench_error_add(&r->err, b->gpu, b->ref_rgb[f], NULL, n);
    r->error[f] = bench_error_mean(&e);
    if (r->fixed_level == 0 && r->budget == 0) {
        b->top_images[f] = xcalloc(n, 4);
        memcpy(b->top_images[f], b->gpu, n * 4);
    } else if (b->top_images[f] && memcmp(b->top_images[f], b->gpu, n * 4) != 0) {
        r->identical_to_top = false;
    }
}

static int level_of(const bench *b, const char *name)
{
    for (int i = 0; i < b->levels; i++)
        if (!strcmp(b->names[i], name)) return i;
    return -1;
}

static void run_frames(bench *b, run *r)
{
    sbfx *fx = create(b, r->budget);
    if (r->fixed_level >= 0 && sbfx_set_quality(fx, &b->ladder[r->fixed_level]) != SBFX_OK)
        die("sbfx_set_quality", sbfx_last_error(fx));
    r->identical_to_top = true;
    for (int f = 0; f < b->opt.frames; f++) {
        sbfx_update(fx, 1.0 / 60.0);
        bench_target_fill_from(&b->target, b->scene.framebuffer);
        glFinish();
        double start = now_ms();
        if (sbfx_render(fx, &b->frame) != SBFX_OK) die("sbfx_render", sbfx_last_error(fx));
        glFinish(); /* the host's present: the module's timer results become available */
        r->ms[f] = now_ms() - start;
        sbfx_counters c;
        sbfx_stats(fx, &c);
        const sbfx_view_particle *v;
        r->particles[f] = sbfx_frame_particles(fx, b->frame.view, &v);
        r->level[f] = r->fixed_level >= 0 ? r->fixed_level : level_of(b, c.quality);
        r->gpu_ms[f] = c.gpu_ms;
        r->changes = c.quality_changes;
        r->frames_over = c.frames_over_budget;
        r->error[f] = NAN;
        if (b->ref_rgb[f]) compare(b, r, f);
    }
    sbfx_destroy(fx);
}

/* ---- summary ------------------------------------------------------------------------- */

typedef struct run_stats {
    double mean, median, p95, max, within, within_settled;
    int loaded;
} run_stats;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Over the frames with particles (the others run no pass); within: the share at most `budget`
 * (all of them, and from frame SETTLE_FRAMES on). */
static run_stats stats_of(const bench *b, const run *r, double budget)
{
    run_stats s = {0};
    double *sorted = xcalloc((size_t)b->opt.frames, sizeof(double));
    int within = 0, settled = 0, within_settled = 0;
    for (int f = 0; f < b->opt.frames; f++) {
        if (r->particles[f] == 0) continue;
        sorted[s.loaded++] = r->ms[f];
        s.mean += r->ms[f];
        within += r->ms[f] <= budget;
        if (f >= SETTLE_FRAMES) settled++, within_settled += r->ms[f] <= budget;
    }
    if (s.loaded) {
        qsort(sorted, (size_t)s.loaded, sizeof(double), cmp_double);
        s.mean /= s.loaded;
        s.p95 = sorted[(int)(0.95 * (s.loaded - 1))];
        s.median = sorted[(s.loaded - 1) / 2];
        s.max = sorted[s.loaded - 1];
        s.within = (double)within / s.loaded;
    }
    s.within_settled = settled ? (double)within_settled / settled : NAN;
    free(sorted);
    return s;
}

static FILE *open_out(const bench *b, const char *name);

static void write_csv(const bench *b, const run *runs, int count)
{
    FILE *f = open_out(b, "budget.csv");
    fprintf(f, "scene,budget_ms,frame,ms,quality,level,run,particles,gpu_ms,error\n");
    for (int i = 0; i < count; i++)
        for (int k = 0; k < b->opt.frames; k++) {
            const run *r = &runs[i];
            int level = r->level[k];
            fprintf(f, "%s,%.2f,%d,%.3f,%s,%d,%s,%d,%.3f,", SCENE_NAME, r->budget, k, r->ms[k],
                    level >= 0 ? b->names[level] : "?", level, r->fixed_level >= 0 ? "fixed" : "budget",
                    r->particles[k], r->gpu_ms[k]);
            if (isnan(r->error[k])) fprintf(f, "\n");
            else fprintf(f, "%.4f\n", r->error[k]);
        }
    fclose(f);
}

/* What the levels a budget run chose cost, measured without the noise between runs (the shared
 * machine's load moves from run to run): the median over its frames with particles of the
 * fixed run's time of the same frame at the level it chose. */
static double modelled_median(const bench *b, const run *fixed, const run *r)
{
    run m = {.fixed_level = -1};
    for (int f = 0; f < b->opt.frames; f++) {
        m.particles[f] = r->particles[f];
        m.ms[f] = r->level[f] >= 0 ? fixed[r->level[f]].ms[f] : r->ms[f];
    }
    return stats_of(b, &m, INFINITY).median;
}

/* The most accurate fixed level (the least error measured here) whose median frame time is at
 * most `ms` (-1: none). */
static int fixed_of_cost(const bench *b, const run *fixed, double ms)
{
    int best = -1;
    for (int i = 0; i < b->levels; i++) {
        run_stats s = stats_of(b, &fixed[i], INFINITY);
        if (s.median <= ms && (best < 0 || bench_error_mean(&fixed[i].err) < bench_error_mean(&fixed[best].err)))
            best = i;
    }
    return best;
}

/* The most accurate fixed level that stays within the budget on at least `share` of the loaded
 * frames after settling (what a fixed choice needs to do as well as the governor). */
static int fixed_of_share(const bench *b, const run *fixed, double budget, double share)
{
    int best = -1;
    for (int i = 0; i < b->levels; i++) {
        run_stats s = stats_of(b, &fixed[i], budget);
        if (s.within_settled >= share - 1e-9 &&
            (best < 0 || bench_error_mean(&fixed[i].err) < bench_error_mean(&fixed[best].err)))
            best = i;
    }
    return best;
}

static FILE *open_out(const bench *b, const char *name) { return bench_open_out(b->opt.out, name); }

static void write_plot_data(const bench *b, const run *fixed, const run *budgets)
{
    FILE *runs = open_out(b, "budget_runs.dat"), *points = open_out(b, "budget_points.dat");
    for (int i = 0; i < b->opt.budget_count; i++) {
        fprintf(runs, "# budget %.2f ms: frame ms level particles\n", budgets[i].budget);
        for (int k = 0; k < b->opt.frames; k++)
            fprintf(runs, "%d %.3f %d %d\n", k, budgets[i].ms[k], budgets[i].level[k], budgets[i].particles[k]);
        fprintf(runs, "\n\n");
    }
    for (int i = 0; i < b->levels; i++)
        fprintf(points, "%.3f %.4f \"%s\" 0\n", stats_of(b, &fixed[i], INFINITY).median, bench_error_mean(&fixed[i].err),
                b->names[i]);
    for (int i = 0; i < b->opt.budget_count; i++)
        fprintf(points, "%.3f %.4f \"budget %.1f ms\" 1\n", modelled_median(b, fixed, &budgets[i]),
                bench_error_mean(&budgets[i].err), budgets[i].budget);
    fclose(runs);
    fclose(points);
}

static void write_summary(const bench *b, const run *fixed, const run *budgets)
{
    FILE *f = open_out(b, "budget.txt");
    fprintf(f, "== Frame budgets: the %s scene, %dx%d, %d frames of 1/60 s, camera at t = 0 ==\n", SCENE_NAME,
            b->opt.width, b->opt.height, b->opt.frames);
    fprintf(f, "frame time: glFinish-bracketed sbfx_render (llvmpipe: the GPU time); error: mean |GPU - reference| in "
               "8-bit levels over every %d-th frame with particles (the CPU reference of all particles)\n",
            b->opt.every);
    fprintf(f, "\nfixed quality (the budget's ladder, top first): frame time over frames with particles\n");
    for (int i = 0; i < b->levels; i++) {
        run_stats s = stats_of(b, &fixed[i], INFINITY);
        fprintf(f, "  %d %-24s median %7.2f ms  mean %7.2f  p95 %7.2f  max %7.2f   error %.3f\n", i, b->names[i],
                s.median, s.mean, s.p95, s.max, bench_error_mean(&fixed[i].err));
    }
    fprintf(f, "\nwith a budget (after settling: from frame %d on):\n", SETTLE_FRAMES);
    for (int i = 0; i < b->opt.budget_count; i++) {
        const run *r = &budgets[i];
        run_stats s = stats_of(b, r, r->budget);
        int lo = r->level[0], hi = r->level[0];
        for (int k = 0; k < b->opt.frames; k++) lo = r->level[k] < lo ? r->level[k] : lo, hi = r->level[k] > hi ? r->level[k] : hi;
        fprintf(f, "  budget %7.2f ms: within %5.1f %% of frames (%5.1f %% after settling), mean %7.2f ms, p95 %7.2f, "
                   "median %7.2f, levels %d..%d, %d changes, %d measured frames over; error %.3f%s\n",
                r->budget, 100 * s.within, 100 * s.within_settled, s.mean, s.p95, s.median, lo, hi, r->changes, r->frames_over,
                bench_error_mean(&r->err), r->identical_to_top ? "; frames identical to the fixed top's" : "");
        double modelled = modelled_median(b, fixed, r);
        int same_cost = fixed_of_cost(b, fixed, modelled), same_share = fixed_of_share(b, fixed, r->budget, s.within_settled);
        if (same_cost >= 0)
            fprintf(f, "      its levels cost a median %.2f ms in the fixed runs; the most accurate fixed level as "
                       "cheap: %s, error %.3f (median %.2f ms)\n", modelled, b->names[same_cost],
                    bench_error_mean(&fixed[same_cost].err), stats_of(b, &fixed[same_cost], INFINITY).median);
        if (same_share >= 0)
            fprintf(f, "      the most accurate fixed level as often within this budget: %s, error %.3f (within %.1f %%)\n",
                    b->names[same_share], bench_error_mean(&fixed[same_share].err),
                    100 * stats_of(b, &fixed[same_share], r->budget).within_settled);
        else
            fprintf(f, "      no fixed level is as often within this budget\n");
    }
    fclose(f);
}

int main(int argc, char **argv)
{
    bench *b = xcalloc(1, sizeof(*b));
    b->opt = parse_options(argc, argv);
    open_scene(b);
    prepare(b);
    run *fixed = xcalloc((size_t)b->levels, sizeof(run));
    for (int i = 0; i < b->levels; i++) {
        fixed[i].fixed_level = i;
        double start = now_ms();
        run_frames(b, &fixed[i]);
        run_stats s = stats_of(b, &fixed[i], INFINITY);
        printf("bench_budget: fixed %-24s mean %7.2f ms, max %7.2f, error %.3f (%.0f s)\n", b->names[i], s.mean, s.max,
               bench_error_mean(&fixed[i].err), (now_ms() - start) / 1e3);
        fflush(stdout);
    }
    if (b->opt.budget_count == 0) {
        run_stats top = stats_of(b, &fixed[0], INFINITY);
        b->opt.budgets[0] = round(3.0 * top.max * 10) / 10; /* generous, spikes of other jobs included */
        const double share[] = {0.6, 0.3, 0.15};
        for (int i = 0; i < 3; i++) b->opt.budgets[i + 1] = round(top.p95 * share[i] * 10) / 10;
        b->opt.budget_count = 4;
    }
    run *budgets = xcalloc((size_t)b->opt.budget_count, sizeof(run));
    for (int i = 0; i < b->opt.budget_count; i++) {
        budgets[i] = (run){.budget = b->opt.budgets[i], .fixed_level = -1};
        double start = now_ms();
        run_frames(b, &budgets[i]);
        run_stats s = stats_of(b, &budgets[i], budgets[i].budget);
        printf("bench_budget: budget %7.2f ms: within %.1f %% (%.1f %% after settling), %d changes, error %.3f (%.0f s)\n",
               budgets[i].budget, 100 * s.within, 100 * s.within_settled, budgets[i].changes,
               bench_error_mean(&budgets[i].err), (now_ms() - start) / 1e3);
        fflush(stdout);
    }
    run *all = xcalloc((size_t)(b->levels + b->opt.budget_count), sizeof(run));
    memcpy(all, fixed, sizeof(run) * (size_t)b->levels);
    memcpy(all + b->levels, budgets, sizeof(run) * (size_t)b->opt.budget_count);
    write_csv(b, all, b->levels + b->opt.budget_count);
    write_summary(b, fixed, budgets);
    write_plot_data(b, fixed, budgets);
    printf("bench_budget: %s/budget.csv, %s/budget.txt\n", b->opt.out, b->opt.out);
    return 0;
}
