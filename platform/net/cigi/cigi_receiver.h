/* CIGI 3.3 on the image generator's side (docs/cigi.md): the host's messages off a UDP socket
 * (udp_socket.h), parsed (cigi_packet.h), turned into events in a fixed queue, and Start of
 * Frame sent back. The player polls it once a frame, on the frame loop's thread:
 *
 *     cigi_receiver_service(r, now_ns);                 reads what waits, never blocks
 *     while (cigi_receiver_next(r, &event)) ...         the events, oldest first
 *     cigi_receiver_send_sof(r, &info, err, n);         Start of Frame for the frame drawn
 *
 * What the events say:
 *   FRAME            an IG Control: the host's frame number and timestamp (the shared clock)
 *   EFFECT_START     an entity whose type the scene's cigi.effects names went Active (or its
 *                    animation was played again after a stop): the effect, its identity, where
 *                    (latitude, longitude, altitude placed through dis.origin) and when
 *   EFFECT_STOP      that entity was Destroyed, went Inactive, or its animation was stopped
 *   OWNSHIP          entity 0's pose (the eyepoint)
 *   VIEW_DEFINITION  a view's frustum (asymmetric half-angles left, right, bottom, top)
 *   VIEW_CONTROL     a view's offsets from its entity (x, y, z; yaw, pitch, roll)
 * View packets pass for every view, or only for settings.view_id's (and its group's).
 *
 * Every packet read is counted once:
 *     packets = used + ignored + malformed
 *   used       IG Control, Entity Control of an effect entity or of the ownship, a view packet
 *   ignored    well-formed but not used: another packet type, an entity whose type is no effect,
 *              an effect entity attached to a parent (not placed), another view's packet
 *   malformed  dropped: truncated, a wrong size, no IG Control first (the whole message), a bad
 *              version or byte-swap magic (the whole message), a value that is not a number
 * --stats: cigi_messages (messages read), cigi_malformed, cigi_ignored, cigi_entities (effect
 * entities started). The first packet of each kind of problem is logged, then the 10th, 100th...
 *
 * Identity: an effect entity's start carries the entity ID, a generation (1 at the first
 * activation this receiver heard of that ID, +1 at each re-activation) and the host frame number
 * of the activation; identity = 2^62 + ID x 2^32 + that frame number, the same on every channel
 * that heard the activation, whenever it started and whatever else it heard before (a count of
 * re-activations is not: a channel restarted since counts from 1 again).
 *
 * Memory: the receiver is one block made at open (the entity table for all 65,536 entity IDs,
 * the datagram buffers, the event queue); nothing is allocated per message. The socket is read at
 * most CIGI_SERVICE_MAX datagrams a call, and never while the queue has less room than a whole
 * message's events: a flood waits in the kernel's buffer, none of its events is lost. */
#ifndef SBFX_CIGI_RECEIVER_H
#define SBFX_CIGI_RECEIVER_H

#include <net/if.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "net/cigi/cigi_packet.h"
#include "net/common/udp_socket.h"

#define CIGI_DEFAULT_PORT 8004        /* CIGI has no registered port; 8004 is the usual IG port */
#define CIGI_BATCH 16                 /* datagrams per recvmmsg */
#define CIGI_SERVICE_MAX 1024         /* datagrams per service call, at most */
#define CIGI_EVENTS_MAX 2048          /* the event queue */
#define CIGI_EFFECTS_MAX 64           /* cigi.effects entries */
#define CIGI_EFFECT_NAME_MAX 64
#define CIGI_OWNSHIP 0                /* the entity the eyepoint rides on */
#define CIGI_ANY_VIEW (-1)

/* The scene's cigi.effects: { entity_type = N; effect = "NAME"; } (cigi_config.h) */
struct cigi_effect_rule {
    uint16_t entity_type;
    char effect[CIGI_EFFECT_NAME_MAX];
};

struct cigi_effect_map {
    struct cigi_effect_rule rules[CIGI_EFFECTS_MAX];
    int count;
};

/* What the flags, the board and the scene say (the player merges them). */
struct cigi_settings {
    struct udp_endpoint listen;       /* --cigi [ADDR:]PORT */
    char interface[IF_NAMESIZE];      /* multicast join: "" for the kernel's choice */
    bool have_host;
    struct udp_endpoint host;         /* --cigi-host ADDR:PORT: where Start of Frame goes; without
                                         it, to the sender of the last IG Control */
    bool have_origin;
    double origin[3];                 /* dis.origin: latitude, longitude (degrees), height (m) */
    int view_id;                      /* this channel's view ID, or CIGI_ANY_VIEW */
    struct cigi_effect_map effects;
};

enum cigi_event_kind {
    CIGI_EVENT_FRAME,
    CIGI_EVENT_EFFECT_START,
    CIGI_EVENT_EFFECT_STOP,
    CIGI_EVENT_OWNSHIP,
    CIGI_EVENT_VIEW_DEFINITION,
    CIGI_EVENT_VIEW_CONTROL,
};

enum cigi_stop_reason { CIGI_STOP_DESTROYED, CIGI_STOP_INACTIVE, CIGI_STOP_ANIMATION };

/* The host's time of the message an event came in. */
struct cigi_time {
    uint32_t host_frame;
    uint32_t timestamp;               /* 10 µs ticks, as sent (wraps after 11.9 hours) */
    bool timestamp_valid;
    double seconds;                   /* the timestamp unwrapped (wraps counted), in seconds */
};

struct cigi_frame {
    int8_t database;
    uint8_t ig_mode;
    uint8_t minor_version;
    bool little_endian;
};

struct cigi_effect {
    uint16_t entity_id, entity_type;
    uint32_t generation;              /* 1, 2, ... activations of this entity ID heard */
    uint32_t activation_frame;        /* the host frame it went active in */
    uint64_t identity;                /* 2^62 + entity ID x 2^32 + activation_frame */
    char effect[CIGI_EFFECT_NAME_MAX];/* the cigi.effects name */
    float position[3];                /* scene metres from dis.origin: x east, y up, z south */
    double geodetic[3];               /* latitude, longitude (degrees), altitude (m), as sent */
    float roll, pitch, yaw;           /* degrees, as sent */
    enum cigi_stop_reason reason;     /* EFFECT_STOP */
};

struct cigi_pose {
    uint16_t entity_id;
    float position[3];                /* scene metres from dis.origin */
    double geodetic[3];
    float roll, pitch, yaw;           /* degrees: yaw from true north, clockwise; pitch up; roll right */
};

struct cigi_event {
    enum cigi_event_kind kind;
    int64_t received_ns;              /* the now_ns of the service call that read it */
    struct cigi_time time;
    union {
        struct cigi_frame frame;                          /* FRAME */
        struct cigi_effect effect;                        /* EFFECT_START, EFFECT_STOP */
        struct cigi_pose ownship;                         /* OWNSHIP */
        struct cigi_view_definition view_definition;      /* VIEW_DEFINITION */
        struct cigi_view_control view_control;            /* VIEW_CONTROL */
    };
};

enum cigi_ignore_reason { CIGI_IGNORED_TYPE, CIGI_IGNORED_NOT_EFFECT, CIGI_IGNORED_ATTACHED,
                          CIGI_IGNORED_VIEW, CIGI_IGNORED_COUNT };

struct cigi_counts {
    uint64_t messages;                /* datagrams read: --stats cigi_messages */
    uint64_t packets, used, ignored, malformed;          /* cigi_ignored, cigi_malformed */
    uint64_t entities;                /* effect starts: cigi_entities */
    uint64_t stops;
    uint64_t active;                  /* effect entities running now */
    uint64_t events_dropped;          /* events the queue had no room for (only when
                                         cigi_receiver_datagram is called with the queue full) */
    uint64_t sof_sent, sof_failed, sof_unaddressed;     /* the last: no host known yet */
    uint64_t ignored_by[CIGI_IGNORED_COUNT];
    uint64_t malformed_by[CIGI_STATUS_COUNT];
};

/* What the player fills in for Start of Frame; the receiver adds the database number and IG mode
 * the host asked for, the last host frame number and the host's byte order. */
struct cigi_sof_info {
    uint32_t ig_frame;                /* the IG's frame counter */
    uint32_t timestamp;               /* the IG's time, 10 µs ticks */
    bool timestamp_valid;
    uint8_t ig_status;                /* 0: normal */
};

typedef void (*cigi_log_fn)(const char *message, void *user);

struct cigi_receiver;

/* Opens the socket (settings->listen) and makes the receiver; settings must have an origin. */
int cigi_receiver_open(struct cigi_receiver **out, const struct cigi_settings *settings, char *err, size_t n);
/* Without a socket (tests, the fuzzer): cigi_receiver_datagram only; Start of Frame is encoded
 * but not sent (cigi_receiver_last_sof). */
int cigi_receiver_make(struct cigi_receiver **out, const struct cigi_settings *settings, char *err, size_t n);
void cigi_receiver_close(struct cigi_receiver *r);
/* Where problems are said (NULL: nowhere). */
void cigi_receiver_set_log(struct cigi_receiver *r, cigi_log_fn log, void *user);
/* New origin, effects and view (a reloaded scene); the socket, the entities, the queue and the
 * counts stay: running effects end as the host says, not at a reload. */
void cigi_receiver_configure(struct cigi_receiver *r, const struct cigi_settings *settings);
int cigi_receiver_fd(const struct cigi_receiver *r);
/* Reads what waits on the socket (never blocks): the datagrams read, or a negative errno. */
int cigi_receiver_service(struct cigi_receiver *r, int64_t now_ns);
/* One datagram (truncated: it was longer than CIGI_MAX_MESSAGE; from: its sender, or NULL). */
void cigi_receiver_datagram(struct cigi_receiver *r, const uint8_t *data, size_t length, bool truncated,
                            const struct sockaddr_in *from, int64_t now_ns);
/* The oldest event waiting, into *out: false when none waits. */
bool cigi_receiver_next(struct cigi_receiver *r, struct cigi_event *out);
int cigi_receiver_pending(const struct cigi_receiver *r);
/* Start of Frame to --cigi-host, else to the sender of the last IG Control: 1 sent, 0 no host
 * known yet (counted), or a negative errno with err (counted; the next frame tries again). */
int cigi_receiver_send_sof(struct cigi_receiver *r, const struct cigi_sof_info *info, char *err, size_t n);
/* The last Start of Frame encoded (tests): its bytes, CIGI_START_OF_FRAME_SIZE of them. */
const uint8_t *cigi_receiver_last_sof(const struct cigi_receiver *r);
const struct cigi_counts *cigi_receiver_counts(const struct cigi_receiver *r);
/* "another packet type", "attached to a parent"... for logs. */
const char *cigi_ignore_name(enum cigi_ignore_reason reason);

#endif
