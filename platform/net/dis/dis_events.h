/* Repeated detonations: a simulation may send a Detonation PDU more than once (a relay, a
 * bridge between networks, a sender that repeats for reliability), and an image generator must
 * show it once. A detonation whose event ID (site, application, event number) was seen within
 * the last DIS_EVENT_WINDOW_NS is a repeat. Event number 0 means "no event" (a detonation with
 * no Fire PDU before it may carry it) and is never a repeat.
 *
 * A fixed open-addressed table, nothing allocated: each ID hashes to a slot and the probe looks
 * at DIS_EVENT_PROBE slots; an entry older than the window is free. With more than
 * DIS_EVENT_SLOTS / DIS_EVENT_PROBE distinct events a second the oldest of the probed slots
 * is overwritten, and a repeat of it would be taken as new. Pure logic, no I/O. */
#ifndef SBFX_DIS_EVENTS_H
#define SBFX_DIS_EVENTS_H

#include <stdbool.h>
#include <stdint.h>

#include "net/dis/dis_pdu.h"

#define DIS_EVENT_SLOTS 4096
#define DIS_EVENT_PROBE 16
#define DIS_EVENT_WINDOW_NS INT64_C(1000000000)

struct dis_event_slot {
    struct dis_entity_id id;
    int64_t seen_ns;
    bool used;
};

struct dis_events {
    struct dis_event_slot slots[DIS_EVENT_SLOTS];
};

void dis_events_init(struct dis_events *e);
/* True when the event was seen within the window before now_ns (a repeat); else notes it. */
bool dis_events_repeat(struct dis_events *e, const struct dis_entity_id *event, int64_t now_ns);

#endif
