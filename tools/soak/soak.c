/* sbfx-soak: the kiosk loop for simulated hours, compressed into minutes (docs/kiosk-and-devices.md,
 * "Kiosk months"). Headless (EGL surfaceless), small frames; one module per scene on one context, all
 * drawn over the test scene every --render-every frames (8); an effect is triggered every
 * fraction of a second, cycling through every effect of every scene (the defaults: barrage,
 * post with velocity blur and depth of field, campfire with heat shimmer, lit-smoke with its
 * orbiting light, and a history-blur scene of two effects). Every frame advances the fixed-step
 * simulation by --dt (at most 0.25 s: what one sbfx_update takes without cutting time). Every N
 * frames a sample goes to DIR/soak.csv (soak_check.h: RSS, anonymous and file-backed, heap
 * bytes, what sbfx holds, the GL objects alive in the context, particles, triggers); at the end
 * the flatness check runs on the samples.
 * Exit status: 0 flat, 1 bad arguments or a GL/sbfx failure, 2 something grew (named on stderr).
 * --inject-leak texture|malloc (with --leak-every N frames, default 10) leaks on purpose, so
 * that tests/soak.sh can show the check catches it. */
#include <errno.h>
#include <malloc.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "egl/egl_headless.h"
#include "scene/scene.h"
#include "soak_check.h"
#include "host/test_scene.h"

#define MAX_MODULES 8
#define MAX_SAMPLES_DEFAULT 400
#define LEAK_BYTES (256 * 1024)

enum leak_kind { LEAK_NONE, LEAK_TEXTURE, LEAK_MALLOC };

struct soak_options {
    double hours, dt, trigger_every, start_time, warmup;
    int width, height, sample_every, leak_every, render_every;
    int64_t rss_tolerance_kib, heap_tolerance_kib;
    const char *scenes[MAX_MODULES];
    int scene_count;
    const char *out_dir;
    enum leak_kind leak;
    bool quiet;
};

struct module {
    sbfx *fx;
    char effects[SBFX_MAX_EFFECTS][SBFX_NAME_MAX];
    int effect_count;
    const char *name;
};

struct soak {
    struct soak_options opt;
    struct egl_headless egl;
    struct test_scene host;
    GLuint out_rb, out_fbo;
    struct module modules[MAX_MODULES];
    int module_count, pair_count;
    sbfx_scene_camera camera;
    int64_t frames, next_trigger;
    struct soak_sample *samples;
    int sample_count, sample_capacity;
    FILE *csv;
    double wall_start;
};

/* A history-blur scene with two effects: the post effect and effect cycling the example scenes
 * do not cover. */
static const char history_scene[] =
    "render = { max_particles = 1024; };\n"
    "media = { smoke = { albedo = 0.3; density = 0.4; };\n"
    "          fire = { density = 0.4; temperature = [1500.0, 2000.0]; emission = 150.0; }; };\n"
    "effects = {\n"
    "  puff = { steps = ( { type = \"emitter\"; medium = \"smoke\"; count = 40; spawn_radius = 0.4;\n"
    "           speed = [0.5, 1.5]; upward = 0.6; lifetime = [1.0, 2.5]; radius = [0.3, 0.9]; } ); };\n"
    "  flare = { steps = ( { type = \"emitter\"; medium = \"fire\"; count = 30; spawn_radius = 0.3;\n"
    "            speed = [1.0, 3.0]; lifetime = [0.5, 1.2]; radius = [0.2, 0.6]; intensity = [1.0, 0.0]; },\n"
    "          { type = \"light_flash\"; duration = 0.4; color = [4.0, 3.0, 2.0]; } ); };\n"
    "};\n"
    "post = { motion_blur = { mode = \"history\"; persistence = 0.08; }; };\n";

static const char *const default_scenes[] = {"scenes/barrage.cfg", "scenes/post.cfg", "scenes/campfire.cfg",
                                             "scenes/lit-smoke.cfg", "history-blur"};

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static void usage(FILE *f)
{
    fputs("usage: sbfx-soak [options]\n"
          "  --hours H              simulated hours (default 10)\n"
          "  --dt S                 simulated seconds per frame, 0 < S <= 0.25 (0.25)\n"
          "  --trigger-every S      simulated seconds between triggers, 0.01..60 (0.2)\n"
          "  --size WxH             frame size, 16..1024 each (128x72)\n"
          "  --scene FILE           a scene (repeatable, up to 8; 'history-blur' is built in);\n"
          "                         default: barrage, post, campfire, lit-smoke, history-blur\n"
          "  --start-time S         the modules' clock starts there (0)\n"
          "  --render-every N       draw every N-th frame (8); the others only simulate\n"
          "  --sample-every N       frames between samples (default: 400 samples in all)\n"
          "  --warmup F             fraction of the samples before the check starts (0.25)\n"
          "  --rss-tolerance KIB    anonymous resident memory growth allowed after warm-up (4096)\n"
          "  --heap-tolerance KIB   malloc'ed bytes growth allowed after warm-up (2048)\n"
          "  --out DIR              DIR/soak.csv (build/soak)\n"
          "  --quiet                no progress lines\n"
          "Exit status: 0 flat, 1 bad arguments or a failure, 2 something grew.\n", f);
}

/* ---- arguments ---------------------------------------------------------------------------- */

static bool number(const char *s, double lo, double hi, double *out)
{
    char *end = NULL;
    errno = 0;
    double v = s ? strtod(s, &end) : NAN;
    if (!s || end == s || *end || errno || !(v >= lo && v <= hi)) return false;
    *out = v;
    return true;
}

static int bad(const char *flag, const char *want, const char *got)
{
    fprintf(stderr, "sbfx-soak: %s: expected %s, got '%s'\n", flag, want, got ? got : "nothing");
    return -EINVAL;
}

static int parse_value(struct soak_options *o, const char *flag, const char *v)
{
    double x = 0;
    if (!strcmp(flag, "--hours")) return number(v, 1e-4, 1e4, &o->hours) ? 0 : bad(flag, "hours in 0.0001..10000", v);
    if (!strcmp(flag, "--dt")) return number(v, 1e-4, 0.25, &o->dt) ? 0 : bad(flag, "seconds in 0.0001..0.25", v);
    if (!strcmp(flag, "--trigger-every"))
        return number(v, 0.01, 60, &o->trigger_every) ? 0 : bad(flag, "seconds in 0.01..60", v);
    if (!strcmp(flag, "--start-time"))
        return number(v, 0, 1e10, &o->start_time) ? 0 : bad(flag, "seconds in 0..1e10", v);
    if (!strcmp(flag, "--warmup")) return number(v, 0, 0.9, &o->warmup) ? 0 : bad(flag, "a fraction in 0..0.9", v);
    if (!strcmp(flag, "--size"))
        return v && sscanf(v, "%dx%d", &o->width, &o->height) == 2 && o->width >= 16 && o->height >= 16 &&
                       o->width <= 1024 && o->height <= 1024 ? 0 : bad(flag, "WxH, 16..1024 each", v);
    if (!strcmp(flag, "--sample-every") || !strcmp(flag, "--leak-every") || !strcmp(flag, "--render-every")) {
        if (!number(v, 1, 1e9, &x) || x != floor(x)) return bad(flag, "a whole number of frames >= 1", v);
        *(flag[2] == 's' ? &o->sample_every : flag[2] == 'l' ? &o->leak_every : &o->render_every) = (int)x;
        return 0;
    }
    if (!strcmp(flag, "--rss-tolerance") || !strcmp(flag, "--heap-tolerance")) {
        if (!number(v, 0, 1e9, &x)) return bad(flag, "KiB, 0..1e9", v);
        *(flag[2] == 'r' ? &o->rss_tolerance_kib : &o->heap_tolerance_kib) = (int64_t)x;
        return 0;
    }
    if (!strcmp(flag, "--scene")) {
        if (o->scene_count == MAX_MODULES) return bad(flag, "at most 8 scenes", v);
        o->scenes[o->scene_count++] = v;
        return 0;
    }
    if (!strcmp(flag, "--out")) return v && *v ? (o->out_dir = v, 0) : bad(flag, "a folder", v);
    if (!strcmp(flag, "--inject-leak")) {
        o->leak = v && !strcmp(v, "texture") ? LEAK_TEXTURE : v && !strcmp(v, "malloc") ? LEAK_MALLOC : LEAK_NONE;
        return o->leak != LEAK_NONE ? 0 : bad(flag, "texture|malloc", v);
    }
    fprintf(stderr, "sbfx-soak: unknown flag '%s' (--help lists them)\n", flag);
    return -EINVAL;
}

static int parse_args(struct soak_options *o, int argc, char **argv)
{
    *o = (struct soak_options){.hours = 10, .dt = 0.25, .trigger_every = 0.2, .warmup = 0.25, .width = 128,
                               .height = 72, .leak_every = 10, .render_every = 8, .rss_tolerance_kib = 4096,
                               .heap_tolerance_kib = 2048, .out_dir = "build/soak"};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage(stdout);
            exit(0);
        }
        if (!strcmp(argv[i], "--quiet")) {
            o->quiet = true;
            continue;
        }
        if (parse_value(o, argv[i], i + 1 < argc ? argv[i + 1] : NULL)) return -EINVAL;
        i++;
    }
    if (!o->scene_count)
        for (size_t i = 0; i < sizeof(default_scenes) / sizeof(default_scenes[0]); i++)
            o->scenes[o->scene_count++] = default_scenes[i];
    return 0;
}

/* ---- set-up ------------------------------------------------------------------------------- */

static void on_log(sbfx_log_level level, const char *message, void *user)
{
    if (level != SBFX_LOG_INFO) fprintf(stderr, "sbfx-soak: %s: %s\n", (const char *)user, message);
}

static int load_module(struct soak *s, const char *name, struct module *m)
{
    char err[512];
    sbfx_scene *scene = NULL;
    sbfx_result r = !strcmp(name, "history-blur")
                        ? sbfx_scene_parse(history_scene, "history-blur", &scene, err, sizeof(err))
                        : sbfx_scene_load(name, &scene, err, sizeof(err));
    if (r != SBFX_OK) {
        fprintf(stderr, "sbfx-soak: %s\n", err);
        return -EINVAL;
    }
    m->name = name;
    m->effect_count = scene->effect_count;
    for (int i = 0; i < scene->effect_count; i++) snprintf(m->effects[i], SBFX_NAME_MAX, "%s", scene->effects[i].name);
    if (s->module_count == 0) sbfx_scene_camera_get(scene, &s->camera);
    sbfx_desc desc = {.scene = scene, .start_time = s->opt.start_time, .log = on_log, .log_user = (void *)name};
    r = sbfx_create(&desc, &m->fx);
    sbfx_scene_free(scene);
    if (r != SBFX_OK) {
        fprintf(stderr, "sbfx-soak: %s: sbfx_create: %s\n", name, sbfx_result_string(r));
        return -EIO;
    }
    s->pair_count += m->effect_count;
    return 0;
}

static int make_output(struct soak *s)
{
    glGenRenderbuffers(1, &s->out_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, s->out_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, s->opt.width, s->opt.height);
    glGenFramebuffers(1, &s->out_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, s->out_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s->out_rb);
    bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (complete && glGetError() == GL_NO_ERROR) return 0;
    fprintf(stderr, "sbfx-soak: the %dx%d output framebuffer is not complete\n", s->opt.width, s->opt.height);
    return -EIO;
}

static int open_csv(struct soak *s)
{
    char path[4096];
    mkdir(s->opt.out_dir, 0755);
    snprintf(path, sizeof(path), "%s/soak.csv", s->opt.out_dir);
    s->csv = fopen(path, "w");
    if (!s->csv) {
        fprintf(stderr, "sbfx-soak: cannot write %s: %s\n", path, strerror(errno));
        return -EIO;
    }
    soak_write_header(s->csv);
    return 0;
}

static int64_t total_frames(const struct soak_options *o) { return (int64_t)ceil(o->hours * 3600.0 / o->dt - 1e-9); }

static int setup(struct soak *s)
{
    char err[512];
    if (egl_headless_open(&s->egl, err, sizeof(err)) != 0) {
        fprintf(stderr, "sbfx-soak: %s\n", err);
        return -ENODEV;
    }
    if (test_scene_create(&s->host, s->opt.width, s->opt.height, err, sizeof(err)) != 0) {
        fprintf(stderr, "sbfx-soak: test scene: %s\n", err);
        return -EIO;
    }
    int rc = make_output(s);
    for (int i = 0; rc == 0 && i < s->opt.scene_count; i++, s->module_count++)
        rc = load_module(s, s->opt.scenes[i], &s->modules[i]);
    int64_t frames = total_frames(&s->opt);
    if (!s->opt.sample_every) s->opt.sample_every = (int)(frames / MAX_SAMPLES_DEFAULT > 0 ? frames / MAX_SAMPLES_DEFAULT : 1);
    s->sample_capacity = (int)(frames / s->opt.sample_every + 2);
    s->samples = calloc((size_t)s->sample_capacity, sizeof(*s->samples));
    if (rc == 0 && !s->samples) rc = -ENOMEM;
    return rc ? rc : open_csv(s);
}

static void teardown(struct soak *s)
{
    for (int i = 0; i < s->module_count; i++) sbfx_destroy(s->modules[i].fx);
    if (s->out_fbo) glDeleteFramebuffers(1, &s->out_fbo);
    if (s->out_rb) glDeleteRenderbuffers(1, &s->out_rb);
    if (s->host.framebuffer) test_scene_destroy(&s->host);
    egl_headless_close(&s->egl);
    if (s->csv) fclose(s->csv);
    free(s->samples);
}

/* ---- the loop ----------------------------------------------------------------------------- */

/* Schedules the triggers due in [t, t + dt) (seconds since create): trigger k goes to the k-th
 * (module, effect) pair, cycling, at a position that wanders over the ground. */
static int schedule_triggers(struct soak *s, double t, double dt)
{
    for (;;) {
        double at = (double)s->next_trigger * s->opt.trigger_every;
        if (at >= t + dt - 1e-9) return 0;
        int64_t k = s->next_trigger++;
        int pair = (int)(k % s->pair_count), mi = 0;
        while (pair >= s->modules[mi].effect_count) pair -= s->modules[mi++].effect_count;
        struct module *m = &s->modules[mi];
        float pos[3] = {(float)((k * 37) % 9 - 4) * 0.4f, 0.0f, (float)((k * 53) % 7 - 3) * 0.4f};
        sbfx_result r = sbfx_schedule(m->fx, m->effects[pair], at, pos);
        if (r != SBFX_OK) {
            fprintf(stderr, "sbfx-soak: %s: schedule %s: %s\n", m->name, m->effects[pair], sbfx_last_error(m->fx));
            return -EIO;
        }
    }
}

static int draw_frame(struct soak *s, double since_start)
{
    int w = s->opt.width, h = s->opt.height;
    sbfx_frame frame = {.scene_color_texture = s->host.color_texture, .scene_depth_texture = s->host.depth_texture,
                        .out_framebuffer = s->out_fbo, .width = w, .height = h};
    test_scene_camera(&s->camera, since_start, (float)w / (float)h, frame.view, frame.projection);
    if (test_scene_draw(&s->host, frame.view, frame.projection) != 0) {
        fprintf(stderr, "sbfx-soak: test scene: GL error at frame %lld\n", (long long)s->frames);
        return -EIO;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s->host.framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s->out_fbo);
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    for (int i = 0; i < s->module_count; i++) {
        sbfx_result r = sbfx_render(s->modules[i].fx, &frame);
        if (r != SBFX_OK) {
            fprintf(stderr, "sbfx-soak: %s: sbfx_render at frame %lld: %s\n", s->modules[i].name,
                    (long long)s->frames, sbfx_last_error(s->modules[i].fx));
            return -EIO;
        }
    }
    return 0;
}

/* Where the debug leak's last block is kept, overwritten each time (the compiler may not drop
 * the allocation; the earlier blocks are lost, which is the leak). */
static void *volatile leak_sink;

/* The debug leak of --inject-leak: a 64x64 RGBA8 texture, or 256 KiB of touched heap. */
static void inject_leak(struct soak *s)
{
    if (s->opt.leak == LEAK_NONE || s->frames % s->opt.leak_every) return;
    if (s->opt.leak == LEAK_TEXTURE) {
        GLuint t = 0;
        glGenTextures(1, &t);
        glBindTexture(GL_TEXTURE_2D, t);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 64, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        glBindTexture(GL_TEXTURE_2D, 0);
    } else {
        char *p = malloc(LEAK_BYTES);
        if (p) memset(p, 1, LEAK_BYTES);
        leak_sink = p;
    }
}

static int step(struct soak *s)
{
    double dt = s->opt.dt, t = (double)s->frames * dt;
    if (schedule_triggers(s, t, dt)) return -EIO;
    for (int i = 0; i < s->module_count; i++)
        if (sbfx_update(s->modules[i].fx, dt) != SBFX_OK) {
            fprintf(stderr, "sbfx-soak: %s: sbfx_update: %s\n", s->modules[i].name, sbfx_last_error(s->modules[i].fx));
            return -EIO;
        }
    s->frames++;
    if (s->frames % s->opt.render_every) return 0;
    int rc = draw_frame(s, (double)s->frames * dt);
    inject_leak(s);
    glFinish();
    return rc;
}

/* ---- samples ------------------------------------------------------------------------------ */

/* Resident memory from /proc/self/status: all of it, anonymous (heap, mappings, JIT code,
 * stacks) and file-backed (library code paged in: it grows when a code path runs first). */
static void read_rss(struct soak_sample *x)
{
    static const char *const keys[] = {"VmRSS:", "RssAnon:", "RssFile:"};
    int64_t *dst[] = {&x->rss_kib, &x->rss_anon_kib, &x->rss_file_kib};
    char line[256];
    FILE *f = fopen("/proc/self/status", "r");
    while (f && fgets(line, sizeof(line), f))
        for (int k = 0; k < 3; k++)
            if (!strncmp(line, keys[k], strlen(keys[k]))) *dst[k] = strtoll(line + strlen(keys[k]), NULL, 10);
    if (f) fclose(f);
}

/* GL objects alive in the whole context (sbfx's, the host's, a leak): Mesa hands out names
 * in increasing order, so every live one lies below a fresh name; glIs* is true for names
 * that were bound and not deleted. The fresh probe names are deleted unbound. */
static void count_gl_objects(struct soak_sample *x)
{
    GLuint t = 0, f = 0, b = 0;
    glGenTextures(1, &t);
    glGenFramebuffers(1, &f);
    glGenBuffers(1, &b);
    for (GLuint n = 1; n < t; n++) x->gl_textures += glIsTexture(n) ? 1 : 0;
    for (GLuint n = 1; n < f; n++) x->gl_framebuffers += glIsFramebuffer(n) ? 1 : 0;
    for (GLuint n = 1; n < b; n++) x->gl_buffers += glIsBuffer(n) ? 1 : 0;
    glDeleteTextures(1, &t);
    glDeleteFramebuffers(1, &f);
    glDeleteBuffers(1, &b);
}

/* malloc'ed bytes in use: small blocks in the arenas and large ones mapped on their own. */
static int64_t heap_bytes(void)
{
    struct mallinfo2 m = mallinfo2();
    return (int64_t)(m.uordblks + m.hblkhd);
}

static int take_sample(struct soak *s)
{
    if (glGetError() != GL_NO_ERROR) {
        fprintf(stderr, "sbfx-soak: a GL error by frame %lld\n", (long long)s->frames);
        return -EIO;
    }
    struct soak_sample *x = &s->samples[s->sample_count++];
    *x = (struct soak_sample){.frames = s->frames, .sim_seconds = sbfx_elapsed(s->modules[0].fx),
                              .wall_seconds = now_seconds() - s->wall_start,
                              .heap_bytes = heap_bytes()};
    read_rss(x);
    count_gl_objects(x);
    for (int i = 0; i < s->module_count; i++) {
        sbfx_counters c;
        sbfx_stats(s->modules[i].fx, &c);
        x->programs += c.programs, x->textures += c.textures, x->framebuffers += c.framebuffers;
        x->gpu_bytes += (int64_t)c.gpu_bytes, x->heap_allocs += (int64_t)c.heap_allocs_after_load;
        x->particles_alive += c.particles_alive, x->triggers_fired += c.triggers_fired;
        x->triggers_refused += c.triggers_refused;
    }
    soak_write_sample(s->csv, x);
    fflush(s->csv);
    return 0;
}

static void progress(const struct soak *s, int64_t total)
{
    const struct soak_sample *x = &s->samples[s->sample_count - 1];
    printf("sbfx-soak: %.2f of %.2f simulated hours, %lld frames, %.0f s, RSS %.1f MiB, %lld particles, "
           "%lld triggers (%lld refused)\n", x->sim_seconds / 3600.0, s->opt.hours, (long long)x->frames,
           x->wall_seconds, (double)x->rss_kib / 1024.0, (long long)x->particles_alive,
           (long long)x->triggers_fired, (long long)x->triggers_refused);
    fflush(stdout);
    (void)total;
}

static int run(struct soak *s)
{
    int64_t total = total_frames(&s->opt), tenth = total / 10 > 0 ? total / 10 : 1;
    s->wall_start = now_seconds();
    int rc = take_sample(s);
    while (rc == 0 && s->frames < total) {
        rc = step(s);
        bool sample = s->frames % s->opt.sample_every == 0 || s->frames == total;
        if (rc == 0 && sample && s->sample_count < s->sample_capacity) rc = take_sample(s);
        if (rc == 0 && !s->opt.quiet && s->frames % tenth == 0) progress(s, total);
    }
    return rc;
}

static int check(const struct soak *s)
{
    struct soak_limits lim;
    soak_limits_default(&lim);
    lim.warmup = s->opt.warmup;
    lim.rss_kib = s->opt.rss_tolerance_kib;
    lim.heap_bytes = s->opt.heap_tolerance_kib * 1024;
    lim.dt = s->opt.dt;
    lim.step = 1.0 / 120.0;
    char report[4096];
    int problems = soak_check(s->samples, s->sample_count, &lim, report, sizeof(report));
    const struct soak_sample *last = &s->samples[s->sample_count - 1];
    printf("sbfx-soak: %.2f simulated hours (%lld frames of %g s, %d modules, %dx%d) in %.1f s; %lld triggers "
           "fired, %lld refused; %d samples in %s/soak.csv\n", last->sim_seconds / 3600.0, (long long)last->frames,
           s->opt.dt, s->module_count, s->opt.width, s->opt.height, last->wall_seconds,
           (long long)last->triggers_fired, (long long)last->triggers_refused, s->sample_count, s->opt.out_dir);
    for (char *line = strtok(report, "\n"); line; line = strtok(NULL, "\n")) {
        if (line[0] == '#') printf("sbfx-soak: %s\n", line + 2);
        else fprintf(stderr, "sbfx-soak: not flat: %s\n", line);
    }
    if (problems == 0) printf("sbfx-soak: flat after warm-up\n");
    return problems ? 2 : 0;
}

int main(int argc, char **argv)
{
    struct soak s;
    memset(&s, 0, sizeof(s));
    if (parse_args(&s.opt, argc, argv)) return 1;
    int rc = setup(&s);
    if (rc == 0) rc = run(&s);
    int status = rc ? 1 : check(&s);
    teardown(&s);
    return status;
}
