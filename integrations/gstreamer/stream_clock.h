/* The effect's clock from a stream's buffers (docs/hosts/gstreamer.md, "Time").
 *
 * The module's clock is the running time of the buffers since the first buffer after a start or
 * a flush: each buffer advances it by the difference between its running time and the last
 * one's, so a file rendered twice gives the same frames whatever the machine's speed, a paused
 * pipeline (no buffers) pauses the effect and a variable frame rate is followed as it comes.
 * Differences are taken in whole nanoseconds and become seconds once (no drift). The step is
 * never negative: a buffer whose running time is not after the last (a repeated or reordered
 * timestamp) advances nothing and leaves the last one where it was. A buffer without a running
 * time (no timestamp, or outside the segment) advances by its duration, else by one frame of
 * the caps' frame rate, else by 1/30 s; its time is then the last one plus that step. A jump
 * beyond STREAM_CLOCK_MAX_STEP_NS (a broken timestamp, a live source resuming after minutes)
 * advances by that much only, so the simulation never has minutes to catch up at once.
 * Pure arithmetic: no GStreamer, no allocation. */
#ifndef SBFX_GST_STREAM_CLOCK_H
#define SBFX_GST_STREAM_CLOCK_H

#include <stdbool.h>
#include <stdint.h>

#define STREAM_CLOCK_NONE UINT64_MAX                  /* GST_CLOCK_TIME_NONE */
#define STREAM_CLOCK_MAX_STEP_NS UINT64_C(10000000000) /* 10 s */
#define STREAM_CLOCK_FALLBACK_NS UINT64_C(33333333)   /* 1/30 s */

struct stream_clock {
    bool started;          /* a buffer came since the start or the last flush */
    uint64_t first_ns;     /* its running time: the module's zero */
    uint64_t last_ns;      /* the running time the module's clock stands at (+ first_ns) */
    uint64_t frame_ns;     /* one frame of the caps' frame rate (0: variable or unknown) */
    uint64_t untimed;      /* buffers that came without a running time */
    uint64_t clamped;      /* steps cut to STREAM_CLOCK_MAX_STEP_NS */
};

/* Forgets the stream (a start, a flush): the next buffer is the module's zero. Keeps frame_ns. */
void stream_clock_reset(struct stream_clock *c);
/* The caps' frame rate, num/den frames per second (0/1 or an invalid rate: variable). */
void stream_clock_set_rate(struct stream_clock *c, int num, int den);
/* One buffer: its running time and duration (STREAM_CLOCK_NONE: unknown). Returns the step in
 * nanoseconds to advance the module by (0 for the first buffer). */
uint64_t stream_clock_advance(struct stream_clock *c, uint64_t running_ns, uint64_t duration_ns);
/* The module's time of the last buffer, in seconds since the first. */
double stream_clock_seconds(const struct stream_clock *c);

#endif
