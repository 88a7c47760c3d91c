/* The ring of waiting triggers (pending.h). */
#include "pending.h"

bool pending_push(struct pending *p, const struct pending_entry *e)
{
    if (p->count == PENDING_MAX) {
        p->dropped++;
        return false;
    }
    p->entries[(p->head + p->count) % PENDING_MAX] = *e;
    p->count++;
    return true;
}

bool pending_pop(struct pending *p, struct pending_entry *out)
{
    if (p->count == 0) return false;
    *out = p->entries[p->head];
    p->head = (p->head + 1) % PENDING_MAX;
    p->count--;
    return true;
}
