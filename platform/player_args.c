/* sbfx-play's command line: one table of flags, one parser per kind of value. Every error
 * names the flag and what it accepts; nothing here exits or prints. */
#include "player_args.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))

static const char usage_text[] =
    "Usage: sbfx-play [options]\n"
    "Renders sbfx effects (by default one explosion) over a test scene - a checkered ground\n"
    "and three boxes seen from a slowly orbiting camera - and writes every frame as a PNG.\n"
    "\n"
    "Display:\n"
    "  --headless             render offscreen through EGL surfaceless (Mesa); the default\n"
    "                         and, in this build, the only display\n"
    "Output:\n"
    "  --size WxH             output size in pixels, 16..16384 each (default 960x540)\n"
    "  --frames N             number of frames, 1..1000000 (default 36)\n"
    "  --fps F                frames per simulated second: each frame advances the\n"
    "                         simulation by 1/F seconds, 0 < F <= 1000 (default 12)\n"
    "  --out DIR              folder for frame-0000.png, frame-0001.png, ...; created if\n"
    "                         missing (default sbfx-frames)\n"
    "  --contact-sheet        also write DIR/contact-sheet.png: all frames, shrunk, in a grid\n"
    "  --stats FILE           after the run, write one JSON object with the counters of\n"
    "                         sbfx_stats() after the last frame: programs, textures,\n"
    "                         framebuffers, gpu_bytes, passes, draw_calls,\n"
    "                         particles_simulated, heap_allocs_after_load (passes,\n"
    "                         draw_calls and particles_simulated are the last frame's)\n"
    "  --quiet                print only warnings and errors\n"
    "Effects:\n"
    "  --trigger EFFECT@SECONDS[:X,Y,Z]\n"
    "                         start EFFECT (an effect of the scene; built in: explosion)\n"
    "                         at simulated time SECONDS, at world position X,Y,Z (default\n"
    "                         0,0,0);\n"
    "                         repeatable, up to 64; e.g. --trigger explosion@1.5:2,0,-1\n"
    "  --no-timeline          ignore the scene's timeline (without --scene: one explosion\n"
    "                         at t=0 at the origin): the run stays idle unless --trigger\n"
    "                         is given\n"
    "  --scene FILE           a scene file (see scenes/ and README \"Scene files\"): its\n"
    "                         render settings, lights, media, effects and timeline; the\n"
    "                         quality flags below override its render settings\n"
    "  --seed N               random seed of spawns and detail windows, 0..4294967295\n"
    "                         (0 = the library's default, 1)\n"
    "Quality:\n"
    "  --scale 1|2|4|8        particle target = output size / scale per axis (default 4)\n"
    "  --opacity planar|soft|spherical|exact\n"
    "                         opacity model of a particle (default spherical)\n"
    "  --format auto|rgba8|rgba16f|rgba32f\n"
    "                         particle target format (auto: RGBA16F where it is\n"
    "                         colour-renderable, else RGBA8)\n"
    "  --upsample bilinear|nearest-depth\n"
    "                         upsampling of the particle target (default nearest-depth)\n"
    "  --help                 print this text and exit\n"
    "\n"
    "Values go after a space or an '=' (--size 640x360, --size=640x360).\n"
    "Timeline: frame i shows simulated time i/F. Frame 0 is rendered before any update, so\n"
    "it shows the scene alone (effects start at the first simulation step); before frame\n"
    "i > 0 the simulation advances by 1/F in fixed steps, and triggers fire at the first\n"
    "step at or after their time, so results do not depend on F. Per frame: test scene,\n"
    "sbfx_update, sbfx_render into an RGBA8\n"
    "framebuffer, glReadPixels, PNG (alpha written as 255: a display has none). At the end\n"
    "the folder, the contact sheet and the time per frame (sbfx update+render+glFinish, and\n"
    "the whole frame) are printed.\n"
    "Mesa's variables work as usual, e.g. GALLIUM_DRIVER=softpipe, LIBGL_ALWAYS_SOFTWARE=1, and\n"
    "MESA_EXTENSION_OVERRIDE='-GL_EXT_color_buffer_half_float -GL_EXT_color_buffer_float'\n"
    "(hides half-float render targets: the particle target falls back to RGBA8).\n"
    "Exit status: 0 on success; 1 on a bad argument or a failure, with a message on stderr.\n";

void player_usage(FILE *f)
{
    fputs(usage_text, f);
}

void player_options_defaults(struct player_options *opt)
{
    memset(opt, 0, sizeof(*opt));
    opt->width = 960;
    opt->height = 540;
    opt->frames = 36;
    opt->fps = 12.0;
    opt->out_dir = "sbfx-frames";
}

/* ---- value parsers: true when the whole string is a valid value in range ------------------ */

static bool parse_integer(const char *s, long long min, long long max, long long *out)
{
    if (!s || !*s || isspace((unsigned char)*s)) return false;
    char *end = NULL;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (errno || *end != '\0' || v < min || v > max) return false;
    *out = v;
    return true;
}

/* A finite number ending at one of the characters in `stops` (or at the end of s). */
static bool parse_number(const char *s, const char *stops, double *out, const char **rest)
{
    if (!s || !*s || isspace((unsigned char)*s)) return false;
    char *end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || errno == ERANGE || !isfinite(v)) return false;
    if (*end != '\0' && (!stops || !strchr(stops, *end))) return false;
    *out = v;
    if (rest) *rest = end;
    return true;
}

struct choice {
    const char *name;
    int value;
};

static int parse_choice(const char *flag, const char *value, const struct choice *choices,
                        size_t count, int *out, char *err, size_t n)
{
    for (size_t i = 0; i < count; i++)
        if (strcmp(value, choices[i].name) == 0) {
            *out = choices[i].value;
            return 0;
        }
    char list[160] = "";
    for (size_t i = 0; i < count; i++) {
        if (i) strncat(list, "|", sizeof(list) - strlen(list) - 1);
        strncat(list, choices[i].name, sizeof(list) - strlen(list) - 1);
    }
    snprintf(err, n, "%s: expected one of %s, got '%s'", flag, list, value);
    return -EINVAL;
}

/* ---- one handler per flag ------------------------------------------------------------- */

static int set_size(struct player_options *opt, const char *value, char *err, size_t n)
{
    char w[32], h[32];
    const char *x = strpbrk(value, "xX");
    long long width = 0, height = 0;
    size_t wlen = x ? (size_t)(x - value) : 0;
    if (x && wlen < sizeof(w) && strlen(x + 1) < sizeof(h)) {
        memcpy(w, value, wlen);
        w[wlen] = '\0';
        strcpy(h, x + 1);
        if (parse_integer(w, PLAYER_MIN_SIZE, PLAYER_MAX_SIZE, &width) &&
            parse_integer(h, PLAYER_MIN_SIZE, PLAYER_MAX_SIZE, &height)) {
            opt->width = (int)width;
            opt->height = (int)height;
            return 0;
        }
    }
    snprintf(err, n, "--size: expected WxH with W and H in %d..%d (e.g. 960x540), got '%s'",
             PLAYER_MIN_SIZE, PLAYER_MAX_SIZE, value);
    return -EINVAL;
}

static int set_frames(struct player_options *opt, const char *value, char *err, size_t n)
{
    long long v = 0;
    if (!parse_integer(value, 1, PLAYER_MAX_FRAMES, &v)) {
        snprintf(err, n, "--frames: expected a whole number in 1..%d, got '%s'",
                 PLAYER_MAX_FRAMES, value);
        return -EINVAL;
    }
    opt->frames = (int)v;
    return 0;
}

static int set_fps(struct player_options *opt, const char *value, char *err, size_t n)
{
    double v = 0;
    if (!parse_number(value, NULL, &v, NULL) || !(v > 0.0) || v > 1000.0) {
        snprintf(err, n, "--fps: expected a number F with 0 < F <= 1000 (e.g. 12 or 29.97), "
                 "got '%s'", value);
        return -EINVAL;
    }
    opt->fps = v;
    return 0;
}

static int set_path(const char *flag, const char **dst, const char *value, char *err, size_t n)
{
    if (!*value) {
        snprintf(err, n, "%s: expected a path, got an empty string", flag);
        return -EINVAL;
    }
    *dst = value;
    return 0;
}

static int set_out(struct player_options *opt, const char *value, char *err, size_t n)
{
    return set_path("--out", &opt->out_dir, value, err, n);
}

static int set_stats(struct player_options *opt, const char *value, char *err, size_t n)
{
    return set_path("--stats", &opt->stats_path, value, err, n);
}

static int set_scene(struct player_options *opt, const char *value, char *err, size_t n)
{
    return set_path("--scene", &opt->scene_path, value, err, n);
}

static int set_trigger(struct player_options *opt, const char *value, char *err, size_t n)
{
    if (opt->trigger_count >= PLAYER_MAX_TRIGGERS) {
        snprintf(err, n, "--trigger: at most %d triggers, '%s' is one too many",
                 PLAYER_MAX_TRIGGERS, value);
        return -EINVAL;
    }
    int rc = player_parse_trigger(value, &opt->triggers[opt->trigger_count], err, n);
    if (rc == 0) opt->trigger_count++;
    return rc;
}

static int set_scale(struct player_options *opt, const char *value, char *err, size_t n)
{
    static const struct choice choices[] = {{"1", 1}, {"2", 2}, {"4", 4}, {"8", 8}};
    return parse_choice("--scale", value, choices, ARRAY_SIZE(choices), &opt->scale, err, n);
}

static int set_opacity(struct player_options *opt, const char *value, char *err, size_t n)
{
    static const struct choice choices[] = {
        {"planar", SBFX_OPACITY_PLANAR}, {"soft", SBFX_OPACITY_SOFT},
        {"spherical", SBFX_OPACITY_SPHERICAL}, {"exact", SBFX_OPACITY_EXACT},
    };
    int v = 0;
    int rc = parse_choice("--opacity", value, choices, ARRAY_SIZE(choices), &v, err, n);
    opt->opacity = (sbfx_opacity_mode)v;
    return rc;
}

static int set_format(struct player_options *opt, const char *value, char *err, size_t n)
{
    static const struct choice choices[] = {
        {"auto", SBFX_FORMAT_DEFAULT}, {"rgba8", SBFX_FORMAT_RGBA8},
        {"rgba16f", SBFX_FORMAT_RGBA16F}, {"rgba32f", SBFX_FORMAT_RGBA32F},
    };
    int v = 0;
    int rc = parse_choice("--format", value, choices, ARRAY_SIZE(choices), &v, err, n);
    opt->format = (sbfx_target_format)v;
    return rc;
}

static int set_upsample(struct player_options *opt, const char *value, char *err, size_t n)
{
    static const struct choice choices[] = {
        {"bilinear", SBFX_UPSAMPLE_BILINEAR}, {"nearest-depth", SBFX_UPSAMPLE_NEAREST_DEPTH},
    };
    int v = 0;
    int rc = parse_choice("--upsample", value, choices, ARRAY_SIZE(choices), &v, err, n);
    opt->upsample = (sbfx_upsample)v;
    return rc;
}

static int set_seed(struct player_options *opt, const char *value, char *err, size_t n)
{
    long long v = 0;
    if (!parse_integer(value, 0, UINT32_MAX, &v)) {
        snprintf(err, n, "--seed: expected a whole number in 0..4294967295, got '%s'", value);
        return -EINVAL;
    }
    opt->seed = (uint32_t)v;
    return 0;
}

static int set_headless(struct player_options *opt, const char *value, char *err, size_t n)
{
    return 0; /* the only display of this build, and the default */
}

static int set_contact_sheet(struct player_options *opt, const char *value, char *err, size_t n)
{
    opt->contact_sheet = true;
    return 0;
}

static int set_no_timeline(struct player_options *opt, const char *value, char *err, size_t n)
{
    opt->no_timeline = true;
    return 0;
}

static int set_quiet(struct player_options *opt, const char *value, char *err, size_t n)
{
    opt->quiet = true;
    return 0;
}

static int set_help(struct player_options *opt, const char *value, char *err, size_t n)
{
    opt->help = true;
    return 0;
}

/* ---- the table ------------------------------------------------------------------------ */

struct flag {
    const char *name;
    const char *value; /* what the value looks like, for "needs a value" errors; NULL: switch */
    int (*apply)(struct player_options *opt, const char *value, char *err, size_t n);
};

static const struct flag flags[] = {
    {"--headless", NULL, set_headless},
    {"--size", "WxH (e.g. 960x540)", set_size},
    {"--frames", "N (1..1000000)", set_frames},
    {"--fps", "F (0 < F <= 1000)", set_fps},
    {"--out", "DIR", set_out},
    {"--contact-sheet", NULL, set_contact_sheet},
    {"--stats", "FILE", set_stats},
    {"--trigger", "EFFECT@SECONDS[:X,Y,Z]", set_trigger},
    {"--no-timeline", NULL, set_no_timeline},
    {"--scale", "1|2|4|8", set_scale},
    {"--opacity", "planar|soft|spherical|exact", set_opacity},
    {"--format", "auto|rgba8|rgba16f|rgba32f", set_format},
    {"--upsample", "bilinear|nearest-depth", set_upsample},
    {"--seed", "N (0..4294967295)", set_seed},
    {"--scene", "FILE", set_scene},
    {"--quiet", NULL, set_quiet},
    {"--help", NULL, set_help},
};

static const struct flag *find_flag(const char *arg, size_t len)
{
    if (len == 2 && strncmp(arg, "-h", 2) == 0) return &flags[ARRAY_SIZE(flags) - 1];
    for (size_t i = 0; i < ARRAY_SIZE(flags); i++)
        if (strlen(flags[i].name) == len && strncmp(arg, flags[i].name, len) == 0)
            return &flags[i];
    return NULL;
}

/* Finds the value of flag f at argv[*i]: after '=' in the same word, else the next word. */
static int flag_value(const struct flag *f, const char *eq, int argc, char **argv, int *i,
                      const char **value, char *err, size_t n)
{
    *value = NULL;
    if (!f->value) {
        if (!eq) return 0;
        snprintf(err, n, "%s takes no value, got '%s'", f->name, argv[*i]);
        return -EINVAL;
    }
    if (eq) {
        *value = eq + 1;
    } else if (*i + 1 < argc && strncmp(argv[*i + 1], "--", 2) != 0) {
        *value = argv[++*i]; /* a following "--flag" is a forgotten value, not a value */
    } else {
        snprintf(err, n, "%s needs a value: %s %s", f->name, f->name, f->value);
        return -EINVAL;
    }
    return 0;
}

int player_parse_args(struct player_options *opt, int argc, char **argv, char *err, size_t n)
{
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        const char *eq = strchr(arg, '=');
        size_t len = eq ? (size_t)(eq - arg) : strlen(arg);
        const struct flag *f = arg[0] == '-' ? find_flag(arg, len) : NULL;
        if (!f) {
            snprintf(err, n, "%s '%.*s' (see sbfx-play --help for the flags)",
                     arg[0] == '-' ? "unknown flag" : "unexpected argument", (int)len, arg);
            return -EINVAL;
        }
        const char *value = NULL;
        int rc = flag_value(f, eq, argc, argv, &i, &value, err, n);
        if (rc == 0) rc = f->apply(opt, value, err, n);
        if (rc) return rc;
        if (opt->help) return 0;
    }
    return 0;
}

/* ---- --trigger EFFECT@SECONDS[:X,Y,Z] --------------------------------------------------- */

static bool valid_effect_name(const char *name, size_t len)
{
    if (len == 0 || len >= PLAYER_EFFECT_NAME_MAX) return false;
    for (size_t i = 0; i < len; i++) {
        unsigned char c = (unsigned char)name[i];
        if (!isalnum(c) && c != '_' && c != '-' && c != '.') return false;
    }
    return true;
}

static bool parse_position(const char *s, float position[3])
{
    for (int k = 0; k < 3; k++) {
        double v = 0;
        const char *rest = NULL;
        if (!parse_number(s, k < 2 ? "," : NULL, &v, &rest)) return false;
        if ((k < 2) != (*rest == ',')) return false;
        position[k] = (float)v;
        s = rest + (k < 2);
    }
    return true;
}

static int trigger_error(const char *text, const char *why, char *err, size_t n)
{
    snprintf(err, n, "--trigger: expected EFFECT@SECONDS[:X,Y,Z] (e.g. explosion@0.5 or "
             "explosion@1.5:2,0,-1), got '%s': %s", text, why);
    return -EINVAL;
}

int player_parse_trigger(const char *text, struct player_trigger *out, char *err, size_t n)
{
    const char *at = strchr(text, '@');
    if (!at) return trigger_error(text, "no '@'", err, n);
    size_t name_len = (size_t)(at - text);
    if (!valid_effect_name(text, name_len))
        return trigger_error(text, "the effect name must be 1..63 of A-Z a-z 0-9 _ - .", err, n);
    struct player_trigger t = {.position = {0, 0, 0}};
    memcpy(t.effect, text, name_len);
    t.effect[name_len] = '\0';
    const char *rest = NULL;
    if (!parse_number(at + 1, ":", &t.seconds, &rest) || t.seconds < 0.0 || t.seconds > 1e6)
        return trigger_error(text, "SECONDS must be a number in 0..1e6", err, n);
    if (*rest == ':' && !parse_position(rest + 1, t.position))
        return trigger_error(text, "the position must be three finite numbers X,Y,Z", err, n);
    *out = t;
    return 0;
}
