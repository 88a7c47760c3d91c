/* sbfx-play: renders sbfx effects over the test scene, headless, into PNG frames.
 *
 * One frame: test scene -> its colour is copied into the output framebuffer (so an idle sbfx,
 * which issues no pass, still leaves the scene there) -> sbfx_update -> sbfx_render into the
 * output framebuffer -> glReadPixels -> PNG. The command line is in player_args.c. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "egl_headless.h"
#include "player_args.h"
#include "png_io.h"
#include "sbfx.h"
#include "test_scene.h"

#define CONTACT_CELL_WIDTH 240 /* a 960-wide frame shrinks by 4 */
#define TRIGGER_EPSILON 1e-9   /* frame times are i/fps: tolerate rounding at equality */

struct frame_times {
    double sbfx_sum, sbfx_max;   /* sbfx_update + sbfx_render + glFinish */
    double total_sum, total_max; /* the whole frame, readback and PNG included */
};

struct player {
    const struct player_options *opt;
    struct egl_headless egl;
    struct test_scene scene;
    GLuint out_framebuffer, out_renderbuffer;
    sbfx *fx;
    uint8_t *pixels;
    struct contact_sheet sheet;
    char out_dir[PATH_MAX];
    double sim_time;
    int frame_simulated;      /* particles advanced by this frame's updates, summed */
    sbfx_counters last;       /* sbfx_stats() after the last frame */
    struct frame_times times;
    int frames_done;
};

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static void on_sbfx_log(sbfx_log_level level, const char *message, void *user)
{
    const struct player_options *opt = user;
    static const char *const prefix[] = {"error", "warning", "info"};
    if (level == SBFX_LOG_INFO && opt->quiet) return;
    const char *name = (unsigned)level <= SBFX_LOG_INFO ? prefix[level] : "?";
    fprintf(stderr, "sbfx: %s: %s\n", name, message);
}

/* ---- setup -------------------------------------------------------------------------------- */

/* mkdir -p: every missing component of path, then a check that it is a directory. */
static int make_dirs(const char *path, char *err, size_t n)
{
    char buf[PATH_MAX];
    if (snprintf(buf, sizeof(buf), "%s", path) >= (int)sizeof(buf)) {
        snprintf(err, n, "--out: path too long: %s", path);
        return -ENAMETOOLONG;
    }
    for (char *p = buf + 1; *p; p++) {
        if (*p != '/') continue;
        *p = '\0';
        if (mkdir(buf, 0777) != 0 && errno != EEXIST) goto err_mkdir;
        *p = '/';
    }
    if (mkdir(buf, 0777) != 0 && errno != EEXIST) goto err_mkdir;
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode)) {
        snprintf(err, n, "--out: %s exists and is not a directory", path);
        return -ENOTDIR;
    }
    return 0;

err_mkdir: {
    int rc = -errno;
    snprintf(err, n, "--out: cannot create %.512s: %s", buf, strerror(errno));
    return rc;
}
}

/* A bad --stats path should fail before the run, not after minutes of rendering. */
static int check_writable(const char *path, char *err, size_t n)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        int rc = -errno;
        snprintf(err, n, "--stats: cannot create %s: %s", path, strerror(errno));
        return rc;
    }
    fclose(f);
    return 0;
}

/* --trigger entries go to the module's schedule: each fires at the first simulation step at
 * or after its time, so a run does not depend on --fps. The default timeline (one explosion at
 * t=0 at the origin) is the scene's own; --no-timeline turns it off (desc.ignore_timeline). */
static int schedule_triggers(struct player *p, char *err, size_t n)
{
    const struct player_options *opt = p->opt;
    for (int i = 0; i < opt->trigger_count; i++) {
        const struct player_trigger *t = &opt->triggers[i];
        sbfx_result r = sbfx_schedule(p->fx, t->effect, t->seconds, t->position);
        if (r != SBFX_OK) {
            snprintf(err, n, "--trigger %s@%g: %s: %s", t->effect, t->seconds, sbfx_result_string(r),
                     sbfx_last_error(p->fx));
            return -EINVAL;
        }
    }
    return 0;
}

static int create_output(struct player *p, char *err, size_t n)
{
    int w = p->opt->width, h = p->opt->height;
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
    if (w > max_size || h > max_size) {
        snprintf(err, n, "--size: %dx%d is larger than this GL allows (%d)", w, h, max_size);
        return -EINVAL;
    }
    glGenRenderbuffers(1, &p->out_renderbuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, p->out_renderbuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glGenFramebuffers(1, &p->out_framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, p->out_framebuffer);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              p->out_renderbuffer);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    GLenum gl_err = glGetError();
    if (status != GL_FRAMEBUFFER_COMPLETE || gl_err != GL_NO_ERROR) {
        snprintf(err, n, "output framebuffer %dx%d RGBA8: status 0x%x, GL error 0x%x", w, h,
                 status, gl_err);
        return gl_err == GL_OUT_OF_MEMORY ? -ENOMEM : -EIO;
    }
    return 0;
}

static int load_scene(const char *path, sbfx_scene **scene, char *err, size_t n)
{
    *scene = NULL;
    if (!path) return 0; /* the library's built-in explosion */
    char why[512];
    if (sbfx_scene_load(path, scene, why, sizeof(why)) != SBFX_OK) {
        snprintf(err, n, "--scene %s", why);
        return -EINVAL;
    }
    return 0;
}

static int create_fx(struct player *p, char *err, size_t n)
{
    const struct player_options *opt = p->opt;
    sbfx_scene *scene = NULL;
    int rc = load_scene(opt->scene_path, &scene, err, n);
    if (rc) return rc;
    const sbfx_desc desc = {
        .target_divisor = opt->scale,
        .target_format = opt->format,
        .upsample = opt->upsample,
        .opacity = opt->opacity,
        .seed = opt->seed,
        .scene = scene,
        .ignore_timeline = opt->no_timeline,
        .log = on_sbfx_log,
        .log_user = (void *)opt,
    };
    sbfx_result r = sbfx_create(&desc, &p->fx);
    sbfx_scene_free(scene); /* the module keeps what it needs */
    if (r != SBFX_OK) { /* the reason went through the log callback */
        snprintf(err, n, "sbfx_create failed: %s", sbfx_result_string(r));
        return -EIO;
    }
    return schedule_triggers(p, err, n);
}

static int setup(struct player *p, char *err, size_t n)
{
    const struct player_options *opt = p->opt;
    int rc = make_dirs(opt->out_dir, err, n);
    if (rc) return rc;
    if (!realpath(opt->out_dir, p->out_dir)) {
        rc = -errno;
        snprintf(err, n, "--out: %s: %s", opt->out_dir, strerror(errno));
        return rc;
    }
    if (opt->stats_path && (rc = check_writable(opt->stats_path, err, n)) != 0) return rc;
    if ((rc = egl_headless_open(&p->egl, err, n)) != 0) return rc;
    if ((rc = test_scene_create(&p->scene, opt->width, opt->height, err, n)) != 0) return rc;
    if ((rc = create_output(p, err, n)) != 0) return rc;
    if ((rc = create_fx(p, err, n)) != 0) return rc;
    p->pixels = malloc((size_t)opt->width * opt->height * 4);
    if (!p->pixels) {
        snprintf(err, n, "out of memory for a %dx%d frame", opt->width, opt->height);
        return -ENOMEM;
    }
    if (opt->contact_sheet)
        rc = contact_sheet_init(&p->sheet, opt->frames, opt->width, opt->height,
                                CONTACT_CELL_WIDTH, err, n);
    return rc;
}

/* Undoes whatever part of setup() happened: every member starts zeroed. */
static void teardown(struct player *p)
{
    contact_sheet_free(&p->sheet);
    free(p->pixels);
    if (p->fx) sbfx_destroy(p->fx);
    if (p->egl.display != EGL_NO_DISPLAY) {
        glDeleteFramebuffers(1, &p->out_framebuffer);
        glDeleteRenderbuffers(1, &p->out_renderbuffer);
        test_scene_destroy(&p->scene);
    }
    egl_headless_close(&p->egl);
}

/* ---- simulation ----------------------------------------------------------------------- */

static int update(struct player *p, double dt, char *err, size_t n)
{
    if (dt <= 0.0) return 0;
    sbfx_result r = sbfx_update(p->fx, dt);
    if (r != SBFX_OK) {
        snprintf(err, n, "sbfx_update(%g) at t=%.4f s: %s: %s", dt, p->sim_time,
                 sbfx_result_string(r), sbfx_last_error(p->fx));
        return -EIO;
    }
    sbfx_counters c;
    sbfx_stats(p->fx, &c);
    p->frame_simulated += c.particles_simulated;
    p->sim_time += dt;
    return 0;
}

static int advance(struct player *p, double target, char *err, size_t n)
{
    p->frame_simulated = 0;
    return update(p, target - p->sim_time, err, n);
}

/* ---- one frame ------------------------------------------------------------------------ */

static int gl_check(const char *what, char *err, size_t n)
{
    GLenum e = glGetError(), first = e;
    while (e != GL_NO_ERROR) e = glGetError(); /* drain, so the next check starts clean */
    if (first == GL_NO_ERROR) return 0;
    snprintf(err, n, "%s: GL error 0x%x", what, first);
    return first == GL_OUT_OF_MEMORY ? -ENOMEM : -EIO;
}

static int draw_scene(struct player *p, double t, sbfx_frame *frame, char *err, size_t n)
{
    int w = p->opt->width, h = p->opt->height;
    test_scene_orbit_camera(t, (float)w / (float)h, frame->view, frame->projection);
    if (test_scene_draw(&p->scene, frame->view, frame->projection) != 0) {
        snprintf(err, n, "test scene: GL error while drawing");
        return -EIO;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, p->scene.framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, p->out_framebuffer);
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    frame->scene_color_texture = p->scene.color_texture;
    frame->scene_depth_texture = p->scene.depth_texture;
    frame->out_framebuffer = p->out_framebuffer;
    frame->width = w;
    frame->height = h;
    glFinish(); /* so the timed part below holds sbfx's GPU work only */
    return gl_check("scene copy to the output framebuffer", err, n);
}

static int run_fx(struct player *p, double t, const sbfx_frame *frame, char *err, size_t n)
{
    int rc = advance(p, t, err, n);
    if (rc) return rc;
    sbfx_result r = sbfx_render(p->fx, frame);
    if (r != SBFX_OK) {
        snprintf(err, n, "sbfx_render at t=%.4f s: %s: %s", t, sbfx_result_string(r),
                 sbfx_last_error(p->fx));
        return -EIO;
    }
    glFinish();
    return 0;
}

static int save_frame(struct player *p, int index, char *err, size_t n)
{
    int w = p->opt->width, h = p->opt->height;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, p->out_framebuffer);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, p->pixels);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    int rc = gl_check("glReadPixels of the output framebuffer", err, n);
    if (rc) return rc;
    /* A display has no alpha; written as is, viewers would show whatever the composite left
     * in alpha as transparency. */
    for (size_t i = 3; i < (size_t)w * h * 4; i += 4) p->pixels[i] = 255;
    char path[PATH_MAX + 32];
    snprintf(path, sizeof(path), "%s/frame-%04d.png", p->out_dir, index);
    rc = png_write_rgba(path, p->pixels, w, h, true, err, n);
    if (rc == 0 && p->opt->contact_sheet) rc = contact_sheet_add(&p->sheet, p->pixels, true);
    return rc;
}

static void record_times(struct frame_times *t, double sbfx_ms, double total_ms)
{
    t->sbfx_sum += sbfx_ms;
    t->total_sum += total_ms;
    if (sbfx_ms > t->sbfx_max) t->sbfx_max = sbfx_ms;
    if (total_ms > t->total_max) t->total_max = total_ms;
}

static int play_frame(struct player *p, int index, char *err, size_t n)
{
    double t = index / p->opt->fps;
    sbfx_frame frame;
    memset(&frame, 0, sizeof(frame));
    double start = now_ms();
    int rc = draw_scene(p, t, &frame, err, n);
    if (rc) return rc;
    double fx_start = now_ms();
    rc = run_fx(p, t, &frame, err, n);
    if (rc) return rc;
    double fx_end = now_ms();
    sbfx_stats(p->fx, &p->last);
    rc = save_frame(p, index, err, n);
    if (rc) return rc;
    record_times(&p->times, fx_end - fx_start, now_ms() - start);
    return 0;
}

/* ---- results -------------------------------------------------------------------------- */

static int write_stats(const struct player *p, const char *path, char *err, size_t n)
{
    const sbfx_counters *c = &p->last;
    FILE *f = fopen(path, "w");
    if (!f) {
        int rc = -errno;
        snprintf(err, n, "--stats: cannot create %s: %s", path, strerror(errno));
        return rc;
    }
    fprintf(f,
            "{\"programs\": %d, \"textures\": %d, \"framebuffers\": %d, \"gpu_bytes\": %zu, "
            "\"passes\": %d, \"draw_calls\": %d, \"particles_simulated\": %d, "
            "\"heap_allocs_after_load\": %llu}\n",
            c->programs, c->textures, c->framebuffers, c->gpu_bytes, c->passes, c->draw_calls,
            p->frame_simulated, (unsigned long long)c->heap_allocs_after_load);
    bool failed = ferror(f) != 0;
    if (fclose(f) != 0 || failed) {
        snprintf(err, n, "--stats: writing %s failed: %s", path, strerror(errno));
        return -EIO;
    }
    return 0;
}

static const char *format_name(sbfx_target_format format)
{
    static const char *const names[] = {"not reported", "RGBA8", "RGBA16F", "RGBA32F"};
    return (unsigned)format < SBFX_FORMAT_COUNT ? names[format] : "?";
}

static int finish(struct player *p, char *err, size_t n)
{
    int rc = 0;
    char sheet_path[PATH_MAX + 32];
    snprintf(sheet_path, sizeof(sheet_path), "%s/contact-sheet.png", p->out_dir);
    if (p->opt->contact_sheet && (rc = contact_sheet_write(&p->sheet, sheet_path, err, n)) != 0)
        return rc;
    if (p->opt->stats_path && (rc = write_stats(p, p->opt->stats_path, err, n)) != 0) return rc;
    if (p->opt->quiet) return 0;
    const struct frame_times *t = &p->times;
    int frames = p->frames_done;
    printf("sbfx-play: %d frames of %dx%d in %s (frame-0000.png .. frame-%04d.png)\n", frames,
           p->opt->width, p->opt->height, p->out_dir, frames - 1);
    if (p->opt->contact_sheet) printf("sbfx-play: contact sheet: %s\n", sheet_path);
    printf("sbfx-play: sbfx update+render+glFinish: mean %.2f ms, max %.2f ms per frame "
           "(particle target %s)\n", t->sbfx_sum / frames, t->sbfx_max,
           format_name(p->last.target_format));
    printf("sbfx-play: whole frame (scene, sbfx, readback, PNG): mean %.2f ms, max %.2f ms\n",
           t->total_sum / frames, t->total_max);
    return 0;
}

static void print_banner(const struct player *p)
{
    printf("sbfx-play: %s, %s, EGL %s; %dx%d, %d frames at %g fps\n",
           (const char *)glGetString(GL_RENDERER), (const char *)glGetString(GL_VERSION),
           p->egl.platform, p->opt->width, p->opt->height, p->opt->frames, p->opt->fps);
}

static int play(const struct player_options *opt)
{
    static struct player player; /* large (PATH_MAX, trigger table): off the stack */
    struct player *p = &player;
    memset(p, 0, sizeof(*p));
    p->opt = opt;
    char err[1024] = "";
    int rc = setup(p, err, sizeof(err));
    if (rc) {
        fprintf(stderr, "sbfx-play: %s\n", err);
        goto out;
    }
    if (!opt->quiet) print_banner(p);
    for (int i = 0; i < opt->frames; i++) {
        rc = play_frame(p, i, err, sizeof(err));
        if (rc) {
            fprintf(stderr, "sbfx-play: frame %d: %s\n", i, err);
            goto out;
        }
        p->frames_done++;
    }
    rc = finish(p, err, sizeof(err));
    if (rc) fprintf(stderr, "sbfx-play: %s\n", err);
out:
    teardown(p);
    return rc;
}

int main(int argc, char **argv)
{
    static struct player_options opt; /* the trigger table is large: off the stack */
    char err[512] = "";
    player_options_defaults(&opt);
    if (player_parse_args(&opt, argc, argv, err, sizeof(err)) != 0) {
        fprintf(stderr, "sbfx-play: %s\n", err);
        return 1;
    }
    if (opt.help) {
        player_usage(stdout);
        return 0;
    }
    return play(&opt) == 0 ? 0 : 1;
}
