/* sbfx-soak's records and its flatness check (README "Kiosk months").
 *
 * A soak run samples the process and the modules every N frames. After the warm-up (the first
 * `warmup` fraction of the samples: Mesa compiles and caches on first use), what sbfx holds
 * must not move at all (GL programs, textures, framebuffers, GPU bytes, heap allocations after
 * load, and the GL textures, framebuffers and buffers alive in the whole context: a leak by
 * anyone sharing the context moves those), and
 * the process's anonymous resident memory and malloc'ed bytes may only wander within a tolerance
 * (file-backed pages are library code paged in the first time a path runs, not a leak): the
 * mean of the last quarter of the samples against the mean of the first quarter after warm-up.
 * The run must also have done something: triggers fired, particles alive, and the simulated
 * time must be frames x dt (a large frame time is not cut short by the fixed-step simulation).
 * Pure logic, no GL: tests/platform/test_soak_check.c feeds it series. */
#ifndef SBFX_SOAK_CHECK_H
#define SBFX_SOAK_CHECK_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

struct soak_sample {
    int64_t frames;
    double sim_seconds;       /* sbfx_elapsed() of the modules */
    double wall_seconds;
    int64_t rss_kib;          /* /proc/self/status VmRSS ... */
    int64_t rss_anon_kib;     /* ... = RssAnon (checked) */
    int64_t rss_file_kib;     /* ... + RssFile (library code paged in: recorded, not checked) */
    int64_t heap_bytes;       /* malloc'ed bytes in use (mallinfo2 uordblks + hblkhd) */
    int64_t programs, textures, framebuffers, gpu_bytes, heap_allocs; /* sbfx_stats, summed */
    int64_t gl_textures, gl_framebuffers, gl_buffers; /* alive in the whole context (glIs*) */
    int64_t particles_alive, triggers_fired, triggers_refused;
};

struct soak_limits {
    double warmup;            /* fraction of the samples ignored at the start (0.25) */
    int64_t rss_kib;          /* anonymous resident memory may grow this much (4096) */
    int64_t heap_bytes;       /* malloc'ed bytes may grow this much (2 MiB: glibc moves in 1 MiB steps) */
    double dt;                /* seconds per frame: sim_seconds must be frames x dt ... */
    double step;              /* ... within one simulation step */
};

void soak_limits_default(struct soak_limits *lim);

/* The CSV header and one line per sample (no allocation). */
void soak_write_header(FILE *f);
void soak_write_sample(FILE *f, const struct soak_sample *s);

/* Checks the series; returns the number of problems, each one line in report ("textures grew
 * from 12 to 13 (+1) after warm-up", "rss_kib grew by 9120 KiB (tolerance 4096) ..."), and a
 * summary line of what was measured (RSS before and after, slope per simulated hour). */
int soak_check(const struct soak_sample *s, int count, const struct soak_limits *lim, char *report, size_t n);

#endif
