/* The table of recent event IDs (dis_events.h). */
#include "net/dis/dis_events.h"

#include <string.h>

void dis_events_init(struct dis_events *e)
{
    memset(e, 0, sizeof(*e));
}

static uint32_t hash(const struct dis_entity_id *id)
{
    uint64_t key = (uint64_t)id->site << 32 | (uint64_t)id->application << 16 | id->entity;
    key *= UINT64_C(0x9E3779B97F4A7C15); /* Fibonacci hashing: the high bits are well mixed */
    return (uint32_t)(key >> 40);
}

static bool same(const struct dis_entity_id *a, const struct dis_entity_id *b)
{
    return a->site == b->site && a->application == b->application && a->entity == b->entity;
}

bool dis_events_repeat(struct dis_events *e, const struct dis_entity_id *event, int64_t now_ns)
{
    if (event->entity == 0) return false;
    uint32_t start = hash(event);
    struct dis_event_slot *free_slot = NULL, *oldest = NULL;
    for (uint32_t i = 0; i < DIS_EVENT_PROBE; i++) {
        struct dis_event_slot *s = &e->slots[(start + i) % DIS_EVENT_SLOTS];
        bool live = s->used && now_ns - s->seen_ns < DIS_EVENT_WINDOW_NS && now_ns >= s->seen_ns;
        if (live && same(&s->id, event)) return true;
        if (!live && !free_slot) free_slot = s;
        if (!oldest || s->seen_ns < oldest->seen_ns) oldest = s;
    }
    struct dis_event_slot *s = free_slot ? free_slot : oldest;
    *s = (struct dis_event_slot){*event, now_ns, true};
    return false;
}
