/* Debounce (quiet time before an edge) and rate limit (time since the last fire) per line. */
#include "gpio/trigger_filter.h"

#include <string.h>

#define NS_PER_MS INT64_C(1000000)

void trigger_filter_init(struct trigger_filter *f, int debounce_ms, int min_interval_ms)
{
    memset(f, 0, sizeof(*f));
    f->debounce_ns = (debounce_ms > 0 ? debounce_ms : 0) * NS_PER_MS;
    f->min_interval_ns = (min_interval_ms > 0 ? min_interval_ms : 0) * NS_PER_MS;
}

bool trigger_filter_edge(struct trigger_filter *f, int64_t t_ns)
{
    if (f->seen_edge && t_ns < f->last_edge_ns) t_ns = f->last_edge_ns;
    bool quiet = !f->seen_edge || t_ns - f->last_edge_ns >= f->debounce_ns;
    bool rested = !f->fired || t_ns - f->last_fire_ns >= f->min_interval_ns;
    f->seen_edge = true;
    f->last_edge_ns = t_ns;
    f->edges++;
    if (!quiet || !rested) return false;
    f->fired = true;
    f->last_fire_ns = t_ns;
    f->fires++;
    return true;
}

void trigger_filter_busy_until(struct trigger_filter *f, int64_t now_ns)
{
    if (!f->seen_edge || now_ns > f->last_edge_ns) f->last_edge_ns = now_ns;
    f->seen_edge = true;
}
