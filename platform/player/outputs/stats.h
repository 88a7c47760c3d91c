/* What `sbfx-play --stats FILE` writes, from one table: the JSON object of a run and the key list
 * of --help (and of the man page, sbfx-play.1, which tests/cli.sh checks against --help) come
 * from the same rows, so they cannot drift apart.
 *
 *   player_stats_record   the numbers of a finished run, one field per key (the player fills it)
 *   player_stats_write    the record as one JSON object: every run's keys, then those of the
 *                         parts in use (a DRM or Wayland display, GPIO lines, a camera, --dis
 *                         or --mqtt: the kiosk's counters and trigger_log; presentation-time
 *                         feedback: presented_frames, latency_ms_*...; GPIO lines: gpio_*; a
 *                         camera: video_*; --dis: dis_*; --mqtt: mqtt_*)
 *   player_stats_usage    the key list for --help, grouped as the JSON is */
#ifndef SBFX_PLAYER_STATS_H
#define SBFX_PLAYER_STATS_H

#include <stdbool.h>
#include <stdio.h>

/* One entry of trigger_log: an effect started (the player's trigger log, inputs/trigger_queue.h). */
#define STATS_TRIGGER_LOG_MAX 16
struct stats_trigger {
    const char *source;       /* "gpio", "dis", "mqtt", "timeline", "cli" or "cigi" (a static string) */
    char effect[64];
    float at[3];
    double time;              /* the module's clock at the effect's first step */
};

/* A run's numbers, one field per key (integers as long long: counters of 64 bits print the
 * same; the player's own counters never reach 2^63). */
struct player_stats_record {
    long long programs, textures, framebuffers, gpu_bytes, passes, draw_calls, composite_tiles, composite_pixels;
    long long particles_simulated, heap_allocs_after_load;
    double budget_ms, gpu_ms;
    long long frames_over_budget, quality_changes;
    char quality[64];
    long long gpu_resets, gpu_reset_notification;
    long long frames, flips, missed_vblanks, triggers_fired, triggers_refused;
    long long display_unplugs, display_replugs, display_paused_frames;
    long long presented_frames, discarded_frames;
    double latency_ms_mean, latency_ms_max;
    long long gpio_edges, gpio_fired, gpio_filtered, gpio_refused, gpio_overflows;
    long long gpio_losses, gpio_returns, gpio_retries, gpio_absent, gpio_appeared;
    long long video_frames, video_distinct, video_losses, video_reopens, video_takeovers;
    long long dis_pdus, dis_detonations, dis_ignored, dis_malformed;
    long long mqtt_messages, mqtt_malformed, mqtt_reconnects;
    long long cigi_messages, cigi_malformed, cigi_ignored, cigi_entities, cigi_stopped, cigi_start_of_frame;
    double world_time;
    long long triggers_expired;
    struct stats_trigger trigger_log[STATS_TRIGGER_LOG_MAX]; /* oldest first */
    int trigger_log_count;
    bool kiosk_on, gpio_on, video_on, presentation_on; /* which groups of keys the run writes */
    bool dis_on, mqtt_on, cigi_on, world_on;
};

/* 0, or -EIO when writing failed (errno says why). */
int player_stats_write(const struct player_stats_record *r, FILE *f);
void player_stats_usage(FILE *f);

#endif
