/* Triggers waiting for the next buffer: from the `trigger` action signal (any thread) and from
 * taps on the sink's window (navigation events, the sink's thread). The streaming thread takes
 * them all at its next buffer and starts them there. A fixed ring: nothing is allocated when a
 * trigger comes; a full ring drops the new one and counts it. The caller locks. */
#ifndef SBFX_GST_PENDING_H
#define SBFX_GST_PENDING_H

#include <stdbool.h>

#define PENDING_MAX 64
#define PENDING_NAME_MAX 64

enum pending_kind {
    PENDING_TRIGGER, /* an effect by name at a world position */
    PENDING_TAP,     /* the scene's first effect where a tap's ray meets the ground */
};

struct pending_entry {
    enum pending_kind kind;
    char effect[PENDING_NAME_MAX]; /* PENDING_TRIGGER */
    float position[3];             /* PENDING_TRIGGER: world; PENDING_TAP: the ground point */
};

struct pending {
    struct pending_entry entries[PENDING_MAX];
    int head, count;
    unsigned dropped;      /* entries refused because the ring was full */
};

/* false (and counted in dropped) when the ring is full. */
bool pending_push(struct pending *p, const struct pending_entry *e);
/* The oldest entry into *out; false when there is none. */
bool pending_pop(struct pending *p, struct pending_entry *out);

#endif
