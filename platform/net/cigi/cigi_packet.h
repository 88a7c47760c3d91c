/* CIGI 3.3 (SISO-STD-013, the Common Image Generator Interface) packets on the image
 * generator's side: the host's messages parsed, the IG's Start of Frame encoded. Pure functions
 * over a byte buffer: no allocation, no I/O; fuzzed (tests/fuzz/fuzz_cigi.c, make fuzz).
 *
 * A message is one UDP datagram: packets one after the other, each starting with its packet ID
 * (byte 0) and its size in bytes (byte 1). The first packet of a host's message is IG Control,
 * whose byte-swap magic (0x8000 at bytes 6-7) gives the byte order of every multi-byte field of
 * the message: read as 0x8000 it is big-endian, as 0x0080 little-endian. Offsets in bytes:
 *
 * IG Control (1, 24 bytes)
 *     2  CIGI version u8 (3)         3  database number s8
 *     4  IG mode bits 0-1 (0 reset/standby, 1 operate, 2 debug, 3 offline maintenance),
 *        timestamp valid bit 2, extrapolation/interpolation enable bit 3, minor version bits 4-7
 *     6  byte-swap magic u16         8  host frame number u32
 *    12  timestamp u32 (10 µs ticks)  16  last IG frame number u32     20  reserved
 * Entity Control (2, 48 bytes)
 *     2  entity ID u16
 *     4  entity state bits 0-1 (0 inactive/standby, 1 active, 2 destroyed), attach state bit 2,
 *        collision detection bit 3, inherit alpha bit 4, ground/ocean clamp bits 5-6
 *     5  animation direction bit 0, loop mode bit 1, animation state bits 2-3 (0 stop,
 *        1 pause, 2 play, 3 continue), extrapolation/interpolation enable bit 4
 *     6  alpha u8                    8  entity type u16               10  parent ID u16
 *    12  roll f32   16  pitch f32   20  yaw f32 (degrees)
 *    24  latitude f64 (degrees) / x offset (m)      32  longitude f64 / y offset
 *    40  altitude f64 (m) / z offset (offsets when attached to a parent)
 * View Control (16, 32 bytes)
 *     2  view ID u16    4  group ID u8    5  enable bits 0-5: x, y, z, roll, pitch, yaw
 *     6  entity ID u16  8  x, y, z offsets f32 (m; x forward, y right, z down)
 *    20  roll, pitch, yaw f32 (degrees)
 * View Definition (21, 32 bytes)
 *     2  view ID u16    4  group ID u8
 *     5  enable bits 0-5: near, far, left, right, top, bottom; mirror mode bits 6-7
 *     6  pixel replication bits 0-2, projection type bit 3 (0 perspective, 1 orthographic),
 *        reorder bit 4, view type bits 5-7
 *     8  near f32, far f32 (m)   16  left f32, right f32, top f32, bottom f32 (degrees from the
 *        view axis: left and bottom negative)
 * Start of Frame (101, 24 bytes; IG to host)
 *     2  CIGI version u8 (3)         3  database number s8            4  IG status u8
 *     5  IG mode bits 0-1, timestamp valid bit 2, earth reference model bit 3 (0 WGS-84),
 *        minor version bits 4-7 (3)
 *     6  byte-swap magic u16         8  IG frame number u32
 *    12  timestamp u32 (10 µs ticks)  16  last host frame number u32   20  reserved
 * Every other packet is well-formed as long as its size byte fits the message: it is skipped by
 * that size. */
#ifndef SBFX_CIGI_PACKET_H
#define SBFX_CIGI_PACKET_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define CIGI_VERSION 3
#define CIGI_MINOR_VERSION 3
#define CIGI_BYTE_SWAP_MAGIC 0x8000u
#define CIGI_MAX_MESSAGE 8192          /* the largest message (datagram) taken */
#define CIGI_DISTANCE_MAX 1e7          /* m: altitudes, offsets, near and far (beyond: malformed) */

#define CIGI_IG_CONTROL 1
#define CIGI_ENTITY_CONTROL 2
#define CIGI_VIEW_CONTROL 16
#define CIGI_VIEW_DEFINITION 21
#define CIGI_START_OF_FRAME 101

#define CIGI_IG_CONTROL_SIZE 24
#define CIGI_ENTITY_CONTROL_SIZE 48
#define CIGI_VIEW_CONTROL_SIZE 32
#define CIGI_VIEW_DEFINITION_SIZE 32
#define CIGI_START_OF_FRAME_SIZE 24

enum cigi_status {
    CIGI_PACKET,          /* a well-formed packet this parser reads (the four above) */
    CIGI_OTHER,           /* a well-formed packet of another type, skipped by its size */
    CIGI_TRUNCATED,       /* fewer bytes left than a packet's first two, or than its size byte */
    CIGI_BAD_SIZE,        /* a size byte under 2, or a read packet's other than the standard's */
    CIGI_NO_IG_CONTROL,   /* a message whose first packet is not IG Control */
    CIGI_BAD_VERSION,     /* IG Control's CIGI version is not 3 */
    CIGI_BAD_MAGIC,       /* IG Control's byte-swap magic is neither 0x8000 nor 0x0080 */
    CIGI_BAD_VALUE,       /* a position, angle or distance that is not a finite number or is out of
                             its range (latitude -90..90, longitude -180..180, angles -360..360,
                             altitudes, offsets and distances within CIGI_DISTANCE_MAX; a view's
                             half-angles within ±90, left under right and bottom under top) */
    CIGI_OVERSIZED,       /* a message over CIGI_MAX_MESSAGE (the receiver's finding) */
    CIGI_STATUS_COUNT
};

enum cigi_entity_state { CIGI_ENTITY_INACTIVE = 0, CIGI_ENTITY_ACTIVE = 1, CIGI_ENTITY_DESTROYED = 2 };
enum cigi_animation { CIGI_ANIMATION_STOP = 0, CIGI_ANIMATION_PAUSE = 1, CIGI_ANIMATION_PLAY = 2,
                      CIGI_ANIMATION_CONTINUE = 3 };

/* View Control's enable bits, and View Definition's */
enum { CIGI_VIEW_X = 1, CIGI_VIEW_Y = 2, CIGI_VIEW_Z = 4, CIGI_VIEW_ROLL = 8, CIGI_VIEW_PITCH = 16,
       CIGI_VIEW_YAW = 32 };
enum { CIGI_FOV_NEAR = 1, CIGI_FOV_FAR = 2, CIGI_FOV_LEFT = 4, CIGI_FOV_RIGHT = 8, CIGI_FOV_TOP = 16,
       CIGI_FOV_BOTTOM = 32 };

struct cigi_ig_control {
    uint8_t version, minor_version;
    int8_t database;
    uint8_t ig_mode;                 /* 0 reset/standby, 1 operate, 2 debug, 3 offline maintenance */
    bool timestamp_valid, extrapolation;
    uint32_t host_frame;
    uint32_t timestamp;              /* 10 µs ticks */
    uint32_t last_ig_frame;
};

struct cigi_entity_control {
    uint16_t entity_id, entity_type, parent_id;
    uint8_t state;                   /* enum cigi_entity_state (3 is read as it is: not active) */
    bool attached, collision_detection, inherit_alpha;
    uint8_t clamp;                   /* 0 none, 1 non-conformal, 2 conformal */
    bool animation_backward, animation_loop;
    uint8_t animation;               /* enum cigi_animation */
    bool extrapolation;
    uint8_t alpha;
    float roll, pitch, yaw;          /* degrees */
    double position[3];              /* latitude, longitude (degrees), altitude (m, WGS-84); x, y, z
                                        offsets (m) from the parent when attached */
};

struct cigi_view_control {
    uint16_t view_id, entity_id;
    uint8_t group_id;                /* 0: this view alone; else every view of the group */
    uint8_t enable;                  /* CIGI_VIEW_* */
    float offset[3];                 /* x forward, y right, z down from the entity (m) */
    float roll, pitch, yaw;          /* degrees */
};

struct cigi_view_definition {
    uint16_t view_id;
    uint8_t group_id;
    uint8_t enable;                  /* CIGI_FOV_*: only enabled fields are to be applied */
    uint8_t mirror, pixel_replication, view_type;
    bool orthographic, reorder;
    float near_m, far_m;
    float left, right, top, bottom;  /* degrees from the view axis (left, bottom negative) */
};

struct cigi_packet {
    uint8_t id, size;
    union {
        struct cigi_ig_control ig_control;
        struct cigi_entity_control entity;
        struct cigi_view_control view_control;
        struct cigi_view_definition view_definition;
    };
};

/* The packets of one message, in order. */
struct cigi_message {
    const uint8_t *data;
    size_t len, at;
    bool little_endian;              /* from the IG Control's magic, once read */
    bool stopped;                    /* the rest cannot be delimited, or its byte order is unknown */
};

void cigi_message_init(struct cigi_message *m, const uint8_t *data, size_t len);
/* The next packet and its status: false at the end of the message. A malformed first packet (no
 * IG Control, a bad version or magic), a size byte under 2 or a truncated packet ends the
 * message there; any other malformed packet is skipped by its size. */
bool cigi_message_next(struct cigi_message *m, struct cigi_packet *out, enum cigi_status *status);

struct cigi_start_of_frame {
    int8_t database;
    uint8_t ig_status;               /* 0: normal */
    uint8_t ig_mode;                 /* 0 reset/standby, 1 operate, 2 debug */
    bool timestamp_valid;
    uint32_t ig_frame, timestamp, last_host_frame;
};

/* Start of Frame in the byte order asked for (CIGI version 3, minor version 3, WGS-84): returns
 * CIGI_START_OF_FRAME_SIZE. */
size_t cigi_sof_encode(const struct cigi_start_of_frame *sof, bool little_endian,
                       uint8_t out[CIGI_START_OF_FRAME_SIZE]);
/* A Start of Frame packet back into its fields (tests; an IG's reply read by a host): 0, or the
 * status that says what is wrong with it; *little_endian from its magic. */
enum cigi_status cigi_sof_decode(const uint8_t *buf, size_t len, struct cigi_start_of_frame *out,
                                 bool *little_endian);

/* "truncated", "no IG Control first"... for logs. */
const char *cigi_status_name(enum cigi_status status);
/* A malformed packet: one to count and drop. */
bool cigi_status_malformed(enum cigi_status status);

#endif
