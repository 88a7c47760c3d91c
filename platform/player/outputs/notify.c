/* READY=1 and WATCHDOG=1 for systemd (player_notify.h; docs/kiosk-deploy.md). */
#include <stdio.h>
#include <stdlib.h>
#include <systemd/sd-daemon.h>
#include <time.h>

#include "player/outputs/notify.h"

#define HANG_ENV "SBFX_PLAY_TEST_HANG_AFTER_FRAMES"

void player_notify_init(struct player_notify *n)
{
    *n = (struct player_notify){0};
    uint64_t usec = 0;
    /* > 0 when WATCHDOG_USEC is set (and WATCHDOG_PID, if set, is this process) */
    if (sd_watchdog_enabled(0, &usec) > 0 && usec > 0) n->ping_every_ns = (int64_t)(usec * 500);
    const char *hang = getenv(HANG_ENV);
    if (hang && *hang) {
        char *end;
        long long frames = strtoll(hang, &end, 10);
        if (*end == '\0' && frames > 0) n->hang_after = frames;
        else fprintf(stderr, "sbfx-play: ignoring %s=%s (a frame count > 0)\n", HANG_ENV, hang);
    }
}

void player_notify_frame(struct player_notify *n, int64_t frames_done, int64_t now_ns)
{
    if (!n->ready_sent) {
        char state[64]; /* sd_notifyf would allocate */
        snprintf(state, sizeof(state), "READY=1\nSTATUS=frame %lld presented", (long long)frames_done);
        sd_notify(0, state);
        n->ready_sent = true;
        n->last_ping_ns = now_ns;
        return;
    }
    if (n->ping_every_ns > 0 && now_ns - n->last_ping_ns >= n->ping_every_ns) {
        sd_notify(0, "WATCHDOG=1");
        n->last_ping_ns = now_ns;
    }
}

void player_notify_stopping(void)
{
    sd_notify(0, "STOPPING=1");
}

void player_notify_test_hang(const struct player_notify *n, int64_t frames_done)
{
    if (n->hang_after <= 0 || frames_done < n->hang_after) return;
    fprintf(stderr, "sbfx-play: %s: the render loop stalls after frame %lld (a test)\n", HANG_ENV,
            (long long)frames_done);
    fflush(stderr);
    /* like a wedged driver: no frame, no ping; SIGTERM/SIGKILL (or the watchdog's SIGABRT) end it */
    for (;;) {
        struct timespec second = {1, 0};
        nanosleep(&second, NULL);
    }
}
