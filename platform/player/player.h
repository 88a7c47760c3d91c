/* sbfx-play's state, shared by its files (private to the player):
 *   player.c         main, setup and teardown, results
 *   player_inputs.c  board profile, GPIO trigger lines, the V4L2 detail source
 *   player_loop.c    the frame loop: poll, inputs, simulate, render, present, stats line
 *   player_reset.c   GPU resets: a new context, its GL objects and sbfx, and the run goes on
 *   player_watch.c   the authoring loop: --watch, SIGHUP and --loop reload the scene */
#ifndef SBFX_PLAYER_H
#define SBFX_PLAYER_H

#include <limits.h>
#include <stdbool.h>
#include <stdint.h>

#include "player/options/board.h"
#include "display/display.h"
#include "egl/gl_reset.h"
#include "gpio/gpio_triggers.h"
#include "video/live_detail.h"
#include "player/options/options.h"
#include "sbfx.h"
#include "host/test_scene.h"
#include "player/outputs/notify.h"
#include "player/inputs/watch.h"

/* sbfx-play's exit status (main): 0 a finished or stopped run (--frames done, SIGINT, SIGTERM,
 * the Wayland window closed), 1 a bad argument or a failure, and this one when the display
 * server went away (the Wayland compositor, d->lost): a unit's Restart=on-failure starts
 * sbfx-play again with the compositor (EX_UNAVAILABLE of sysexits.h). */
#define PLAYER_EXIT_DISPLAY_LOST 69

struct frame_times {
    double sbfx_sum, sbfx_max;   /* sbfx_update + sbfx_render (+ glFinish when headless) */
    double total_sum, total_max; /* the whole frame, readback and PNG included */
};

/* What the once-a-second line reports: counters at the start of the second. */
struct second_stats {
    int64_t start_ns;
    uint64_t frames, flips, missed, fired, video;
    uint64_t shown;           /* presentation feedback's frames on screen (wayland) */
    int64_t latency_ns;       /* and their latency, summed */
    double frame_ms_sum, frame_ms_max;
};

struct player {
    const struct player_options *opt;
    struct board_profile board;
    bool have_board;
    struct display *display;
    struct test_scene scene;
    bool scene_made;
    sbfx_scene_camera camera; /* the scene file's camera group, or the default orbit */
    sbfx_scene_host host;     /* the scene file's daylight, host_lights, host_shadows */
    sbfx *fx;
    char out_dir[PATH_MAX];
    double sim_time;
    int frame_simulated;      /* particles advanced by this frame's updates, summed */
    sbfx_counters last;       /* sbfx_stats() after the last frame */
    struct frame_times times;
    int64_t frames_done;      /* 64-bit: a kiosk at 60 Hz passes 2^31 frames in 414 days */
    bool realtime;            /* drm or wayland without --fps: the simulation follows the clock */
    bool measure_gpu;         /* glFinish around sbfx (headless timings) */
    int64_t run_start_ns, last_frame_ns;
    /* inputs */
    struct gpio_trigger_spec gpio_specs[GPIO_TRIGGERS_MAX];
    int gpio_spec_count;
    struct gpio_triggers gpio;
    bool gpio_on;
    struct live_detail live;
    bool live_on;
    struct second_stats second;
    struct player_notify notify; /* READY=1, WATCHDOG=1 (player_notify.c) */
    /* GPU resets (player_reset.c) */
    struct gl_reset reset;
    uint64_t gpu_resets;
    bool recovering;          /* sbfx is being made again after a reset */
    double fx_time_lost;      /* the lost module's time: --trigger entries up to it had fired */
    double fx_clock_lost;     /* its absolute clock (sbfx_time): the new module starts there */
    double fx_created_at;     /* the player's time when the current module was made */
    /* the authoring loop (player_watch.c) */
    struct player_watch watch;
    sbfx_scene *scene_kept;   /* --loop: the scene it replays */
    double timeline_start;    /* sim_time when the timeline last started (--loop) */
    int64_t take_first;       /* headless: the first frame of this take (a reload starts one) */
};

int64_t player_now_ns(void);
void player_log(const char *message, void *user); /* "sbfx-play: message" on stderr */

/* player.c */
/* Makes sbfx (again, while p->recovering: the scene's GPIO lines are kept, its timeline is not
 * replayed, --trigger entries still ahead are scheduled relative to now). */
int player_create_fx(struct player *p, char *err, size_t n);

/* player_host.c */
/* Before the test scene is drawn at time t: the scene file's daylight, and where it asks for
 * them the smoke's shadow map (render.host_shadows) and the fire's lights
 * (render.host_lights), which need the simulation at t: it is advanced here first. */
int player_host_prepare(struct player *p, double t, char *err, size_t n);
/* Advances sbfx to time t (player_loop.c). */
int player_update(struct player *p, double t, char *err, size_t n);

/* player_reset.c */
/* Before each frame: asks the context whether the GPU was reset (SBFX_PLAY_INJECT_GPU_RESET=N
 * makes frame N answer "guilty" once) and, if so, makes everything that lived in it again. */
int player_check_gpu_reset(struct player *p, int frame, char *err, size_t n);
/* After the display is made: reset notification and the injected reset, if asked for. */
void player_reset_setup(struct player *p);

/* player_inputs.c */
int player_load_board(struct player *p, char *err, size_t n);
/* Collects the scene's GPIO triggers (before the scene is freed). */
int player_collect_scene_gpio(struct player *p, const sbfx_scene *scene, char *err, size_t n);
int player_open_inputs(struct player *p, char *err, size_t n);
/* The camera again, into a new sbfx (after a GPU reset). */
int player_open_video(struct player *p, char *err, size_t n);
/* Decodes the scene's detail clip, if it names one, into the volume (clip_detail.h): 0, or an
 * error naming the file. */
int player_open_clip(struct player *p, char *err, size_t n);
void player_close_inputs(struct player *p);
/* Reads the GPIO events that wait and fires what passes; never blocks. */
void player_service_gpio(struct player *p);
/* Takes the newest camera frame if one arrived (once per frame: a camera faster than the
 * display does not cost more uploads), notices losses, retries; never blocks. */
void player_service_video(struct player *p);

/* player_loop.c */
void player_catch_signals(void);
bool player_stop_requested(void);
int player_run_frames(struct player *p, char *err, size_t n);

#endif
