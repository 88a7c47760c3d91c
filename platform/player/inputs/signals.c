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

/* No SA_RESTART: a poll that waits (for a page flip, for a change of the scene) returns at once. */
static void catch_signal(int sig, void (*handler)(int))
{
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = handler;
    sigemptyset(&sa.sa_mask);
    sigaction(sig, &sa, NULL);
}

/* SIGINT and SIGTERM end the kiosk loop after the frame in progress. */
void player_catch_signals(void)
{
    catch_signal(SIGINT, on_signal);
    catch_signal(SIGTERM, on_signal);
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

/* A headless run waiting for a change wakes at once. */
void player_catch_hup(void)
{
    catch_signal(SIGHUP, on_hup);
}

bool player_hup_taken(void)
{
    if (!hup_signal) return false;
    hup_signal = 0;
    return true;
}
