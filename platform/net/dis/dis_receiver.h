/* DIS detonations into effects: the UDP socket (udp_socket.h), the PDU parser (dis_pdu.h), the
 * exercise and repeat filters (dis_events.h), the range, the effect table (dis_effects.h) and the
 * placement (geodesy.h), in that order. Every PDU read is counted once:
 *     pdus = detonations + ignored + malformed
 *   detonations  set off an effect (handed to the sink)
 *   ignored      well-formed but not used: another PDU type, another exercise, a repeat, farther
 *                than the range, or no effect for its munition and result
 *   malformed    dropped: truncated, oversized, another protocol version, a wrong length field,
 *                a location that is not a number
 * The first PDU of each kind of problem is logged, then the 10th, 100th, 1000th...: a storm of
 * bad traffic says so without flooding the log.
 *
 * The socket is read on the frame loop's thread, never blocking, at most DIS_SERVICE_MAX
 * datagrams a call (a flood waits in the kernel's buffer, and frames go on). Datagram buffers are
 * part of the receiver, made once at open: nothing is allocated per PDU. */
#ifndef SBFX_DIS_RECEIVER_H
#define SBFX_DIS_RECEIVER_H

#include <net/if.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "net/common/udp_socket.h"
#include "net/dis/dis_effects.h"
#include "net/dis/dis_pdu.h"

#define DIS_DEFAULT_PORT 3000
#define DIS_DEFAULT_RANGE_M 20000.0
#define DIS_BATCH 32                 /* datagrams per recvmmsg */
#define DIS_SERVICE_MAX 4096         /* datagrams per service call, at most */

/* What the scene's dis group, the board and the flags say (the player merges them: player/inputs/dis_source.c). */
struct dis_settings {
    struct udp_endpoint listen;
    char interface[IF_NAMESIZE];     /* multicast join: "" for the kernel's choice */
    int exercise;                    /* 1..255, or DIS_ANY */
    bool have_origin;
    double origin[3];                /* latitude, longitude (degrees), height (m, WGS-84) */
    double range_m;
    struct dis_effect_map effects;
};

enum dis_ignore_reason { DIS_IGNORED_TYPE, DIS_IGNORED_EXERCISE, DIS_IGNORED_REPEAT, DIS_IGNORED_RANGE,
                         DIS_IGNORED_UNMAPPED, DIS_IGNORED_COUNT };

struct dis_counts {
    uint64_t datagrams, pdus, detonations, ignored, malformed;
    uint64_t ignored_by[DIS_IGNORED_COUNT];
    uint64_t malformed_by[DIS_STATUS_COUNT];
};

/* Where detonations go: fire() takes the effect and the scene position; fire_event(), where set,
 * is called instead with the detonation's event ID (its identity on every channel) and the PDU's
 * timestamp (docs/simulators.md); heard(), where set, with every well-formed PDU's timestamp. */
struct dis_sink {
    void (*fire)(const char *effect, const float position[3], void *user);
    void (*log)(const char *message, void *user);
    void *user;
    void (*fire_event)(const char *effect, const float position[3], const struct dis_entity_id *event,
                       uint32_t timestamp, void *user);
    /* every well-formed PDU's timestamp, where set (the world clock from DIS) */
    void (*heard)(uint32_t timestamp, void *user);
    /* every well-formed Entity State PDU of the exercise, where set (an entity to follow); the PDU
     * is still counted as ignored (it starts no effect) */
    void (*entity)(const struct dis_entity_state *state, void *user);
};

struct dis_receiver;

/* Opens the socket (settings->listen) and makes the buffers; settings must have an origin. */
int dis_receiver_open(struct dis_receiver **out, const struct dis_settings *settings, char *err, size_t n);
/* Without a socket (tests, the fuzzer): dis_receiver_datagram only. */
int dis_receiver_make(struct dis_receiver **out, const struct dis_settings *settings, char *err, size_t n);
void dis_receiver_close(struct dis_receiver *r);
/* New placement, exercise, range and effects (a reloaded scene); the socket and counts stay. */
void dis_receiver_configure(struct dis_receiver *r, const struct dis_settings *settings);
int dis_receiver_fd(const struct dis_receiver *r);
/* Reads what waits on the socket (never blocks): the datagrams read, or a negative errno. */
int dis_receiver_service(struct dis_receiver *r, int64_t now_ns, const struct dis_sink *sink);
/* One datagram (truncated: it was longer than DIS_MAX_PDU_SIZE; from: its sender, or NULL). */
void dis_receiver_datagram(struct dis_receiver *r, const uint8_t *data, size_t length, bool truncated,
                           const struct sockaddr_in *from, int64_t now_ns, const struct dis_sink *sink);
const struct dis_counts *dis_receiver_counts(const struct dis_receiver *r);
/* "another exercise", "out of range"... for logs. */
const char *dis_ignore_name(enum dis_ignore_reason reason);

#endif
