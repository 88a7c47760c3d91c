/* Command line of sbfx-play. The flag names are a contract relied on from outside (scripts,
 * CI, docs): change them only together with docs/player.md, the man page
 * (sbfx-play.1) and tests/cli.sh. */
#ifndef SBFX_PLAYER_ARGS_H
#define SBFX_PLAYER_ARGS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sbfx.h"

#define PLAYER_MAX_TRIGGERS 64
#define PLAYER_EFFECT_NAME_MAX 64
#define PLAYER_MIN_SIZE 16    /* a 1/8 particle target stays at least 2 pixels wide */
#define PLAYER_MAX_SIZE 16384 /* the run also checks the GL limits */
#define PLAYER_MAX_FRAMES 1000000
#define PLAYER_MAX_GPIO 32
#define PLAYER_MAX_START_TIME 1e10 /* desc.start_time's range: about 317 years */

/* --trigger EFFECT@SECONDS[:X,Y,Z][#ID] */
struct player_trigger {
    char effect[PLAYER_EFFECT_NAME_MAX];
    double seconds;
    float position[3];
    uint64_t id;              /* #ID: 1..2^63-1, the instance's identity; 0: none (the order) */
};

#define PLAYER_MAX_WORLD_TIME 1e10

/* Where the world clock comes from (docs/simulators.md): none (the player's own frame count),
 * the system clock (kept in step by PTP or NTP), CIGI's IG Control timestamps, or DIS PDUs'
 * absolute timestamps (the seconds past the hour; the hour from the system clock). */
enum player_world_clock { PLAYER_CLOCK_FRAMES, PLAYER_CLOCK_SYSTEM, PLAYER_CLOCK_CIGI, PLAYER_CLOCK_DIS };

/* A channel: one display's slice of the eyepoint's view (--frustum, --view-offset, the board's
 * view group, CIGI's View Definition and View Control). Degrees. */
struct player_channel {
    bool have_frustum;
    float frustum[4];         /* left, right, bottom, top: angles from the view axis, left and
                                 bottom negative */
    bool have_offset;
    float offset[3];          /* yaw (right +), pitch (up +), roll (right +) from the eyepoint */
};

/* --gpio CHIP:LINE=EFFECT[@X,Y,Z] (rising edges; the board or scene may say otherwise) */
struct player_gpio {
    char chip[64];
    int line;
    char effect[PLAYER_EFFECT_NAME_MAX];
    float position[3];
};

enum player_display { PLAYER_DISPLAY_HEADLESS, PLAYER_DISPLAY_DRM, PLAYER_DISPLAY_WAYLAND };
/* --display auto: resolved while parsing (player_parse_args) */
#define PLAYER_DISPLAY_AUTO (-1)

struct player_options {
    int width, height;
    int frames;
    double fps;
    const char *out_dir;
    bool contact_sheet;
    const char *stats_path;   /* NULL: no stats file */
    struct player_trigger triggers[PLAYER_MAX_TRIGGERS];
    int trigger_count;        /* from --trigger, in command-line order */
    bool no_timeline;
    int scale;                /* desc.target_divisor; 0 = the library's default (4) */
    sbfx_opacity_mode opacity;
    sbfx_target_format format;
    sbfx_upsample upsample;
    sbfx_tone_map tone_map;   /* 0 = the scene's or the library's default */
    int early_termination;    /* --early-termination: 0 the scene's (on by default), 1 on, -1 off */
    float exposure;           /* 0 = the scene's or the library's default (1) */
    uint32_t seed;            /* 0 = the library's default */
    double start_time;        /* --start-time: desc.start_time, the clock's start (0) */
    float budget_ms;          /* --budget-ms: desc.frame_budget_ms; 0 = the scene's or none */
    const char *scene_path;   /* NULL: the built-in timeline */
    bool watch;               /* --watch: reload the scene file (and its includes) on change */
    double loop_seconds;      /* --loop: replay the timeline every SECONDS (0: never) */
    bool quiet;
    bool help;
    bool version;             /* --version */
    /* display and devices (docs/kiosk-and-devices.md) */
    enum player_display display;
    bool headless_flag;       /* --headless was given */
    bool display_set;         /* --display was given */
    bool display_auto;        /* it was auto: wayland where WAYLAND_DISPLAY is set, else drm */
    bool size_set, frames_set, fps_set, out_set;
    const char *device;       /* --device: DRM card */
    const char *connector;
    const char *mode;         /* WxH or WxH@HZ */
    int modeset;              /* enum modeset_kind; -1: not given */
    const char *screenshot;
    const char *board_path;
    const char *video;        /* --video: V4L2 node */
    struct player_gpio gpio[PLAYER_MAX_GPIO];
    int gpio_count;
    /* network triggers (docs/triggers.md) */
    const char *dis;          /* --dis [ADDR:]PORT */
    int dis_exercise;         /* --dis-exercise; 0: not given */
    const char *mqtt;         /* --mqtt HOST[:PORT] */
    const char *mqtt_topic;   /* --mqtt-topic */
    /* one world, many channels (docs/simulators.md) */
    bool world_time_set;
    double world_time;        /* --world-time: the first frame's world time (on the grid k / fps) */
    enum player_world_clock world_clock; /* --world-clock frames|system|cigi|dis */
    struct player_channel channel;       /* --frustum, --view-offset */
    bool follow_set;
    uint16_t follow[3];       /* --follow SITE:APP:ENTITY: a DIS entity as the eyepoint */
    const char *cigi;         /* --cigi [ADDR:]PORT */
    const char *cigi_host;    /* --cigi-host ADDR:PORT */
};
/* "L,R,B,T" degrees (-89..89, left < right, bottom < top) into c; NULL or what is wrong. */
const char *player_parse_frustum(const char *text, struct player_channel *c);
/* NULL when the four angles make a frustum (each within -89..89, left < right, bottom < top). */
const char *player_channel_check_frustum(const float frustum[4]);
/* "YAW,PITCH,ROLL" degrees (-360..360) into c; NULL or what is wrong. */
const char *player_parse_view_offset(const char *text, struct player_channel *c);

void player_options_defaults(struct player_options *opt);
/* A display that shows frames (drm, wayland): runs until stopped, paced by it, stats line. */
bool player_on_screen(const struct player_options *opt);
/* Fills opt from argv (opt must hold the defaults). 0, or -EINVAL with a message in err that
 * names the flag and the values it accepts. Stops at --help or --version (opt->help,
 * opt->version set). */
int player_parse_args(struct player_options *opt, int argc, char **argv, char *err, size_t n);
/* The display a board profile names (display.backend: drm, wayland, auto) where the command
 * line named none (no --display, no --headless), checked against the flags as --display is. */
int player_board_display(struct player_options *opt, const char *backend, char *err, size_t n);
/* Parses one EFFECT@SECONDS[:X,Y,Z]; the position defaults to the origin. */
int player_parse_trigger(const char *text, struct player_trigger *out, char *err, size_t n);
/* Parses one CHIP:LINE=EFFECT[@X,Y,Z]. */
int player_parse_gpio(const char *text, struct player_gpio *out, char *err, size_t n);
void player_usage(FILE *f);
/* --version: "sbfx-play VERSION" (the Makefile's VERSION, the library's too). */
void player_version(FILE *f);

#endif
