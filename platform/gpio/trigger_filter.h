/* Debounce and rate limit of one GPIO trigger line: a bouncing switch fires one effect.
 *
 * An edge fires when both hold:
 *   - debounce: the line was quiet (no edge at all, fired or not) for debounce_ms before it;
 *   - rate limit: at least min_interval_ms passed since the line last fired.
 * So contact bounce (edges a few ms apart) and a storm of edges (1000 in a second) fire once,
 * at their first edge, and the next clean press fires again.
 *
 * Time is in nanoseconds of CLOCK_MONOTONIC (the kernel's GPIO event timestamps). The kernel
 * keeps only a small FIFO of events per line and drops what does not fit; a read that came
 * back full may hide dropped edges, so trigger_filter_busy_until() then marks the line as
 * active up to the time of the read, and a gap of dropped edges does not look quiet.
 * Pure logic, no I/O: tests drive it with made-up timelines. */
#ifndef SBFX_TRIGGER_FILTER_H
#define SBFX_TRIGGER_FILTER_H

#include <stdbool.h>
#include <stdint.h>

struct trigger_filter {
    int64_t debounce_ns, min_interval_ns;
    int64_t last_edge_ns, last_fire_ns;
    bool seen_edge, fired;
    uint64_t edges, fires; /* counted since init */
};

void trigger_filter_init(struct trigger_filter *f, int debounce_ms, int min_interval_ms);
/* One edge at t_ns: true when it fires. Edges must come in time order; one that does not
 * (a clock step) is taken as happening at the last edge's time. */
bool trigger_filter_edge(struct trigger_filter *f, int64_t t_ns);
/* The line counts as active (not quiet) up to now_ns. */
void trigger_filter_busy_until(struct trigger_filter *f, int64_t now_ns);

#endif
