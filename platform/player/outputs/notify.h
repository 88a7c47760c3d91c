/* The player and the service manager (docs/kiosk-deploy.md): under a systemd unit with
 * Type=notify and WatchdogSec=, READY=1 after the first frame is presented and WATCHDOG=1 while
 * frames complete, so a render loop that hangs stops the pings and systemd restarts the
 * player. Outside systemd (no NOTIFY_SOCKET) nothing is sent. */
#ifndef SBFX_PLAYER_NOTIFY_H
#define SBFX_PLAYER_NOTIFY_H

#include <stdbool.h>
#include <stdint.h>

struct player_notify {
    bool ready_sent;
    int64_t ping_every_ns; /* half the watchdog interval; 0: no watchdog */
    int64_t last_ping_ns;
    int64_t hang_after;    /* the test hook (SBFX_PLAY_TEST_HANG_AFTER_FRAMES); 0: none */
};

/* Reads the watchdog interval (WATCHDOG_USEC, WATCHDOG_PID) and the test hook. */
void player_notify_init(struct player_notify *n);
/* After each presented frame (frames_done counts it): READY=1 on the first, WATCHDOG=1 when
 * half the interval has passed since the last ping. Allocates nothing; failures are ignored
 * (systemd then restarts a player that looks hung, which is the point). */
void player_notify_frame(struct player_notify *n, int64_t frames_done, int64_t now_ns);
/* STOPPING=1 when the loop ends on a signal. */
void player_notify_stopping(void);
/* The test hook: after SBFX_PLAY_TEST_HANG_AFTER_FRAMES frames the render loop stalls here as a
 * wedged GPU would (sleeping until a signal ends the process), so a test can check that the
 * pings stop. Returns at once when the hook is not set. */
void player_notify_test_hang(const struct player_notify *n, int64_t frames_done);

#endif
