/* Camera frames -> detail slices, with the procedural volume as the fallback. */
#include "video/live_detail.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define NS_PER_MS INT64_C(1000000)
#define DEFAULT_TIMEOUT_MS 2000
#define DEFAULT_BACKOFF_MS 250
#define MAX_BACKOFF_FACTOR 16

static void say(struct live_detail *ld, const char *fmt, const char *a, const char *b)
{
    char msg[512];
    snprintf(msg, sizeof(msg), fmt, a, b);
    if (ld->log) ld->log(msg, ld->log_user);
}

static uint64_t hash_slice(const uint16_t *texels, size_t count)
{
    uint64_t h = UINT64_C(1469598103934665603); /* FNV-1a */
    for (size_t i = 0; i < count; i++) {
        h ^= texels[i];
        h *= UINT64_C(1099511628211);
    }
    return h;
}

/* The module's procedural volume as half floats, kept for take-overs. */
static int keep_procedural(struct live_detail *ld, char *err, size_t n)
{
    size_t count = (size_t)ld->size * ld->size * ld->frames;
    float *values = malloc(count * sizeof(*values));
    ld->procedural = malloc(count * sizeof(*ld->procedural));
    int rc = 0;
    if (!values || !ld->procedural) {
        snprintf(err, n, "video: out of memory for a %dx%dx%d detail volume", ld->size, ld->size,
                 ld->frames);
        rc = -ENOMEM;
    } else if (sbfx_detail_procedural(ld->fx, values, count) != SBFX_OK) {
        snprintf(err, n, "video: sbfx_detail_procedural: %s", sbfx_last_error(ld->fx));
        rc = -EINVAL;
    } else {
        for (size_t i = 0; i < count; i++) ld->procedural[i] = luma_half_bits(values[i]);
    }
    free(values);
    return rc;
}

/* Writes the whole procedural volume back through the ring: frames slices, one full turn. */
static int push_procedural(struct live_detail *ld)
{
    size_t slice = (size_t)ld->size * ld->size;
    for (int k = 0; k < ld->frames; k++)
        if (sbfx_detail_push_slice(ld->fx, ld->procedural + (size_t)k * slice, ld->size) != SBFX_OK)
            return -EIO;
    return 0;
}

static void grow_backoff(struct live_detail *ld)
{
    int64_t cap = (int64_t)ld->desc.backoff_ms * MAX_BACKOFF_FACTOR * NS_PER_MS;
    ld->backoff_ns = ld->backoff_ns * 2 < cap ? ld->backoff_ns * 2 : cap;
}

/* The outage goes on: say why once, retry after the back-off, which grows. */
static void wait_retry(struct live_detail *ld, const char *why, const char *what_now, int64_t now_ns)
{
    if (!ld->outage_logged) say(ld, "%s; %s", why, what_now);
    ld->outage_logged = true;
    ld->outage = true;
    ld->state = LIVE_WAITING;
    ld->retry_at_ns = now_ns + ld->backoff_ns;
    grow_backoff(ld);
}

static void try_open(struct live_detail *ld, int64_t now_ns)
{
    char why[384];
    const struct live_detail_desc *d = &ld->desc;
    int rc = v4l2_source_open(&ld->source, d->device, d->width, d->height, why, sizeof(why));
    if (rc == 0)
        rc = luma_resampler_init(&ld->resampler, ld->size, ld->source.width, ld->source.height,
                                 ld->box_values, why, sizeof(why));
    if (rc) {
        v4l2_source_close(&ld->source);
        wait_retry(ld, why, "procedural detail until it works (retrying with back-off)", now_ns);
        return;
    }
    ld->state = LIVE_STREAMING;
    ld->announce = true; /* with the first frame */
    ld->last_frame_ns = now_ns;
}

static int alloc_buffers(struct live_detail *ld, char *err, size_t n)
{
    size_t slice = (size_t)ld->size * ld->size;
    ld->box_values = malloc(slice * sizeof(*ld->box_values));
    ld->slice = malloc(slice * sizeof(*ld->slice));
    if (!ld->box_values || !ld->slice) {
        snprintf(err, n, "video: out of memory for %dx%d detail slices", ld->size, ld->size);
        return -ENOMEM;
    }
    return keep_procedural(ld, err, n);
}

int live_detail_start(struct live_detail *ld, sbfx *fx, const struct live_detail_desc *desc,
                      live_log_fn log, void *user, char *err, size_t n)
{
    memset(ld, 0, sizeof(*ld));
    ld->source.fd = -1;
    ld->desc = *desc;
    if (ld->desc.timeout_ms <= 0) ld->desc.timeout_ms = DEFAULT_TIMEOUT_MS;
    if (ld->desc.backoff_ms <= 0) ld->desc.backoff_ms = DEFAULT_BACKOFF_MS;
    ld->fx = fx;
    ld->log = log;
    ld->log_user = user;
    sbfx_detail_dimensions(fx, &ld->size, &ld->frames);
    if (ld->size < 1 || ld->size > LUMA_MAX_SIZE || ld->frames < 1) {
        snprintf(err, n, "video %s: the detail volume is %dx%dx%d, cannot feed it", desc->device,
                 ld->size, ld->size, ld->frames);
        return -EINVAL;
    }
    int rc = alloc_buffers(ld, err, n);
    if (rc == 0 && push_procedural(ld) != 0) { /* also tells whether there is a volume at all */
        snprintf(err, n, "video %s: cannot feed the detail volume: %s", desc->device,
                 sbfx_last_error(fx));
        rc = -EINVAL;
    }
    if (rc) {
        live_detail_stop(ld);
        return rc;
    }
    ld->backoff_ns = (int64_t)ld->desc.backoff_ms * NS_PER_MS;
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    try_open(ld, (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec);
    return 0;
}

static void lose(struct live_detail *ld, const char *why, int64_t now_ns)
{
    v4l2_source_close(&ld->source);
    if (!ld->outage) {
        ld->counts.losses++;
        ld->backoff_ns = (int64_t)ld->desc.backoff_ms * NS_PER_MS;
    }
    if (ld->feeding && push_procedural(ld) == 0) ld->counts.takeovers++;
    ld->feeding = false;
    wait_retry(ld, why, "procedural detail takes over, reopening with back-off", now_ns);
}

/* The first frame after an open: the camera works (again). */
static void announce(struct live_detail *ld)
{
    char what[128];
    v4l2_source_describe(&ld->source, what, sizeof(what));
    if (!ld->ever_fed) say(ld, "video %s: %s feeds the detail volume", ld->desc.device, what);
    else if (ld->outage) say(ld, "video %s is back: %s feeds the detail volume", ld->desc.device, what);
    if (ld->ever_fed && ld->outage) ld->counts.reopens++;
    ld->announce = false;
    ld->ever_fed = true;
    ld->outage = ld->outage_logged = false;
    ld->backoff_ns = (int64_t)ld->desc.backoff_ms * NS_PER_MS;
}

static void push_frame(struct live_detail *ld, const struct luma_view *view)
{
    if (luma_to_slice(&ld->resampler, view, ld->slice) != 0) return; /* short buffer: skipped */
    size_t count = (size_t)ld->size * ld->size;
    uint64_t h = hash_slice(ld->slice, count);
    if (sbfx_detail_push_slice(ld->fx, ld->slice, ld->size) != SBFX_OK) return;
    if (ld->announce) announce(ld);
    if (ld->counts.frames > 0 && h != ld->last_hash) ld->counts.distinct++;
    ld->last_hash = h;
    ld->counts.frames++;
    ld->feeding = true;
}

static void service_stream(struct live_detail *ld, int64_t now_ns)
{
    char why[384];
    struct luma_view view;
    int rc = v4l2_source_latest(&ld->source, &view, why, sizeof(why));
    if (rc == 1) {
        push_frame(ld, &view);
        ld->last_frame_ns = now_ns;
        rc = v4l2_source_release(&ld->source, why, sizeof(why));
    } else if (rc == 0 && now_ns - ld->last_frame_ns > (int64_t)ld->desc.timeout_ms * NS_PER_MS) {
        snprintf(why, sizeof(why), "video %s: no frame for %d ms", ld->desc.device,
                 ld->desc.timeout_ms);
        rc = -ETIMEDOUT;
    }
    if (rc < 0) lose(ld, why, now_ns);
}

void live_detail_service(struct live_detail *ld, int64_t now_ns)
{
    if (ld->state == LIVE_STREAMING) service_stream(ld, now_ns);
    else if (ld->state == LIVE_WAITING && now_ns >= ld->retry_at_ns) try_open(ld, now_ns);
}

void live_detail_stop(struct live_detail *ld)
{
    v4l2_source_close(&ld->source);
    free(ld->box_values);
    free(ld->slice);
    free(ld->procedural);
    ld->box_values = NULL;
    ld->slice = NULL;
    ld->procedural = NULL;
    ld->state = LIVE_OFF;
}

void live_detail_describe(const struct live_detail *ld, char *out, size_t n)
{
    if (ld->state == LIVE_STREAMING) v4l2_source_describe(&ld->source, out, n);
    else if (ld->state == LIVE_WAITING) snprintf(out, n, "waiting for %s", ld->desc.device);
    else snprintf(out, n, "off");
}
