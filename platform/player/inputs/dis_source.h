/* DIS detonations as a trigger source (inputs.h; docs/triggers.md): --dis [ADDR:]PORT (or the
 * board's dis.listen) opens a UDP socket for Detonation PDUs (platform/net/dis/dis_receiver.h does
 * the protocol; this is the player's side of it), placed and mapped to effects by the scene
 * file's dis group (net/dis/dis_config.h), with --dis-exercise over the scene's dis.exercise. The
 * socket is one of the loop's descriptors, read without blocking; each detonation that passes
 * goes to the trigger queue. A reloaded scene's dis group takes over (a bad one is logged and
 * the old one goes on); the socket and the counts stay. */
#ifndef SBFX_PLAYER_DIS_SOURCE_H
#define SBFX_PLAYER_DIS_SOURCE_H

#include "net/common/geodesy.h"
#include "net/dis/dis_receiver.h"
#include "player/inputs/inputs.h"
#include "player/options/board.h"
#include "player/options/options.h"

struct dis_source {
    struct trigger_source source;    /* what the loop sees */
    struct dis_settings settings;    /* the scene's dis group with the board's and the flags' */
    struct dis_settings next;        /* a reloaded scene's, read here first (large: not on a stack) */
    struct dis_receiver *receiver;   /* NULL: no --dis; its counters are --stats' dis_* keys */
    const char *scene_path;
    int exercise_flag;               /* --dis-exercise; 0: not given */
    int read_errors;                 /* socket read errors (logged the first time) */
    bool world_timestamps;           /* --world-clock system|dis: absolute timestamps are world times */
    bool have_time;                  /* an absolute timestamp was heard (--world-clock dis) */
    uint32_t last_timestamp;
    int64_t last_timestamp_ns;       /* when (the monotonic clock) */
    double last_timestamp_system;    /* and the system clock then (the hour) */
    /* --follow SITE:APP:ENTITY: that entity's Entity State PDUs are the eyepoint */
    bool follow;
    struct dis_entity_id follow_id;
    bool have_pose;
    float pose_position[3];          /* scene metres from dis.origin */
    float pose_angles[3];            /* yaw from north clockwise, pitch up, roll right (degrees) */
    uint64_t poses;                  /* Entity State PDUs of the followed entity heard */
    struct geo_frame frame;          /* dis.origin's, for the poses */
    input_log_fn log;
    void *log_user;
};

/* Opens the socket when --dis or the board's dis.listen names one (fx checks the dis group's
 * effects), then adds the source to the run's: 0, or an error naming the flag or key and what
 * to do. Nothing stays open on failure. quiet: no "listening on" line. */
int dis_source_open(struct dis_source *d, struct trigger_sources *all, const struct player_options *opt,
                    const struct board_profile *b, const sbfx *fx, input_log_fn log, void *user, char *err, size_t n);
/* A DIS timestamp (absolute: seconds past the hour) in world time: the hour nearest `now`
 * (the system clock's seconds). */
double dis_timestamp_world(uint32_t timestamp, double now);
/* --world-clock dis: the world time now, from the last absolute timestamp heard (the hour from
 * the system clock) and the monotonic time since; false before the first. */
bool dis_source_time(const struct dis_source *d, int64_t now_ns, double *seconds);
/* DIS's Euler angles (psi, theta, phi: the body axes from ECEF's, z-y-x, radians) at an ECEF
 * point as the heading (from north, clockwise), pitch (up) and roll (right) of the local frame, in
 * degrees. */
void dis_orientation_local(const struct geo_frame *f, const float euler[3], float out[3]);
/* Its counters (NULL: no --dis). */
const struct dis_counts *dis_source_counts(const struct dis_source *d);

#endif
