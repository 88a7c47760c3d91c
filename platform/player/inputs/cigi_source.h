/* CIGI 3.3 from a simulation host as one of the player's inputs (inputs.h; docs/simulators.md):
 * --cigi [ADDR:]PORT opens the receiver (platform/net/cigi/cigi_receiver.h does the protocol;
 * this is the player's side of it), placed through the scene's dis.origin and mapped by its
 * cigi.effects. Each service drains the receiver's events:
 *   FRAME            the host's clock (IG Control's timestamp): --world-clock cigi's world time
 *   EFFECT_START     an identified trigger (the entity's identity) into the trigger queue, at the
 *                    message's host time under --world-clock cigi, else when it fires
 *   EFFECT_STOP      the instance ended (the queue's stop)
 *   OWNSHIP          the eyepoint (entity 0): the player's camera rides on it
 *   VIEW_DEFINITION  this channel's frustum (the enabled half-angles)
 *   VIEW_CONTROL     this channel's view offset (yaw, pitch, roll)
 * and the player sends Start of Frame after each frame (cigi_source_frame_done). Nothing is
 * allocated after open. */
#ifndef SBFX_PLAYER_CIGI_SOURCE_H
#define SBFX_PLAYER_CIGI_SOURCE_H

#include "net/cigi/cigi_receiver.h"
#include "player/inputs/inputs.h"
#include "player/options/options.h"

struct cigi_source {
    struct trigger_source source;    /* what the loop sees */
    struct cigi_settings settings;
    struct cigi_receiver *receiver;  /* NULL: no --cigi */
    const char *scene_path;
    bool world_clock;                /* --world-clock cigi: the host's timestamps are world time */
    int read_errors, send_errors;
    input_log_fn log;
    void *log_user;
    /* what the host said last */
    bool have_time;
    double host_seconds;             /* the last IG Control's timestamp, unwrapped */
    int64_t host_received_ns;        /* when it came (the monotonic clock) */
    bool have_ownship;
    struct cigi_pose ownship;
    struct player_channel view;      /* from View Definition and View Control (have_* set) */
    uint32_t ig_frame;               /* Start of Frame's counter */
};

/* Opens the receiver when --cigi is given (the scene must have dis.origin; its cigi.effects are
 * checked against fx) and adds the source: 0, or an error naming the flag and what to do. */
int cigi_source_open(struct cigi_source *c, struct trigger_sources *all, const struct player_options *opt,
                     const sbfx *fx, input_log_fn log, void *user, char *err, size_t n);
/* The host's time now (its last timestamp + the monotonic time since), false before the first. */
bool cigi_source_time(const struct cigi_source *c, int64_t now_ns, double *seconds);
/* After a frame is drawn: Start of Frame to the host (a failure is logged once and counted). */
void cigi_source_frame_done(struct cigi_source *c, int64_t now_ns);
/* Its counters (NULL: no --cigi). */
const struct cigi_counts *cigi_source_counts(const struct cigi_source *c);

#endif
