/* The run's trigger sources (inputs.h): a list the frame loop polls and services as one. */
#include <errno.h>
#include <stdio.h>

#include "player/inputs/inputs.h"

int trigger_sources_add(struct trigger_sources *all, struct trigger_source *s, char *err, size_t n)
{
    if (all->count == TRIGGER_SOURCES_MAX) {
        snprintf(err, n, "%s: more than %d trigger sources", s->name, TRIGGER_SOURCES_MAX);
        return -ENOSPC;
    }
    all->list[all->count++] = s;
    return 0;
}

int trigger_sources_pollfds(const struct trigger_sources *all, struct pollfd *fds, int max)
{
    int count = 0;
    for (int i = 0; i < all->count && count < max; i++)
        count += all->list[i]->ops->pollfds(all->list[i], fds + count, max - count);
    return count;
}

void trigger_sources_service(struct trigger_sources *all, sbfx *fx, int64_t now_ns)
{
    for (int i = 0; i < all->count; i++) all->list[i]->ops->service(all->list[i], fx, now_ns);
}

void trigger_sources_close(struct trigger_sources *all)
{
    for (int i = 0; i < all->count; i++) all->list[i]->ops->close(all->list[i]);
    all->count = 0;
}
