/* Effect entities' starts and stops (cigi_entities.h). */
#include "net/cigi/cigi_entities.h"

#include <string.h>

const char *cigi_effect_find(const struct cigi_effect_map *m, uint16_t entity_type)
{
    for (int i = 0; i < m->count; i++)
        if (m->rules[i].entity_type == entity_type) return m->rules[i].effect;
    return NULL;
}

void cigi_entities_reset(struct cigi_entities *t)
{
    memset(t, 0, sizeof(*t));
}

static bool playing(uint8_t animation)
{
    return animation == CIGI_ANIMATION_PLAY || animation == CIGI_ANIMATION_CONTINUE;
}

enum cigi_change cigi_entity_decide(const struct cigi_entities *t, const struct cigi_entity_control *e,
                                    enum cigi_stop_reason *reason)
{
    const struct cigi_entity_slot *s = &t->slot[e->entity_id];
    if (e->state != CIGI_ENTITY_ACTIVE) {
        *reason = e->state == CIGI_ENTITY_INACTIVE ? CIGI_STOP_INACTIVE : CIGI_STOP_DESTROYED;
        return s->running ? CIGI_CHANGE_STOP : CIGI_CHANGE_NONE;
    }
    if (s->running) {
        *reason = CIGI_STOP_ANIMATION;
        return e->animation == CIGI_ANIMATION_STOP && s->played ? CIGI_CHANGE_STOP : CIGI_CHANGE_NONE;
    }
    return !s->stopped_by_animation || playing(e->animation) ? CIGI_CHANGE_START : CIGI_CHANGE_NONE;
}

void cigi_entity_apply(struct cigi_entities *t, const struct cigi_entity_control *e, enum cigi_change change,
                       uint32_t host_frame)
{
    struct cigi_entity_slot *s = &t->slot[e->entity_id];
    if (change == CIGI_CHANGE_START) {
        s->running = true;
        s->played = false;
        s->stopped_by_animation = false;
        s->entity_type = e->entity_type;
        s->generation++;
        s->activation_frame = host_frame;
        t->running++;
    } else if (change == CIGI_CHANGE_STOP) {
        s->running = false;
        s->stopped_by_animation = e->state == CIGI_ENTITY_ACTIVE;
        t->running--;
    } else if (e->state != CIGI_ENTITY_ACTIVE) {
        s->stopped_by_animation = false; /* off already; the next Active starts it */
    }
    if (s->running && playing(e->animation)) s->played = true;
}

const struct cigi_entity_slot *cigi_entity_slot(const struct cigi_entities *t, uint16_t entity_id)
{
    return &t->slot[entity_id];
}
