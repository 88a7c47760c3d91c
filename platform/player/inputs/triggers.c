/* The run's trigger sources (inputs.h): a list the frame loop polls and services as one, and
 * the queue they share. */
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

void trigger_sources_service(struct trigger_sources *all, const sbfx *fx, int64_t now_ns)
{
    for (int i = 0; i < all->count; i++) all->list[i]->ops->service(all->list[i], &all->queue, fx, now_ns);
}

int trigger_sources_fire(struct trigger_sources *all, sbfx *fx, int64_t now_ns)
{
    trigger_sources_service(all, fx, now_ns);
    return trigger_queue_fire(&all->queue, fx);
}

void trigger_sources_listen(struct trigger_sources *all, sbfx *fx)
{
    sbfx_set_trigger_listener(fx, trigger_queue_listen, &all->queue);
}

void trigger_sources_reload(struct trigger_sources *all, const sbfx *fx)
{
    for (int i = 0; i < all->count; i++)
        if (all->list[i]->ops->reload) all->list[i]->ops->reload(all->list[i], fx);
}

bool trigger_sources_realtime(const struct trigger_sources *all)
{
    for (int i = 0; i < all->count; i++)
        if (all->list[i]->realtime) return true;
    return false;
}

void trigger_sources_close(struct trigger_sources *all)
{
    for (int i = 0; i < all->count; i++) all->list[i]->ops->close(all->list[i]);
    all->count = 0;
}
