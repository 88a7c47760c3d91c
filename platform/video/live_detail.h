/* Live detail images from a V4L2 camera into sbfx's detail volume, and the procedural volume
 * back whenever the camera is missing.
 *
 * Each new camera frame becomes one slice (luma.h) pushed with sbfx_detail_push_slice: the ring
 * then holds the camera's last `frames` frames and the particles' windows animate through them.
 * A camera missing at start, unplugged (ENODEV), failing or silent for timeout_ms is logged once
 * per outage; the procedural volume the module made at load (sbfx_detail_procedural, kept from
 * start) is pushed back whole in the same frame, so the picture keeps going without a dropped
 * frame; the device is reopened with a growing back-off (backoff_ms doubling up to 16 x; a
 * device that opens but stays silent counts as the same outage) and the first frame after the
 * outage is logged ("is back"). A missing camera is never fatal.
 *
 * Buffers (slice, procedural copy, box tables) are allocated once at live_detail_start; the
 * per-frame path allocates nothing. */
#ifndef SBFX_LIVE_DETAIL_H
#define SBFX_LIVE_DETAIL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "video/luma.h"
#include "sbfx.h"
#include "video/v4l2_source.h"

enum live_state { LIVE_OFF, LIVE_STREAMING, LIVE_WAITING };

struct live_detail_desc {
    const char *device;      /* "/dev/video0" */
    int width, height;       /* capture size to ask for (0: the driver's) */
    int timeout_ms;          /* no frame this long while streaming = lost (default 2000) */
    int backoff_ms;          /* first reopen delay (default 250), doubling up to 16 x */
};

struct live_detail_counts {
    uint64_t frames;      /* camera slices pushed */
    uint64_t distinct;    /* ... that differed from the slice before */
    uint64_t losses;      /* outages: the camera went away, failed or fell silent */
    uint64_t reopens;     /* outages that ended with frames again */
    uint64_t takeovers;   /* procedural volumes pushed back */
};

typedef void (*live_log_fn)(const char *message, void *user);

struct live_detail {
    struct live_detail_desc desc;
    sbfx *fx;
    int size, frames;
    struct v4l2_source source;
    struct luma_resampler resampler;
    float *box_values;        /* size * size */
    uint16_t *slice;          /* size * size half floats */
    uint16_t *procedural;     /* size * size * frames half floats */
    uint64_t last_hash;
    enum live_state state;
    int64_t last_frame_ns, retry_at_ns, backoff_ns;
    bool feeding;             /* camera slices are in the volume (a take-over is due on loss) */
    bool outage;              /* no frame since the camera went missing or failed */
    bool outage_logged;       /* ... and that was said (once per outage) */
    bool announce;            /* opened: say so with the first frame */
    bool ever_fed;
    live_log_fn log;
    void *log_user;
    struct live_detail_counts counts;
};

/* Allocates the buffers and tries the device once: 0 even when the camera is missing (logged,
 * retried later); -EINVAL with a message when the scene has no detail volume to feed, -ENOMEM. */
int live_detail_start(struct live_detail *ld, sbfx *fx, const struct live_detail_desc *desc,
                      live_log_fn log, void *user, char *err, size_t n);
/* Takes the newest frame if there is one, notices losses and timeouts, retries when due.
 * Never blocks; now_ns is CLOCK_MONOTONIC. */
void live_detail_service(struct live_detail *ld, int64_t now_ns);
void live_detail_stop(struct live_detail *ld);
/* "640x360 YUYV (vivid)" or "waiting for /dev/video0" */
void live_detail_describe(const struct live_detail *ld, char *out, size_t n);

#endif
