/* Which Entity Control starts or stops an effect: the scene's cigi.effects (entity type ->
 * effect name) and a table of every entity ID's state, one slot per ID (65,536 of them, made
 * once). Pure logic, no I/O.
 *
 * An effect entity (its type in cigi.effects, not attached to a parent) starts when it goes
 * Active: on the first Active heard for its ID, after Inactive or Destroyed, or when its
 * animation is played again (Play or Continue) after the host stopped it. It stops when it is
 * Destroyed, goes Inactive, or its animation goes to Stop after having played. An entity whose
 * animation was never played (a host that leaves the animation state at 0, Stop) runs from
 * Active to Destroyed. The type is the activation's: a later change of type is not followed
 * until the next activation. */
#ifndef SBFX_CIGI_ENTITIES_H
#define SBFX_CIGI_ENTITIES_H

#include <stdbool.h>
#include <stdint.h>

#include "net/cigi/cigi_packet.h"
#include "net/cigi/cigi_receiver.h"

#define CIGI_ENTITY_IDS 65536

struct cigi_entity_slot {
    bool running;              /* the effect is on */
    bool played;               /* its animation has played since it started */
    bool stopped_by_animation; /* the host stopped its animation: Active, but off until played */
    uint16_t entity_type;
    uint32_t generation;       /* activations heard */
    uint32_t activation_frame;
};

struct cigi_entities {
    struct cigi_entity_slot slot[CIGI_ENTITY_IDS];
    uint64_t running;
};

enum cigi_change { CIGI_CHANGE_NONE, CIGI_CHANGE_START, CIGI_CHANGE_STOP };

/* The effect for an entity type: its name, or NULL when the type is no effect. */
const char *cigi_effect_find(const struct cigi_effect_map *m, uint16_t entity_type);

void cigi_entities_reset(struct cigi_entities *t);
/* What this Entity Control (of an effect entity) does to its slot, without doing it; *reason for
 * a stop. */
enum cigi_change cigi_entity_decide(const struct cigi_entities *t, const struct cigi_entity_control *e,
                                    enum cigi_stop_reason *reason);
/* Does it: the slot afterwards (a start counts a generation and keeps host_frame). */
void cigi_entity_apply(struct cigi_entities *t, const struct cigi_entity_control *e, enum cigi_change change,
                       uint32_t host_frame);
/* An entity ID's slot (a running one stops as the host says, even when a reloaded scene no
 * longer names its type). */
const struct cigi_entity_slot *cigi_entity_slot(const struct cigi_entities *t, uint16_t entity_id);

#endif
