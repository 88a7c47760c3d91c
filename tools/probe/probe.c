/* sbfx-probe: answers one line per query line, CPU reference next to a real GPU render.
 *   opacity MODE D R ZC ZS NEAR TAU  ->  CPU GPU
 *     the opaque surface at ZS reaches the GPU as a host depth buffer holds it: reversed-Z
 *     float depth (infinite far, GL_EXT_clip_control's ZERO_TO_ONE) where the context offers
 *     the extension, else standard float depth; stderr says which at start
 *   blackbody T                      ->  R G B (Planck x CIE in double)  R G B (GPU)
 *   phase COS G                      ->  CPU GPU   (COS = 1: light goes straight on)
 * The GPU columns of blackbody and phase are particle.frag's own functions on tables sized for
 * what is asked: a black-body table over at least 500..20000 K (wider if T is outside), a phase
 * table made for G (or the analytic function where a table would miss 1e-3, as in sbfx). Both
 * are normalised as sbfx normalises them (luminance 1 at 6000 K; 1 over the sphere).
 * A malformed line gets a message on stderr naming its line number; later lines are still
 * answered; the exit status is then 1. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "egl/egl_headless.h"
#include "host/host_depth.h"
#include "internal.h"
#include "reference.h"

typedef struct probe {
    sbfx *by_mode[SBFX_OPACITY_COUNT];
    sbfx *tables;                  /* black body and phase, remade for what is asked */
    double lo_kelvin, hi_kelvin, g;
    GLuint depth_texture, out_texture, out_fbo;
    sbfx_cmf cmf;
    bool have_cmf;
    int line;
    bool failed;
    bool reversed_z;   /* host depth in reversed-Z float (GL_EXT_clip_control is offered) */
} probe;

#define PROBE_LO_KELVIN 500.0
#define PROBE_HI_KELVIN 20000.0

static const char *const mode_names[SBFX_OPACITY_COUNT] = {
    [SBFX_OPACITY_PLANAR] = "planar", [SBFX_OPACITY_SOFT] = "soft",
    [SBFX_OPACITY_SPHERICAL] = "spherical", [SBFX_OPACITY_EXACT] = "exact"};

static void complain(probe *p, const char *fmt, const char *detail)
{
    fprintf(stderr, "sbfx-probe: line %d: ", p->line);
    fprintf(stderr, fmt, detail);
    fputc('\n', stderr);
    p->failed = true;
}

static void log_to_stderr(sbfx_log_level level, const char *message, void *user)
{
    (void)user;
    fprintf(stderr, "sbfx-probe: %s: %s\n", level == SBFX_LOG_ERROR ? "error" : "warning", message);
}

/* One module per opacity mode (the mode is a load-time specialisation), 1x1, full resolution,
 * float target, made on first use. */
static sbfx *module_for(probe *p, sbfx_opacity_mode mode)
{
    if (p->by_mode[mode]) return p->by_mode[mode];
    sbfx_desc desc = {.target_divisor = 1, .target_format = SBFX_FORMAT_RGBA32F, .opacity = mode,
                      .max_particles = 16, .log = log_to_stderr};
    if (sbfx_create(&desc, &p->by_mode[mode]) != SBFX_OK) return NULL;
    return p->by_mode[mode];
}

static int parse_doubles(const char *text, double *out, int count)
{
    for (int i = 0; i < count; i++) {
        char *end;
        errno = 0;
        out[i] = strtod(text, &end);
        if (end == text || errno == ERANGE) return -1;
        text = end;
    }
    while (*text == ' ' || *text == '\t' || *text == '\r' || *text == '\n') text++;
    return *text ? -1 : 0;
}

/* The host's projection: reversed-Z with no far plane, or (without clip control) a standard
 * one far enough to hold the sphere (an opaque surface beyond it reads as the far clear value,
 * which clips nothing either) and not further: standard float depth would lose the near/far
 * ratio. */
static void host_projection(const probe *p, const double v[6], sbfx_frame *frame)
{
    double d = v[0], r = v[1], zc = v[2], zs = v[3], near = v[4];
    double far = 4.0 * fmax(fmax(fabs(zc) + fabs(r), near), fmin(zs, 1e30));
    if (zs > 2.0 * (fabs(zc) + fabs(r))) far = 4.0 * fmax(fabs(zc) + fabs(r), near);
    sbfx_perspective(frame->projection, 1.5707963f, 1.0f, (float)near, p->reversed_z ? INFINITY : (float)far);
    if (p->reversed_z) sbfx_reverse_z(frame->projection, (float)near, INFINITY);
    frame->clip_depth_mode = p->reversed_z ? SBFX_CLIP_DEPTH_ZERO_TO_ONE : SBFX_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE;
    frame->projection[0] = frame->projection[5] = 1.0f;
    frame->projection[8] = (float)(d / zc); /* the single pixel's ray passes at D in the centre plane */
}

static double gpu_opacity(probe *p, sbfx *fx, const double v[6])
{
    double r = v[1], zc = v[2], zs = v[3], tau = v[5];
    sbfx_frame frame = {.scene_depth_texture = p->depth_texture, .out_framebuffer = p->out_fbo,
                        .width = 1, .height = 1};
    host_projection(p, v, &frame);
    frame.view[0] = frame.view[5] = frame.view[10] = frame.view[15] = 1.0f;
    float depth = sbfx_window_depth(&frame, zs); /* what the host's depth buffer holds */
    glBindTexture(GL_TEXTURE_2D, p->depth_texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, 1, 1, 0, GL_DEPTH_COMPONENT, GL_FLOAT, &depth);
    sbfx_media(fx)[SBFX_SMOKE].tau = (float)tau;
    sbfx_media(fx)[SBFX_SMOKE].detail_strength = 0.0f;
    sbfx_view_particle particle = {.center = {0.0f, 0.0f, (float)-zc}, .radius = (float)r,
                                   .intensity = 1.0f, .medium = SBFX_SMOKE};
    if (sbfx_render_view_particles(fx, &frame, &particle, 1) != SBFX_OK) return NAN;
    sbfx_counters c;
    sbfx_stats(fx, &c);
    if (c.passes == 0) return 0.0; /* the particle was skipped: it adds nothing */
    float rgba[4];
    int w, h;
    if (sbfx_read_particle_target(fx, rgba, 4, &w, &h) != SBFX_OK) return NAN;
    return 1.0 - rgba[3];
}

static void answer_opacity(probe *p, const char *args)
{
    char mode_name[32];
    int used = 0;
    double v[6];
    if (sscanf(args, "%31s%n", mode_name, &used) != 1) return complain(p, "%s", "opacity needs MODE D R ZC ZS NEAR TAU");
    sbfx_opacity_mode mode = SBFX_OPACITY_DEFAULT;
    for (int m = 1; m < SBFX_OPACITY_COUNT; m++)
        if (mode_names[m] && strcmp(mode_name, mode_names[m]) == 0) mode = (sbfx_opacity_mode)m;
    if (!mode) return complain(p, "unknown opacity mode \"%s\" (planar, soft, spherical, exact)", mode_name);
    if (parse_doubles(args + used, v, 6) != 0)
        return complain(p, "%s", "opacity needs MODE D R ZC ZS NEAR TAU (numbers)");
    if (v[2] == 0.0 || !(v[4] > 0.0))
        return complain(p, "%s", "ZC must not be 0 and NEAR must be > 0");
    sbfx *fx = module_for(p, mode);
    if (!fx) return complain(p, "%s", "cannot create the module (see the message above)");
    sbfx_ref_particle particle = {{0.0, 0.0, -v[2]}, v[1], v[5]};
    sbfx_ref_pixel pixel = {{v[0] / v[2], 0.0, -1.0}, v[3], v[4], 0.0};
    double cpu = sbfx_ref_opacity(mode, &particle, &pixel);
    printf("%.9g %.9g\n", cpu, gpu_opacity(p, fx, v));
}

/* A module whose fire reaches [lo, hi] and whose smoke scatters with g: the built-in scene's
 * media set so sbfx's own range rule (tables.c) gives a table over that range, then reloaded. */
static sbfx *tables_for(probe *p, double lo, double hi, double g)
{
    if (p->tables && lo >= p->lo_kelvin && hi <= p->hi_kelvin && g == p->g) return p->tables;
    lo = fmin(lo, p->tables ? p->lo_kelvin : lo), hi = fmax(hi, p->tables ? p->hi_kelvin : hi);
    if (!p->tables) {
        sbfx_desc desc = {.target_divisor = 1, .max_particles = 16, .ignore_timeline = true, .log = log_to_stderr};
        if (sbfx_create(&desc, &p->tables) != SBFX_OK) return NULL;
    }
    sbfx_medium_params *m = sbfx_media(p->tables);
    m[SBFX_FIRE].t0 = (float)lo;
    m[SBFX_FIRE].t1 = (float)(hi / SBFX_BLACKBODY_MARGIN - lo);
    m[SBFX_FIRE].cooling = 0.0f;
    m[SBFX_SMOKE].phase_g = (float)g;
    p->lo_kelvin = lo, p->hi_kelvin = hi, p->g = g;
    if (sbfx_reload(p->tables) != SBFX_OK) {
        sbfx_destroy(p->tables);
        p->tables = NULL;
    }
    return p->tables;
}

static void answer_blackbody(probe *p, const char *args)
{
    double t;
    if (parse_doubles(args, &t, 1) != 0 || !(t >= 0.0) || !(t <= 1e7))
        return complain(p, "%s", "blackbody needs T, kelvin from 0 to 1e7");
    char err[256];
    if (!p->have_cmf && sbfx_cmf_load(SBFX_CMF_DEFAULT_PATH, &p->cmf, err, sizeof(err)) != SBFX_OK)
        return complain(p, "%s", err);
    p->have_cmf = true;
    sbfx *fx = tables_for(p, fmin(PROBE_LO_KELVIN, t), fmax(PROBE_HI_KELVIN, t), p->tables ? p->g : 0.0);
    if (!fx) return complain(p, "%s", "cannot create the module (see the message above)");
    double cpu[3] = {0.0, 0.0, 0.0};
    if (t > 0.0) sbfx_blackbody_rgb(&p->cmf, t, sbfx_blackbody_norm(&p->cmf, SBFX_DEFAULT_MAX_KELVIN), cpu);
    float gpu[3], phase;
    if (sbfx_fetch_luts(fx, SBFX_SMOKE, (float)t, 0.0f, gpu, &phase) != SBFX_OK)
        return complain(p, "%s", "GPU table fetch failed (see the message above)");
    printf("%.9g %.9g %.9g %.9g %.9g %.9g\n", cpu[0], cpu[1], cpu[2], gpu[0], gpu[1], gpu[2]);
}

static void answer_phase(probe *p, const char *args)
{
    double v[2];
    if (parse_doubles(args, v, 2) != 0) return complain(p, "%s", "phase needs COS G");
    if (!(fabs(v[0]) <= 1.0) || !(fabs(v[1]) <= SBFX_PHASE_G_MAX))
        return complain(p, "%s", "phase needs -1 <= COS <= 1 and -0.99 <= G <= 0.99");
    sbfx *fx = tables_for(p, p->tables ? p->lo_kelvin : PROBE_LO_KELVIN, p->tables ? p->hi_kelvin : PROBE_HI_KELVIN,
                          (double)(float)v[1]);
    if (!fx) return complain(p, "%s", "cannot create the module (see the message above)");
    float rgb[3], gpu;
    if (sbfx_fetch_luts(fx, SBFX_SMOKE, 0.0f, (float)v[0], rgb, &gpu) != SBFX_OK)
        return complain(p, "%s", "GPU table fetch failed (see the message above)");
    printf("%.9g %.9g\n", sbfx_phase(v[0], (double)(float)v[1]), gpu);
}

static void answer(probe *p, char *line)
{
    char verb[32];
    int used = 0;
    if (sscanf(line, "%31s%n", verb, &used) != 1) return; /* blank lines are ignored */
    if (verb[0] == '#') return;
    const char *args = line + used;
    if (strcmp(verb, "opacity") == 0) answer_opacity(p, args);
    else if (strcmp(verb, "blackbody") == 0) answer_blackbody(p, args);
    else if (strcmp(verb, "phase") == 0) answer_phase(p, args);
    else complain(p, "unknown query \"%s\" (opacity, blackbody, phase)", verb);
    fflush(stdout);
}

static int create_host_objects(probe *p)
{
    glGenTextures(1, &p->depth_texture);
    glGenTextures(1, &p->out_texture);
    glBindTexture(GL_TEXTURE_2D, p->out_texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glGenFramebuffers(1, &p->out_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, p->out_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, p->out_texture, 0);
    bool ok = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return ok ? 0 : -1;
}

static void usage(FILE *to)
{
    fprintf(to, "usage: sbfx-probe < queries\n"
                "  opacity MODE D R ZC ZS NEAR TAU   -> CPU GPU (MODE: planar soft spherical exact)\n"
                "  blackbody T                       -> R G B R G B (Planck x CIE in double, GPU)\n"
                "  phase COS G                       -> CPU GPU\n");
}

int main(int argc, char **argv)
{
    if (argc > 1) {
        bool help = strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0;
        usage(help ? stdout : stderr);
        return help ? 0 : 1;
    }
    struct egl_headless egl;
    char err[512];
    if (egl_headless_open(&egl, err, sizeof(err)) != 0) {
        fprintf(stderr, "sbfx-probe: %s\n", err);
        return 1;
    }
    probe p = {0};
    p.reversed_z = host_depth_has_clip_control();
    fprintf(stderr, "sbfx-probe: host depth: %s\n",
            p.reversed_z ? "reversed-Z float (GL_EXT_clip_control ZERO_TO_ONE, infinite far)"
                         : "standard float (GL_EXT_clip_control missing)");
    if (create_host_objects(&p) != 0) {
        fprintf(stderr, "sbfx-probe: cannot create a 1x1 RGBA8 framebuffer\n");
        egl_headless_close(&egl);
        return 1;
    }
    char line[1024];
    while (fgets(line, sizeof(line), stdin)) {
        p.line++;
        answer(&p, line);
    }
    for (int m = 0; m < SBFX_OPACITY_COUNT; m++) sbfx_destroy(p.by_mode[m]);
    sbfx_destroy(p.tables);
    glDeleteFramebuffers(1, &p.out_fbo);
    GLuint textures[] = {p.depth_texture, p.out_texture};
    glDeleteTextures(2, textures);
    egl_headless_close(&egl);
    return p.failed ? 1 : 0;
}
