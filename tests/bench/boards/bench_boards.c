/* make bench, the boards' frame (issue 33; docs/gpus.md, "The boards' frame"): every example
 * scene over its life, from its own camera (sbfx-play's) over the test scene, at 1280x720 and
 * 1920x1080. Every STEP seconds of the scene's timeline a frame is rendered twice: with the
 * composite and the depth passes over the particles' tiles ("tiles", src/render/tiles.h) and over
 * the whole screen, as before tiles ("full", sbfx_tiles.full_screen); each time the fragments of
 * every program sbfx draws with are counted on the GPU (bench_fragments.h) and named after the
 * variant it built (bench_programs.h). The composite's counted fragments are checked against
 * sbfx_counters.composite_pixels. Writes OUT/boards.csv, one row per program of a rendered frame:
 *   scene,width,height,divisor,t,mode,shader,variant,fragments,composite_tiles,composite_pixels,rects,particles,refined
 * (refined: of the fragments, those of mixed resolution's refinement, render/refine.c)
 * which tools/boards-table.sh prices with Mesa's Mali estimates (mali.csv, tools/shader-stats.sh).
 *   bench_boards [--out DIR] [--sizes WxH[,WxH...]] [--step SECONDS] [--scenes a,b] [--camera scene|orbit]
 *                [--tile-sizes N[,N...]] [--quality LEVEL] [--termination on|off] [--frame-rate HZ]
 * --termination on|off renders with or without early termination of the particles
 * (render/terminate.c; default: each scene's render.early_termination, off unless it says on):
 * docs/gpus.md's "Front to back, and early termination".
 * --quality LEVEL renders every scene at that level (e.g. exact/4/mx) instead of its own;
 * --quality mixed, at its own level with mixed resolution's upsampling.
 * --error also renders each frame at its level and at full resolution in RGBA32F (the level's
 * other choices kept) over the test scene and writes OUT/errors.csv:
 *   scene,width,height,t,quality,pixels,mean_abs_err
 * (mean |difference| in 8-bit levels over the pixels either image changes).
 * --frame-rate HZ (60): each counted rendering sees the frame before as a player at HZ would (the
 * camera and the particles 1/HZ s earlier): the motion the velocity blur's blocks follow.
 * --camera orbit: the accuracy bench's camera (test_scene_orbit_camera, 8.5 m from the blast)
 * instead of each scene's own.
 * --tile-sizes renders the tiled frame once per tile size (mode "tilesN"; the default size only:
 * "tiles"), for choosing the size (docs/gpus.md, "Tiles"). Counts, not times: llvmpipe's times
 * say nothing about a Mali's. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_fragments.h"
#include "bench_gl.h"
#include "bench_programs.h"
#include "egl/egl_headless.h"
#include "host/test_scene.h"
#include "internal.h"

#define MAX_SIZES 4
#define MAX_TILE_SIZES 6
#define MAX_SCENES 16
#define LIFE_MAX 12.0    /* seconds of a scene's timeline at most */
#define SIM_STEP (1.0 / 60.0)

typedef struct options {
    const char *out;
    int sizes[MAX_SIZES][2], size_count;
    int tile_sizes[MAX_TILE_SIZES], tile_size_count;
    double step;
    double frame_rate; /* --frame-rate: the player's, for the motion between frames */
    bool orbit;   /* --camera orbit: the accuracy bench's orbit camera, not the scene's */
    bool error;          /* --error: OUT/errors.csv, each frame against its own full resolution */
    const char *quality; /* --quality LEVEL: every scene at that level (sbfx_set_quality), not its own */
    int termination;     /* --termination: 1 on, 0 off, -1 the scene's */
    char scenes[MAX_SCENES][64];
    int scene_count;
} options;

static void die(const char *what, const char *why)
{
    fprintf(stderr, "bench_boards: %s: %s\n", what, why);
    exit(1);
}

static void log_line(sbfx_log_level level, const char *message, void *user)
{
    (void)user;
    if (level == SBFX_LOG_INFO) bench_programs_note(message);
    else fprintf(stderr, "bench_boards: sbfx: %s\n", message);
}

/* The frame before, as at the player's frame rate (--frame-rate, 60 Hz): the camera one frame
 * earlier and the particles where they were then, so that every counted rendering (both modes
 * render the same instant) sees the motion a player at that rate shows, not the step between the
 * bench's frames nor none (the second rendering of an instant after the first). The velocity
 * blur's blocks (post.c) depend on it. */
static void previous_frame(sbfx *fx, const sbfx_scene_camera *camera, double t, float aspect, double hz)
{
    float view[16], projection[16];
    if (camera) test_scene_camera(camera, t - 1.0 / hz, aspect, view, projection);
    else test_scene_orbit_camera(t - 1.0 / hz, aspect, view, projection);
    memcpy(fx->sim->previous_view, view, sizeof(view));
    fx->sim->previous_render_time = fx->sim->time - 1.0 / hz;
    fx->sim->have_previous_view = true;
    sbfx_post_gl *p = &fx->render->post;
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++) s += (double)projection[k * 4 + r] * view[c * 4 + k];
            p->previous_view_projection[c * 4 + r] = s;
        }
    p->last_time = fx->sim->time - 1.0 / hz;
    p->have_previous = true;
}

/* One rendering of a frame: the module's programs and what each shaded. */
static void render_counted(sbfx *fx, const sbfx_frame *frame, const char *mode, FILE *csv, const char *scene,
                           double t)
{
    bench_fragment_tally tally;
    bench_fragments_begin(&tally);
    if (sbfx_render(fx, frame) != SBFX_OK) die("sbfx_render", sbfx_last_error(fx));
    bench_fragments_end();
    if (tally.failed) die(scene, "a fragment count failed");
    sbfx_counters c;
    sbfx_stats(fx, &c);
    const sbfx_tiles *tiles = &fx->render->tiles;
    for (int k = 0; k < tally.draws; k++) {
        char shader[64], variant[256];
        bench_program_shader(tally.program[k], shader, sizeof(shader), variant, sizeof(variant));
        bool composite = strcmp(shader, "composite.frag") == 0 && !strstr(variant, "SCENE_ONLY");
        if (composite && tally.fragments[k] != (double)c.composite_pixels)
            fprintf(stderr, "bench_boards: %s at %.2f s (%s): the composite shaded %.0f fragments, "
                    "composite_pixels says %d\n", scene, t, mode, tally.fragments[k], c.composite_pixels);
        fprintf(csv, "%s,%d,%d,%d,%.3f,%s,%s,%s,%.0f,%d,%d,%d,%d,%.0f\n", scene, frame->width, frame->height,
                fx->scene->desc.target_divisor, t, mode, shader, variant, tally.fragments[k], c.composite_tiles,
                c.composite_pixels, tiles->inside + tiles->outside, c.particles_alive, tally.masked[k]);
    }
}

/* --error: the frame at the module's level against the same frame at full resolution in RGBA32F
 * (the level's other choices kept), over the test scene: mean |difference| in 8-bit levels over
 * the pixels either changes (the bare scene's differ), a row of OUT/errors.csv. */
typedef struct error_pass {
    uint8_t *bare, *level, *full;
    FILE *csv;
} error_pass;

static void render_into(sbfx *fx, const sbfx_frame *frame, const bench_target *out, GLuint scene_fbo, uint8_t *rgba)
{
    bench_target_fill_from(out, scene_fbo);
    if (rgba && sbfx_render(fx, frame) != SBFX_OK) die("sbfx_render", sbfx_last_error(fx));
    bench_read_rgba8(out->fbo, out->width, out->height, rgba);
}

static void frame_error(sbfx *fx, const sbfx_frame *frame, const bench_target *out, GLuint scene_fbo,
                        error_pass *e, const char *scene, double t)
{
    sbfx_quality level, full;
    sbfx_get_quality(fx, &level);
    full = level;
    full.target_divisor = 1;
    full.target_format = SBFX_FORMAT_RGBA32F;
    full.upsample = SBFX_UPSAMPLE_NEAREST_DEPTH;
    full.lod_particles = 0;
    bench_target_fill_from(out, scene_fbo);
    bench_read_rgba8(out->fbo, out->width, out->height, e->bare);
    render_into(fx, frame, out, scene_fbo, e->level);
    if (sbfx_set_quality(fx, &full) != SBFX_OK) die("full resolution", sbfx_last_error(fx));
    render_into(fx, frame, out, scene_fbo, e->full);
    if (sbfx_set_quality(fx, &level) != SBFX_OK) die("back to the level", sbfx_last_error(fx));
    double sum = 0.0;
    long covered = 0;
    for (long i = 0; i < (long)out->width * out->height; i++) {
        const uint8_t *a = &e->level[4 * i], *b = &e->full[4 * i], *s = &e->bare[4 * i];
        if (a[0] == s[0] && a[1] == s[1] && a[2] == s[2] && b[0] == s[0] && b[1] == s[1] && b[2] == s[2]) continue;
        sum += (abs(a[0] - b[0]) + abs(a[1] - b[1]) + abs(a[2] - b[2])) / 3.0;
        covered++;
    }
    char name[64];
    sbfx_quality_name(&level, name, sizeof(name));
    fprintf(e->csv, "%s,%d,%d,%.3f,%s,%ld,%.4f\n", scene, out->width, out->height, t, name, covered,
            covered ? sum / covered : 0.0);
}

/* The scene over its life at one size: a frame every opt->step seconds until its last particle
 * died (the timeline's last trigger past), both ways. */
static void scene_at_size(const options *opt, const char *name, int w, int h, FILE *csv, FILE *errors)
{
    char path[256], err[512];
    snprintf(path, sizeof(path), "scenes/%s.cfg", name);
    sbfx_scene *scene = NULL;
    if (sbfx_scene_load(path, &scene, err, sizeof(err)) != SBFX_OK) die(path, err);
    sbfx_scene_camera camera;
    bool has_camera = !opt->orbit && sbfx_scene_camera_get(scene, &camera);
    struct test_scene host;
    if (test_scene_create(&host, w, h, err, sizeof(err)) != 0) die("test scene", err);
    bench_target out;
    if (bench_target_create(&out, w, h) != 0) die("output framebuffer", "incomplete");
    sbfx *fx = NULL;
    if (sbfx_create(&(sbfx_desc){.scene = scene, .log = log_line}, &fx) != SBFX_OK) die(path, "sbfx_create failed");
    if (opt->termination >= 0 && sbfx_set_early_termination(fx, opt->termination > 0) != SBFX_OK)
        die("--termination", sbfx_last_error(fx));
    if (opt->quality) {
        sbfx_quality q;
        if (!strcmp(opt->quality, "mixed")) { /* the scene's own level, refined */
            sbfx_get_quality(fx, &q);
            q.upsample = SBFX_UPSAMPLE_MIXED;
        } else if (sbfx_quality_parse(opt->quality, &q, err, sizeof(err)) != SBFX_OK)
            die("--quality", err);
        if (sbfx_set_quality(fx, &q) != SBFX_OK) die("--quality", sbfx_last_error(fx));
    }
    double last_trigger = 0.0;
    for (int i = 0; i < scene->timeline_count; i++)
        if (scene->timeline[i].time > last_trigger) last_trigger = scene->timeline[i].time;
    sbfx_frame frame = {.scene_color_texture = host.color_texture, .scene_depth_texture = host.depth_texture,
                        .out_framebuffer = out.fbo, .width = w, .height = h};
    int frames = 0;
    for (double next = opt->step; sbfx_elapsed(fx) < LIFE_MAX; next += opt->step) {
        while (sbfx_elapsed(fx) < next - 1e-9) sbfx_update(fx, SIM_STEP);
        double t = sbfx_elapsed(fx);
        sbfx_counters c;
        sbfx_stats(fx, &c);
        if (t > last_trigger && c.particles_alive == 0) break;
        if (has_camera) test_scene_camera(&camera, t, (float)w / (float)h, frame.view, frame.projection);
        else test_scene_orbit_camera(t, (float)w / (float)h, frame.view, frame.projection);
        if (test_scene_draw(&host, frame.view, frame.projection) != 0) die("test scene", "GL error");
        float aspect = (float)w / (float)h;
        fx->render->tiles.full_screen = true;
        previous_frame(fx, has_camera ? &camera : NULL, t, aspect, opt->frame_rate);
        render_counted(fx, &frame, "full", csv, name, t);
        fx->render->tiles.full_screen = false;
        for (int k = 0; k < opt->tile_size_count; k++) {
            previous_frame(fx, has_camera ? &camera : NULL, t, aspect, opt->frame_rate);
            char mode[32] = "tiles";
            if (opt->tile_sizes[k] > 0) snprintf(mode, sizeof(mode), "tiles%d", opt->tile_sizes[k]);
            fx->render->tiles.size_wanted = opt->tile_sizes[k];
            render_counted(fx, &frame, mode, csv, name, t);
        }
        if (errors) {
            error_pass e = {malloc((size_t)w * h * 4), malloc((size_t)w * h * 4), malloc((size_t)w * h * 4), errors};
            if (!e.bare || !e.level || !e.full) die("--error", "out of memory");
            frame_error(fx, &frame, &out, host.framebuffer, &e, name, t);
            free(e.bare), free(e.level), free(e.full);
        }
        frames++;
    }
    printf("bench_boards: %s at %dx%d: %d frames over %.1f s\n", name, w, h, frames, sbfx_elapsed(fx));
    fflush(stdout);
    sbfx_destroy(fx);
    sbfx_scene_free(scene);
    bench_target_destroy(&out);
    test_scene_destroy(&host);
}

/* ---- options ---- */

static void parse_list(const char *text, const char *what, int *out, int max, int *count, bool pairs)
{
    *count = 0;
    for (const char *p = text; p && *p;) {
        int a = 0, b = 0, used = 0;
        if (*count == max || (pairs ? sscanf(p, "%dx%d%n", &a, &b, &used) != 2 : sscanf(p, "%d%n", &a, &used) != 1))
            die(what, text);
        out[(*count) * (pairs ? 2 : 1)] = a;
        if (pairs) out[(*count) * 2 + 1] = b;
        (*count)++;
        p += used;
        p = *p == ',' ? p + 1 : NULL;
    }
}

static options parse(int argc, char **argv)
{
    options o = {.out = "build/bench", .size_count = 2, .sizes = {{1280, 720}, {1920, 1080}}, .step = 0.1,
                 .frame_rate = 60.0, .tile_size_count = 1, .termination = -1};
    const char *all[] = {"barrage", "campfire", "dust-storm", "explosion", "lit-smoke", "night", "post", "smoke"};
    for (size_t i = 0; i < sizeof(all) / sizeof(all[0]); i++) snprintf(o.scenes[o.scene_count++], 64, "%s", all[i]);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--error")) { /* the one option without a value */
            o.error = true;
            continue;
        }
        if (!v) die(a, "needs a value");
        i++;
        if (!strcmp(a, "--out")) o.out = v;
        else if (!strcmp(a, "--step") && (o.step = atof(v)) > 0) continue;
        else if (!strcmp(a, "--frame-rate") && (o.frame_rate = atof(v)) > 0) continue;
        else if (!strcmp(a, "--quality") && v) o.quality = v;
        else if (!strcmp(a, "--termination") && (!strcmp(v, "on") || !strcmp(v, "off"))) o.termination = !strcmp(v, "on");
        else if (!strcmp(a, "--camera") && (!strcmp(v, "scene") || !strcmp(v, "orbit"))) o.orbit = !strcmp(v, "orbit");
        else if (!strcmp(a, "--sizes")) parse_list(v, a, &o.sizes[0][0], MAX_SIZES, &o.size_count, true);
        else if (!strcmp(a, "--tile-sizes")) parse_list(v, a, o.tile_sizes, MAX_TILE_SIZES, &o.tile_size_count, false);
        else if (!strcmp(a, "--scenes")) {
            o.scene_count = 0;
            for (const char *p = v; *p && o.scene_count < MAX_SCENES;) {
                size_t n = strcspn(p, ",");
                snprintf(o.scenes[o.scene_count++], 64, "%.*s", (int)n, p);
                p += n + (p[n] == ',');
            }
        } else die(a, "unknown option or value (--out DIR, --sizes WxH,..., --step S, --scenes a,b, "
                      "--camera scene|orbit, --tile-sizes N,..., --quality LEVEL, --termination on|off, "
                      "--frame-rate HZ, --error)");
    }
    return o;
}

int main(int argc, char **argv)
{
    options opt = parse(argc, argv);
    setenv("SBFX_SHADER_LOG", "1", 1); /* the programs' names */
    struct egl_headless egl;
    char err[512], path[1024];
    if (egl_headless_open(&egl, err, sizeof(err)) != 0) die("EGL", err);
    snprintf(path, sizeof(path), "%s/boards.csv", opt.out);
    FILE *csv = fopen(path, "w");
    if (!csv) die(path, "cannot write");
    fprintf(csv, "scene,width,height,divisor,t,mode,shader,variant,fragments,composite_tiles,composite_pixels,rects,"
                 "particles,refined\n");
    FILE *errors = NULL;
    if (opt.error) {
        snprintf(path, sizeof(path), "%s/errors.csv", opt.out);
        if (!(errors = fopen(path, "w"))) die(path, "cannot write");
        fprintf(errors, "scene,width,height,t,quality,pixels,mean_abs_err\n");
    }
    for (int s = 0; s < opt.scene_count; s++)
        for (int k = 0; k < opt.size_count; k++)
            scene_at_size(&opt, opt.scenes[s], opt.sizes[k][0], opt.sizes[k][1], csv, errors);
    fclose(csv);
    if (errors) fclose(errors);
    bench_fragments_destroy();
    egl_headless_close(&egl);
    printf("bench_boards: %s\n", path);
    return 0;
}
