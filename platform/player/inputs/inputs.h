/* The player's inputs (platform/player/rooms.txt; docs/hacking.md "Adding a trigger source"):
 * what comes from outside, and reaches the frame loop only through the small contracts here.
 *   trigger sources   start effects; GPIO lines are one (gpio_source.h), a network source is
 *                     another. The loop polls their descriptors beside the display's and lets
 *                     each read what arrived (trigger_sources_*); none of them is named there.
 *   detail feeds      a V4L2 camera, a video clip: slices for the module's detail volume (detail.h)
 *   the scene's files what --watch watches (watch.h)
 *   signals           SIGINT and SIGTERM end the run, SIGHUP asks for a reload (signals.c)
 * Which of them a run has comes from the options (options/); nothing here knows the player's
 * own state (player.h), which holds them. */
#ifndef SBFX_PLAYER_INPUTS_H
#define SBFX_PLAYER_INPUTS_H

#include <poll.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sbfx.h"

/* Where an input says what happened ("sbfx-play: ..." on stderr, the player's). */
typedef void (*input_log_fn)(const char *message, void *user);

/* A trigger source: something outside that starts effects. One trigger path for all of them:
 * a source fires with sbfx_trigger on the module the loop hands it (the player's module of the
 * moment: a GPU reset makes a new one), as the scene's timeline and --trigger entries fire
 * through the module's schedule. Nothing blocks; a source that loses its device says so
 * through its log and tries again on its own, as the GPIO lines do. */
struct trigger_source;
struct trigger_source_ops {
    /* Descriptors for the loop's poll (POLLIN): fills at most max, returns how many. */
    int (*pollfds)(const struct trigger_source *s, struct pollfd *fds, int max);
    /* Reads what waits and fires what passes into fx; never blocks. */
    void (*service)(struct trigger_source *s, sbfx *fx, int64_t now_ns);
    /* Releases what the source holds (its lines, sockets, memory). */
    void (*close)(struct trigger_source *s);
};

struct trigger_source {
    const struct trigger_source_ops *ops;
    const char *name;   /* for messages: "gpio" */
};

/* The run's trigger sources (triggers.c): the loop waits on and services all of them. */
#define TRIGGER_SOURCES_MAX 8
#define TRIGGER_POLLFDS_MAX 64 /* the sources' descriptors together */
struct trigger_sources {
    struct trigger_source *list[TRIGGER_SOURCES_MAX];
    int count;
};

/* Adds an opened source (the loop polls it from the next wait on); -ENOSPC when full. */
int trigger_sources_add(struct trigger_sources *all, struct trigger_source *s, char *err, size_t n);
/* Every source's descriptors, at most max; returns how many. */
int trigger_sources_pollfds(const struct trigger_sources *all, struct pollfd *fds, int max);
/* Each source reads what waits and fires into fx. */
void trigger_sources_service(struct trigger_sources *all, sbfx *fx, int64_t now_ns);
/* Closes every source; the list is empty after. */
void trigger_sources_close(struct trigger_sources *all);

/* signals.c: SIGINT and SIGTERM end the kiosk loop after the frame in progress; SIGHUP asks for
 * a reload (a kiosk's `systemctl reload`). No SA_RESTART: a poll that waits returns at once. */
void player_catch_signals(void);
bool player_stop_requested(void);
void player_catch_hup(void);
/* True once per SIGHUP received. */
bool player_hup_taken(void);

#endif
