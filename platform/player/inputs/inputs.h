/* The player's inputs (platform/player/rooms.txt; docs/hacking.md "Adding a trigger source"):
 * what comes from outside, and reaches the frame loop only through the small contracts here.
 *   trigger sources   start effects: GPIO lines (gpio_source.h), DIS detonations
 *                     (dis_source.h), MQTT messages (mqtt_source.h). The loop polls their
 *                     descriptors beside the display's and lets each read what arrived into
 *                     the one trigger queue (trigger_queue.h), which it fires into the module
 *                     once a frame (trigger_sources_*); none of them is named there.
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

#include "player/inputs/trigger_queue.h"
#include "sbfx.h"

/* Where an input says what happened ("sbfx-play: ..." on stderr, the player's). */
typedef void (*input_log_fn)(const char *message, void *user);

/* A trigger source: something outside that starts effects. One trigger path for all of them:
 * a source queues what arrives (trigger_queue_push, with its kind), and the loop starts the
 * queue's triggers at the next frame's first step (trigger_sources_fire) on the player's module
 * of the moment (a GPU reset makes a new one), where the scene's timeline and --trigger entries
 * fire through the module's schedule; the module's listener logs them all. Nothing blocks; a
 * source that loses its device or broker says so through its log and tries again on its own,
 * as the GPIO lines and the MQTT client do. */
struct trigger_source;
struct trigger_source_ops {
    /* Descriptors for the loop's poll (POLLIN): fills at most max, returns how many. */
    int (*pollfds)(const struct trigger_source *s, struct pollfd *fds, int max);
    /* Reads what waits and queues what passes on q; never blocks. fx: the module of the
     * moment, for the names of its effects (a source never fires into it itself). */
    void (*service)(struct trigger_source *s, struct trigger_queue *q, const sbfx *fx, int64_t now_ns);
    /* The scene file was read again and the module took it over (--watch, SIGHUP): a source
     * that reads its own part of the scene reads it again (a bad one is logged, and the old
     * one goes on). NULL: nothing to do. */
    void (*reload)(struct trigger_source *s, const sbfx *fx);
    /* Releases what the source holds (its lines, sockets, threads, memory). */
    void (*close)(struct trigger_source *s);
};

struct trigger_source {
    const struct trigger_source_ops *ops;
    const char *name;   /* for messages: "gpio" */
    bool realtime;      /* its senders keep the wall clock (the network's): a headless run's
                           frames come at --fps in real time */
};

/* The run's trigger sources (triggers.c): the loop waits on and services all of them, and fires
 * their queue. */
#define TRIGGER_SOURCES_MAX 8
#define TRIGGER_POLLFDS_MAX 64 /* the sources' descriptors together */
struct trigger_sources {
    struct trigger_source *list[TRIGGER_SOURCES_MAX];
    int count;
    struct trigger_queue queue; /* where every source's triggers meet the loop */
};

/* Adds an opened source (the loop polls it from the next wait on); -ENOSPC when full. */
int trigger_sources_add(struct trigger_sources *all, struct trigger_source *s, char *err, size_t n);
/* Every source's descriptors, at most max; returns how many. */
int trigger_sources_pollfds(const struct trigger_sources *all, struct pollfd *fds, int max);
/* Each source reads what waits into the queue. */
void trigger_sources_service(struct trigger_sources *all, const sbfx *fx, int64_t now_ns);
/* Once a frame, before its simulation: each source serviced once more (MQTT's messages come on
 * the client's thread, with no descriptor to poll), then the queue started in fx. Returns how
 * many effects started. */
int trigger_sources_fire(struct trigger_sources *all, sbfx *fx, int64_t now_ns);
/* The module's trigger listener is the queue's log (after every sbfx_create: a GPU reset makes
 * a new module), so the timeline's and --trigger's starts are logged too. */
void trigger_sources_listen(struct trigger_sources *all, sbfx *fx);
/* The scene was reloaded: each source's reload. */
void trigger_sources_reload(struct trigger_sources *all, const sbfx *fx);
/* Whether a source keeps the wall clock (trigger_source.realtime). */
bool trigger_sources_realtime(const struct trigger_sources *all);
/* Closes every source; the list is empty after (the queue's counts and log stay for --stats). */
void trigger_sources_close(struct trigger_sources *all);

/* signals.c: SIGINT and SIGTERM end the kiosk loop after the frame in progress; SIGHUP asks for
 * a reload (a kiosk's `systemctl reload`). No SA_RESTART: a poll that waits returns at once. */
void player_catch_signals(void);
bool player_stop_requested(void);
void player_catch_hup(void);
/* True once per SIGHUP received. */
bool player_hup_taken(void);

#endif
