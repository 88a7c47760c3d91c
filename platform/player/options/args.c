/* sbfx-play's command line: one table of flags, one parser per kind of value. Every error
 * names the flag and what it accepts; nothing here exits or prints. */
#include "player/options/options.h"

#include "gpio/effect_at.h" /* EFFECT[@X,Y,Z] */
#include "net/common/net_address.h" /* --dis, --mqtt */
#include "drm/drm_mode_spec.h"
#include "player/options/board.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))

void player_options_defaults(struct player_options *opt)
{
    memset(opt, 0, sizeof(*opt));
    opt->width = 960;
    opt->height = 540;
    opt->frames = 36;
    opt->fps = 12.0;
    opt->out_dir = "sbfx-frames";
    opt->modeset = -1;
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
            opt->size_set = true;
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
    opt->frames_set = true;
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
    opt->fps_set = true;
    return 0;
}

static int set_start_time(struct player_options *opt, const char *value, char *err, size_t n)
{
    double v = 0;
    if (!parse_number(value, NULL, &v, NULL) || !(v >= 0.0) || v > PLAYER_MAX_START_TIME) {
        snprintf(err, n, "--start-time: expected seconds from 0 to 1e10 (e.g. 31536000 for a year), "
                 "got '%s'", value);
        return -EINVAL;
    }
    opt->start_time = v;
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
    opt->out_set = true;
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

static int set_watch(struct player_options *opt, const char *value, char *err, size_t n)
{
    opt->watch = true;
    return 0;
}

static int set_loop(struct player_options *opt, const char *value, char *err, size_t n)
{
    double v = 0;
    if (!parse_number(value, NULL, &v, NULL) || !(v >= 0.1) || v > 1e6) {
        snprintf(err, n, "--loop: expected a period in seconds from 0.1 to 1e6 (e.g. 3), got '%s'", value);
        return -EINVAL;
    }
    opt->loop_seconds = v;
    return 0;
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
        {"mixed", SBFX_UPSAMPLE_MIXED},
    };
    int v = 0;
    int rc = parse_choice("--upsample", value, choices, ARRAY_SIZE(choices), &v, err, n);
    opt->upsample = (sbfx_upsample)v;
    return rc;
}

static int set_tone_map(struct player_options *opt, const char *value, char *err, size_t n)
{
    static const struct choice choices[] = {
        {"none", SBFX_TONE_MAP_NONE}, {"hue-preserving", SBFX_TONE_MAP_HUE_PRESERVING},
        {"per-channel", SBFX_TONE_MAP_PER_CHANNEL}, {"filmic", SBFX_TONE_MAP_FILMIC},
    };
    int v = 0;
    int rc = parse_choice("--tone-map", value, choices, ARRAY_SIZE(choices), &v, err, n);
    opt->tone_map = (sbfx_tone_map)v;
    return rc;
}

static int set_early_termination(struct player_options *opt, const char *value, char *err, size_t n)
{
    static const struct choice choices[] = {{"on", 1}, {"off", -1}};
    int v = 0;
    int rc = parse_choice("--early-termination", value, choices, ARRAY_SIZE(choices), &v, err, n);
    opt->early_termination = v;
    return rc;
}

static int set_exposure(struct player_options *opt, const char *value, char *err, size_t n)
{
    double v = 0;
    if (!parse_number(value, NULL, &v, NULL) || !(v >= 0.01) || v > 100.0) {
        snprintf(err, n, "--exposure: expected a scale from 0.01 to 100 (e.g. 1 or 0.5), got '%s'", value);
        return -EINVAL;
    }
    opt->exposure = (float)v;
    return 0;
}

static int set_budget(struct player_options *opt, const char *value, char *err, size_t n)
{
    double v = 0;
    if (!parse_number(value, NULL, &v, NULL) || !(v > 0.0) || v > 10000.0) {
        snprintf(err, n, "--budget-ms: expected a frame time in milliseconds above 0 and at most 10000 "
                 "(e.g. 16.7), got '%s'", value);
        return -EINVAL;
    }
    opt->budget_ms = (float)v;
    return 0;
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
    opt->headless_flag = true; /* the default display */
    return 0;
}

static int set_display(struct player_options *opt, const char *value, char *err, size_t n)
{
    static const struct choice choices[] = {
        {"drm", PLAYER_DISPLAY_DRM}, {"headless", PLAYER_DISPLAY_HEADLESS},
        {"wayland", PLAYER_DISPLAY_WAYLAND}, {"auto", PLAYER_DISPLAY_AUTO},
    };
    int v = 0;
    int rc = parse_choice("--display", value, choices, ARRAY_SIZE(choices), &v, err, n);
    opt->display_auto = v == PLAYER_DISPLAY_AUTO;
    /* auto: a Wayland session's variable says a compositor runs; without one, the kiosk owns
     * the screen through DRM/KMS */
    const char *wayland = getenv("WAYLAND_DISPLAY");
    if (opt->display_auto) v = wayland && *wayland ? PLAYER_DISPLAY_WAYLAND : PLAYER_DISPLAY_DRM;
    opt->display = (enum player_display)v;
    opt->display_set = true;
    return rc;
}

bool player_on_screen(const struct player_options *opt)
{
    return opt->display != PLAYER_DISPLAY_HEADLESS;
}

static int set_device(struct player_options *opt, const char *value, char *err, size_t n)
{
    return set_path("--device", &opt->device, value, err, n);
}

static int set_connector(struct player_options *opt, const char *value, char *err, size_t n)
{
    if (*value && strlen(value) < 32 && !strpbrk(value, " \t/")) {
        opt->connector = value;
        return 0;
    }
    snprintf(err, n, "--connector: expected a connector name such as HDMI-A-1 or DSI-1, got '%s'", value);
    return -EINVAL;
}

static int set_mode(struct player_options *opt, const char *value, char *err, size_t n)
{
    int w, h, hz;
    if (mode_spec_parse(value, &w, &h, &hz) == 0) {
        opt->mode = value;
        return 0;
    }
    snprintf(err, n, "--mode: expected WxH or WxH@HZ (e.g. 1920x1080 or 1280x720@60), got '%s'", value);
    return -EINVAL;
}

static int set_modeset(struct player_options *opt, const char *value, char *err, size_t n)
{
    static const struct choice choices[] = {
        {"auto", MODESET_AUTO}, {"atomic", MODESET_ATOMIC}, {"legacy", MODESET_LEGACY},
    };
    return parse_choice("--modeset", value, choices, ARRAY_SIZE(choices), &opt->modeset, err, n);
}

static int set_screenshot(struct player_options *opt, const char *value, char *err, size_t n)
{
    return set_path("--screenshot", &opt->screenshot, value, err, n);
}

static int set_board(struct player_options *opt, const char *value, char *err, size_t n)
{
    return set_path("--board", &opt->board_path, value, err, n);
}

static int set_video(struct player_options *opt, const char *value, char *err, size_t n)
{
    return set_path("--video", &opt->video, value, err, n);
}

static int set_gpio(struct player_options *opt, const char *value, char *err, size_t n)
{
    if (opt->gpio_count >= PLAYER_MAX_GPIO) {
        snprintf(err, n, "--gpio: at most %d lines, '%s' is one too many", PLAYER_MAX_GPIO, value);
        return -EINVAL;
    }
    int rc = player_parse_gpio(value, &opt->gpio[opt->gpio_count], err, n);
    if (rc == 0) opt->gpio_count++;
    return rc;
}

/* --dis [ADDR:]PORT, --mqtt HOST[:PORT]: the syntax now, the network at setup (inputs/dis_source.c, inputs/mqtt_source.c) */
static int set_dis(struct player_options *opt, const char *value, char *err, size_t n)
{
    struct udp_endpoint e;
    char why[256];
    if (udp_endpoint_parse(value, &e, why, sizeof(why)) == 0) return set_path("--dis", &opt->dis, value, err, n);
    snprintf(err, n, "--dis: %s", why);
    return -EINVAL;
}

static int set_dis_exercise(struct player_options *opt, const char *value, char *err, size_t n)
{
    long long v = 0;
    if (!parse_integer(value, 1, 255, &v)) {
        snprintf(err, n, "--dis-exercise: expected an exercise ID 1..255, got '%s'", value);
        return -EINVAL;
    }
    opt->dis_exercise = (int)v;
    return 0;
}

static int set_mqtt(struct player_options *opt, const char *value, char *err, size_t n)
{
    char host[256], why[256];
    int port = 0;
    if (mqtt_endpoint_parse(value, host, sizeof(host), &port, why, sizeof(why)) == 0)
        return set_path("--mqtt", &opt->mqtt, value, err, n);
    snprintf(err, n, "--mqtt: %s", why);
    return -EINVAL;
}

static int set_mqtt_topic(struct player_options *opt, const char *value, char *err, size_t n)
{
    if (!*value || strlen(value) > 255) {
        snprintf(err, n, "--mqtt-topic: expected a topic of 1..255 bytes (e.g. sbfx/trigger), got '%s'", value);
        return -EINVAL;
    }
    opt->mqtt_topic = value;
    return 0;
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

static int set_version(struct player_options *opt, const char *value, char *err, size_t n)
{
    opt->version = true;
    return 0;
}

/* ---- the table ------------------------------------------------------------------------ */

struct flag {
    const char *name;
    const char *value; /* what the value looks like, for "needs a value" errors; NULL: switch */
    int (*apply)(struct player_options *opt, const char *value, char *err, size_t n);
};

static int set_world_time(struct player_options *opt, const char *value, char *err, size_t n)
{
    double v = 0;
    if (!parse_number(value, NULL, &v, NULL) || !(v >= 0.0) || v > PLAYER_MAX_WORLD_TIME) {
        snprintf(err, n, "--world-time: expected seconds from 0 to 1e10 (the first frame's world time, e.g. 2 "
                 "or 1764300000), got '%s'", value);
        return -EINVAL;
    }
    opt->world_time = v;
    opt->world_time_set = true;
    return 0;
}

static int set_world_clock(struct player_options *opt, const char *value, char *err, size_t n)
{
    static const struct choice choices[] = {{"frames", PLAYER_CLOCK_FRAMES}, {"system", PLAYER_CLOCK_SYSTEM},
                                            {"cigi", PLAYER_CLOCK_CIGI}, {"dis", PLAYER_CLOCK_DIS}};
    int v = 0;
    int rc = parse_choice("--world-clock", value, choices, ARRAY_SIZE(choices), &v, err, n);
    if (rc == 0) opt->world_clock = (enum player_world_clock)v;
    return rc;
}

static int set_frustum(struct player_options *opt, const char *value, char *err, size_t n)
{
    const char *why = player_parse_frustum(value, &opt->channel);
    if (why) snprintf(err, n, "--frustum: expected LEFT,RIGHT,BOTTOM,TOP in degrees from the view axis (e.g. "
                      "-30,-10,-15,15), got '%s': %s", value, why);
    return why ? -EINVAL : 0;
}

static int set_view_offset(struct player_options *opt, const char *value, char *err, size_t n)
{
    const char *why = player_parse_view_offset(value, &opt->channel);
    if (why) snprintf(err, n, "--view-offset: expected YAW,PITCH,ROLL in degrees (e.g. -40,0,0), got '%s': %s",
                      value, why);
    return why ? -EINVAL : 0;
}

static int set_follow(struct player_options *opt, const char *value, char *err, size_t n)
{
    unsigned v[3];
    char tail;
    if (sscanf(value, "%u:%u:%u%c", &v[0], &v[1], &v[2], &tail) != 3 || v[0] > 65535 || v[1] > 65535 ||
        v[2] > 65535 || strchr(value, '-') || strchr(value, '+') || strchr(value, ' ')) {
        snprintf(err, n, "--follow: expected SITE:APP:ENTITY, each 0..65535 (a DIS entity ID, e.g. 1:3:101), got '%s'",
                 value);
        return -EINVAL;
    }
    for (int k = 0; k < 3; k++) opt->follow[k] = (uint16_t)v[k];
    opt->follow_set = true;
    return 0;
}

static int set_cigi(struct player_options *opt, const char *value, char *err, size_t n)
{
    (void)err, (void)n; /* checked with the socket's address rules when it opens */
    opt->cigi = value;
    return 0;
}

static int set_cigi_host(struct player_options *opt, const char *value, char *err, size_t n)
{
    (void)err, (void)n;
    opt->cigi_host = value;
    return 0;
}

static const struct flag flags[] = {
    {"--headless", NULL, set_headless},
    {"--display", "headless|drm|wayland|auto", set_display},
    {"--device", "PATH (e.g. /dev/dri/card0)", set_device},
    {"--connector", "NAME (e.g. HDMI-A-1)", set_connector},
    {"--mode", "WxH[@HZ] (e.g. 1920x1080@60)", set_mode},
    {"--modeset", "auto|atomic|legacy", set_modeset},
    {"--screenshot", "FILE", set_screenshot},
    {"--board", "FILE", set_board},
    {"--video", "DEV (e.g. /dev/video0)", set_video},
    {"--gpio", "CHIP:LINE=EFFECT[@X,Y,Z]", set_gpio},
    {"--dis", "[ADDR:]PORT (e.g. 3000 or 239.1.2.3:3000)", set_dis},
    {"--dis-exercise", "N (1..255)", set_dis_exercise},
    {"--mqtt", "HOST[:PORT] (e.g. broker.local:1883)", set_mqtt},
    {"--mqtt-topic", "TOPIC (e.g. sbfx/trigger)", set_mqtt_topic},
    {"--size", "WxH (e.g. 960x540)", set_size},
    {"--frames", "N (1..1000000)", set_frames},
    {"--fps", "F (0 < F <= 1000)", set_fps},
    {"--start-time", "SECONDS (0..1e10)", set_start_time},
    {"--out", "DIR", set_out},
    {"--contact-sheet", NULL, set_contact_sheet},
    {"--stats", "FILE", set_stats},
    {"--trigger", "EFFECT@SECONDS[:X,Y,Z][#ID]", set_trigger},
    {"--world-time", "SECONDS (0..1e10)", set_world_time},
    {"--world-clock", "frames|system|cigi|dis", set_world_clock},
    {"--frustum", "LEFT,RIGHT,BOTTOM,TOP (degrees)", set_frustum},
    {"--view-offset", "YAW,PITCH,ROLL (degrees)", set_view_offset},
    {"--follow", "SITE:APP:ENTITY (a DIS entity)", set_follow},
    {"--cigi", "[ADDR:]PORT (e.g. 8004 or 239.1.2.3:8004)", set_cigi},
    {"--cigi-host", "ADDR:PORT (where Start of Frame goes)", set_cigi_host},
    {"--no-timeline", NULL, set_no_timeline},
    {"--scale", "1|2|4|8", set_scale},
    {"--opacity", "planar|soft|spherical|exact", set_opacity},
    {"--format", "auto|rgba8|rgba16f|rgba32f", set_format},
    {"--upsample", "bilinear|nearest-depth|mixed", set_upsample},
    {"--tone-map", "none|hue-preserving|per-channel|filmic", set_tone_map},
    {"--exposure", "X (0.01..100)", set_exposure},
    {"--early-termination", "on|off", set_early_termination},
    {"--budget-ms", "MS (0 < MS <= 10000)", set_budget},
    {"--seed", "N (0..4294967295)", set_seed},
    {"--scene", "FILE", set_scene},
    {"--watch", NULL, set_watch},
    {"--loop", "SECONDS (0.1..1e6)", set_loop},
    {"--quiet", NULL, set_quiet},
    {"--version", NULL, set_version},
    {"--help", NULL, set_help}, /* last: -h finds it there */
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

static int parse_flags(struct player_options *opt, int argc, char **argv, char *err, size_t n);

static const char *display_name(enum player_display display)
{
    return display == PLAYER_DISPLAY_DRM ? "drm" : display == PLAYER_DISPLAY_WAYLAND ? "wayland" : "headless";
}

/* Flags that only mean something on one display. --size also sets a Wayland window's size
 * where the compositor leaves it to the client (full screen refused). */
static int check_display(const struct player_options *opt, char *err, size_t n)
{
    bool drm = opt->display == PLAYER_DISPLAY_DRM, screen = player_on_screen(opt);
    const char *wrong = NULL;
    if (screen && opt->headless_flag) wrong = "--headless";
    else if (drm && opt->size_set) wrong = "--size";
    else if (screen && opt->out_set) wrong = "--out";
    else if (screen && opt->contact_sheet) wrong = "--contact-sheet";
    if (wrong && drm) {
        snprintf(err, n, "%s applies to --display headless, not drm (drm: the mode sets the size; "
                 "--screenshot saves a frame)", wrong);
        return -EINVAL;
    }
    if (wrong) {
        snprintf(err, n, "%s applies to --display headless, not wayland%s (wayland: the compositor "
                 "sets the window's size)", wrong, opt->display_auto ? " (auto chose it: WAYLAND_DISPLAY is set)" : "");
        return -EINVAL;
    }
    if (!drm && opt->device) wrong = "--device";
    else if (!drm && opt->connector) wrong = "--connector";
    else if (!drm && opt->mode) wrong = "--mode";
    else if (!drm && opt->modeset >= 0) wrong = "--modeset";
    else if (!drm && opt->screenshot) wrong = "--screenshot";
    if (wrong) {
        snprintf(err, n, "%s applies to --display drm (the display is %s%s)", wrong, display_name(opt->display),
                 opt->display_auto ? ": auto chose it, WAYLAND_DISPLAY is set" : "");
        return -EINVAL;
    }
    return 0;
}

int player_board_display(struct player_options *opt, const char *backend, char *err, size_t n)
{
    if (opt->display_set || opt->headless_flag || !backend[0]) return 0;
    int rc = set_display(opt, backend, err, n);
    return rc ? rc : check_display(opt, err, n);
}

int player_parse_args(struct player_options *opt, int argc, char **argv, char *err, size_t n)
{
    int rc = parse_flags(opt, argc, argv, err, n);
    if (rc || opt->help || opt->version) return rc;
    if (opt->watch && !opt->scene_path) {
        snprintf(err, n, "--watch reloads the scene file: give it with --scene FILE");
        return -EINVAL;
    }
    return check_display(opt, err, n);
}

static int parse_flags(struct player_options *opt, int argc, char **argv, char *err, size_t n)
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
        if (opt->help || opt->version) return 0;
    }
    return 0;
}

/* ---- --trigger EFFECT@SECONDS[:X,Y,Z][#ID] ----------------------------------------------- */

static int trigger_error(const char *text, const char *why, char *err, size_t n)
{
    snprintf(err, n, "--trigger: expected EFFECT@SECONDS[:X,Y,Z][#ID] (e.g. explosion@0.5, "
             "explosion@1.5:2,0,-1 or explosion@1.5:2,0,-1#17), got '%s': %s", text, why);
    return -EINVAL;
}

/* "#ID" at the end: 1..2^63-1, decimal; the text before it goes on to be parsed in `head`. */
static const char *trigger_id(const char *text, char *head, size_t size, uint64_t *id)
{
    const char *hash = strrchr(text, '#');
    *id = 0;
    size_t len = hash ? (size_t)(hash - text) : strlen(text);
    if (len >= size) return "too long";
    memcpy(head, text, len);
    head[len] = '\0';
    if (!hash) return NULL;
    const char *digits = hash + 1;
    char *end = NULL;
    errno = 0;
    unsigned long long v = strtoull(digits, &end, 10);
    if (!*digits || !isdigit((unsigned char)*digits) || *end || errno || v == 0 || v > (unsigned long long)INT64_MAX)
        return "ID must be a whole number in 1..9223372036854775807";
    *id = v;
    return NULL;
}

int player_parse_trigger(const char *full, struct player_trigger *out, char *err, size_t n)
{
    char text[256];
    uint64_t id = 0;
    const char *why = trigger_id(full, text, sizeof(text), &id);
    if (why) return trigger_error(full, why, err, n);
    const char *at = strchr(text, '@');
    if (!at) return trigger_error(full, "no '@'", err, n);
    size_t name_len = (size_t)(at - text);
    if (!effect_name_valid(text, name_len))
        return trigger_error(full, "the effect name must be 1..63 of A-Z a-z 0-9 _ - .", err, n);
    struct player_trigger t = {.position = {0, 0, 0}};
    memcpy(t.effect, text, name_len);
    t.effect[name_len] = '\0';
    const char *rest = NULL;
    if (!parse_number(at + 1, ":", &t.seconds, &rest) || t.seconds < 0.0 || t.seconds > 1e6)
        return trigger_error(full, "SECONDS must be a number in 0..1e6", err, n);
    if (*rest == ':' && !effect_position_parse(rest + 1, t.position))
        return trigger_error(full, "the position must be three finite numbers X,Y,Z", err, n);
    t.id = id;
    *out = t;
    return 0;
}

/* ---- --gpio CHIP:LINE=EFFECT[@X,Y,Z] ------------------------------------------------------ */

static int gpio_error(const char *text, const char *why, char *err, size_t n)
{
    snprintf(err, n, "--gpio: expected CHIP:LINE=EFFECT[@X,Y,Z] (e.g. gpiochip0:17=explosion or "
             "gpiochip0:17=explosion@0,0,-1), got '%s': %s", text, why);
    return -EINVAL;
}

int player_parse_gpio(const char *text, struct player_gpio *out, char *err, size_t n)
{
    const char *eq = strchr(text, '=');
    if (!eq) return gpio_error(text, "no '='", err, n);
    const char *colon = NULL;
    for (const char *p = text; p < eq; p++)
        if (*p == ':') colon = p; /* the last one: chip labels may hold ':' */
    if (!colon || colon == text) return gpio_error(text, "no CHIP: before the line number", err, n);
    struct player_gpio g = {.position = {0, 0, 0}};
    size_t chip_len = (size_t)(colon - text);
    if (chip_len >= sizeof(g.chip)) return gpio_error(text, "the chip name is too long", err, n);
    memcpy(g.chip, text, chip_len);
    char line[16];
    size_t line_len = (size_t)(eq - colon - 1);
    long long v = -1;
    if (line_len < sizeof(line)) {
        memcpy(line, colon + 1, line_len);
        line[line_len] = '\0';
    }
    if (line_len >= sizeof(line) || !parse_integer(line, 0, 65535, &v))
        return gpio_error(text, "LINE must be a whole number in 0..65535", err, n);
    g.line = (int)v;
    const char *why = effect_at_parse(eq + 1, strlen(eq + 1), g.effect, g.position);
    if (why) return gpio_error(text, why, err, n);
    *out = g;
    return 0;
}
