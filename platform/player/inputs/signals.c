/* Signals (inputs.h): SIGINT and SIGTERM end the run after the frame in progress, SIGHUP asks for
 * a reload (the authoring loop's, authoring.c). */
#include <signal.h>
#include <string.h>

#include "player/inputs/inputs.h"

static volatile sig_atomic_t stop_signal;

static void on_signal(int sig)
{
    stop_signal = sig;
}

/* SIGINT and SIGTERM end the kiosk loop after the frame in progress; no SA_RESTART, so a poll
 * waiting for a page flip returns at once. */
void player_catch_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

bool player_stop_requested(void)
{
    return stop_signal != 0;
}

static volatile sig_atomic_t hup_signal;

static void on_hup(int sig)
{
    (void)sig;
    hup_signal = 1;
}

/* No SA_RESTART: a headless run waiting for a change wakes at once. */
void player_catch_hup(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_hup;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGHUP, &sa, NULL);
}

bool player_hup_taken(void)
{
    if (!hup_signal) return false;
    hup_signal = 0;
    return true;
}
