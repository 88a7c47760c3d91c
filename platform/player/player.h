/* sbfx-play's state, shared by the player's own files (the top of platform/player/rooms.txt):
 *   player.c     main, setup and teardown, results
 *   module.c     sbfx made from the scene and the options (again after a GPU reset), advanced
 *   loop.c       the frame loop: wait (display, trigger sources), start the queued triggers,
 *                draw, simulate, render, present
 *   host.c       the test scene as the scene file describes it: daylight, the smoke's shadow,
 *                the fire's lights
 *   reset.c      GPU resets: a new context, its GL objects and sbfx, and the run goes on
 *   authoring.c  --watch, SIGHUP and --loop reload the scene or replay its timeline
 *   clock.c      the player's clock and its log line
 * Below them: the options and board profiles (options/), the inputs (inputs/: trigger sources,
 * detail feeds, the scene's files, signals) and what the player reports (outputs/). */
#ifndef SBFX_PLAYER_H
#define SBFX_PLAYER_H

#include <limits.h>
#include <stdbool.h>
#include <stdint.h>

#include "display/display.h"
#include "egl/gl_reset.h"
#include "host/test_scene.h"
#include "player/inputs/cigi_source.h"
#include "player/inputs/detail.h"
#include "player/inputs/dis_source.h"
#include "player/inputs/gpio_source.h"
#include "player/inputs/inputs.h"
#include "player/inputs/mqtt_source.h"
#include "player/inputs/watch.h"
#include "player/options/board.h"
#include "player/options/options.h"
#include "player/outputs/notify.h"
#include "player/outputs/stats.h"
#include "sbfx.h"

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

/* One world, many channels (world.c) */
#define WORLD_TIMELINE_MAX 256
struct world_timeline_entry {
    char effect[PLAYER_EFFECT_NAME_MAX];
    double time;
    float position[3];
};
struct world {
    bool on;                  /* world mode: --world-time or --world-clock system|cigi|dis */
    int64_t first_k;          /* the first frame's k on the grid k / fps */
    double base;              /* the module's desc.start_time: the whole minute at or before it */
    uint64_t cli_fired[(PLAYER_MAX_TRIGGERS + 63) / 64];    /* identified --trigger entries started */
    struct world_timeline_entry timeline[WORLD_TIMELINE_MAX]; /* the scene's, world mode */
    int timeline_count;
    uint64_t timeline_fired[WORLD_TIMELINE_MAX / 64];
    int jump_said;            /* a world clock far ahead of the module was logged */
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
    bool paced;               /* headless with a real-time trigger source (--dis, --mqtt): frames
                                 at --fps on the wall clock */
    int64_t run_start_ns, last_frame_ns;
    /* inputs (inputs/): the loop polls and services the trigger sources, fires their queue,
     * and services the detail feeds */
    struct trigger_sources triggers; /* GPIO, DIS, MQTT; with the timeline and --trigger, one path */
    struct gpio_source gpio;  /* the GPIO lines, one of the trigger sources when it has any */
    struct dis_source dis;    /* --dis: DIS detonations */
    struct cigi_source cigi;  /* --cigi: a simulation host's IG messages */
    struct mqtt_source mqtt;  /* --mqtt: MQTT messages */
    struct detail_feed detail;
    struct second_stats second;
    struct player_notify notify; /* READY=1, WATCHDOG=1 (outputs/notify.c) */
    /* GPU resets (reset.c) */
    struct gl_reset reset;
    uint64_t gpu_resets;
    bool recovering;          /* sbfx is being made again after a reset */
    double fx_time_lost;      /* the lost module's time: --trigger entries up to it had fired */
    double fx_clock_lost;     /* its absolute clock (sbfx_time): the new module starts there */
    double fx_created_at;     /* the player's time when the current module was made */
    /* the authoring loop (authoring.c) */
    struct scene_watch watch;
    sbfx_scene *scene_kept;   /* --loop: the scene it replays */
    sbfx_scene *scene_first;  /* --scene parsed before the display opens; the first module takes it */
    double timeline_start;    /* sim_time when the timeline last started (--loop) */
    int64_t take_first;       /* headless: the first frame of this take (a reload starts one) */
    struct world world;       /* world time, identified triggers (world.c) */
    struct player_channel channel; /* the board's view, then --frustum, --view-offset (later: CIGI) */
};

/* world.c */
bool world_mode(const struct player_options *opt);
double world_system_seconds(void);              /* CLOCK_REALTIME (PTP/NTP-disciplined), seconds */
int world_setup(struct player *p, char *err, size_t n); /* the first frame on the grid; the base */
double world_frame_time(const struct player *p, int64_t index); /* (first_k + index) / fps */
bool world_trigger_identified(const struct player *p, const struct player_trigger *t);
/* The scene's timeline, copied (world mode runs it at world times). */
void world_take_timeline(struct player *p, const sbfx_scene *scene);
/* Starts the identified --trigger and (world mode) timeline entries due at the clock `now`. */
int world_fire_due(struct player *p, double now, char *err, size_t n);
/* An eyepoint (scene metres; yaw from north clockwise, pitch up, roll right, degrees) as a view. */
void world_eyepoint_view(const float position[3], const float angles[3], float view[16]);
/* The eyepoint's view: CIGI's entity 0, else the DIS entity --follow names, once heard (true);
 * false: the scene's camera. */
bool world_eyepoint(const struct player *p, float view[16]);
/* The channel of the moment: the board's and the flags' (p->channel), CIGI's View Definition and
 * View Control over them where the host sent them. */
struct player_channel world_channel(const struct player *p);
/* The channel's view: the eyepoint's view turned by the offset, the frustum's projection. */
void world_channel_view(const struct player_channel *c, float near_z, float far_z, float view[16],
                        float projection[16]);

/* clock.c */
int64_t player_now_ns(void);
void player_log(const char *message, void *user); /* "sbfx-play: message" on stderr */

/* module.c */
/* Parses the --scene file before anything else is opened (a typo is reported before a display
 * is set up or a mode set); the first player_create_fx takes it. */
int player_parse_scene(struct player *p, char *err, size_t n);
/* Makes sbfx (again, while p->recovering: the scene's GPIO lines are kept, its timeline is not
 * replayed, --trigger entries still ahead are scheduled relative to now). */
int player_create_fx(struct player *p, char *err, size_t n);
/* Advances sbfx to time t. */
int player_update(struct player *p, double t, char *err, size_t n);

/* host.c */
/* Before the test scene is drawn at time t: the scene file's daylight, and where it asks for
 * them the smoke's shadow map (render.host_shadows) and the fire's lights
 * (render.host_lights), which need the simulation at t: it is advanced here first. */
int player_host_prepare(struct player *p, double t, char *err, size_t n);

/* reset.c */
/* Before each frame: asks the context whether the GPU was reset (SBFX_PLAY_INJECT_GPU_RESET=N
 * makes frame N answer "guilty" once) and, if so, makes everything that lived in it again. */
int player_check_gpu_reset(struct player *p, int frame, char *err, size_t n);
/* After the display is made: reset notification and the injected reset, if asked for. */
void player_reset_setup(struct player *p);

/* authoring.c */
/* --watch: the scene's files (none without --watch or a scene file). */
int player_watch_files(struct player *p, const sbfx_scene *scene, char *err, size_t n);
/* Between two frames: a SIGHUP, a settled change or --loop's period. Returns PLAYER_RELOADED when
 * a new scene took over, PLAYER_REPLAYED when --loop started the timeline again, 0 when nothing
 * did (a refused edit is logged, and the old scene goes on); never an error: an author's
 * mistake does not stop the player. */
enum { PLAYER_RELOADED = 1, PLAYER_REPLAYED = 2 };
int player_watch_service(struct player *p);
/* Headless --watch after a take: waits for a reload (1) or a stop signal (0). */
int player_watch_wait(struct player *p, char *err, size_t n);
/* Keeps the scene (for --loop and the watch list) or frees it. */
void player_keep_scene(struct player *p, sbfx_scene *scene);

/* loop.c */
int player_run_frames(struct player *p, char *err, size_t n);

#endif
