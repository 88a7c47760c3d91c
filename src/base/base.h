/* The ground floor of src/ (src/rooms.txt; docs/hacking.md has the map): what every room may
 * use and which uses nothing of theirs, the way libcamera's base/ does.
 *
 * Exports to the rooms above:
 *   - errors and logging (log.c): sbfx_fail keeps a message as the module's last error and sends
 *     it to the host's log callback, sbfx_log logs; no room calls back into sbfx.c to report;
 *   - allocation counting (alloc.c): every heap allocation of the module, so that "nothing
 *     allocated per frame" is a number a test asserts (sbfx_counters.heap_allocs_after_load);
 *   - the deterministic RNG (rng.h) and the FNV-1a hash (hash.h);
 *   - ARRAY_SIZE. */
#ifndef SBFX_BASE_H
#define SBFX_BASE_H

#include <stdarg.h>
#include <stddef.h>
#include "sbfx.h"

#define ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))

/* ---- allocation accounting (alloc.c): every heap allocation of the module goes here ---- */
void *sbfx_calloc(sbfx *fx, size_t count, size_t size);
void sbfx_free(sbfx *fx, void *p);

/* ---- errors and logging (log.c) ---- */
/* Records the message as last error, sends it to the log callback, returns `result`. */
sbfx_result sbfx_fail(sbfx *fx, sbfx_result result, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
void sbfx_log(sbfx *fx, sbfx_log_level level, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

#endif
