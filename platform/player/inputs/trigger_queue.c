/* The one trigger path (trigger_queue.h). */
#include "player/inputs/trigger_queue.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void trigger_queue_init(struct trigger_queue *q) { memset(q, 0, sizeof(*q)); }

void trigger_queue_limit(struct trigger_queue *q, enum trigger_kind kind, int min_interval_ms)
{
    q->min_interval_ms[kind] = min_interval_ms > 0 ? min_interval_ms : 0;
}

/* The rate limit of a kind's effect; a table that is full lets the effect through unlimited. */
static bool rate_allows(struct trigger_queue *q, enum trigger_kind kind, const char *effect, int64_t now_ns)
{
    if (!q->min_interval_ms[kind]) return true;
    for (int i = 0; i < q->limit_count; i++)
        if (q->limits[i].kind == kind && strcmp(q->limits[i].effect, effect) == 0)
            return trigger_filter_edge(&q->limits[i].filter, now_ns);
    if (q->limit_count == TRIGGER_LIMITS_MAX) return true;
    struct trigger_limit *l = &q->limits[q->limit_count++];
    l->kind = kind;
    snprintf(l->effect, sizeof(l->effect), "%s", effect);
    trigger_filter_init(&l->filter, 0, q->min_interval_ms[kind]);
    return trigger_filter_edge(&l->filter, now_ns);
}

bool trigger_queue_push(struct trigger_queue *q, enum trigger_kind kind, const char *effect, const float position[3],
                        int64_t now_ns)
{
    return trigger_queue_push_identified(q, kind, effect, position, 0, NAN, now_ns);
}

bool trigger_queue_push_identified(struct trigger_queue *q, enum trigger_kind kind, const char *effect,
                                   const float position[3], uint64_t identity, double start, int64_t now_ns)
{
    if (q->count == TRIGGER_QUEUE_MAX) {
        q->full[kind]++;
        return false;
    }
    if (!rate_allows(q, kind, effect, now_ns)) {
        q->limited[kind]++;
        return false;
    }
    struct trigger_request *r = &q->pending[q->count++];
    r->kind = kind;
    snprintf(r->effect, sizeof(r->effect), "%s", effect);
    memcpy(r->position, position, sizeof(r->position));
    r->identity = identity;
    r->start = start;
    return true;
}

bool trigger_queue_push_stop(struct trigger_queue *q, enum trigger_kind kind, uint64_t identity, int64_t now_ns)
{
    (void)now_ns; /* a stop is never rate limited */
    if (q->count == TRIGGER_QUEUE_MAX) {
        q->full[kind]++;
        return false;
    }
    q->pending[q->count++] = (struct trigger_request){.kind = kind, .identity = identity, .stop = true};
    return true;
}

static sbfx_result start_one(struct trigger_queue *q, sbfx *fx, const struct trigger_request *r)
{
    if (r->stop) {
        if (sbfx_stop_identified(fx, r->identity) > 0) q->stopped[r->kind]++;
        return SBFX_OK;
    }
    if (!r->identity) return sbfx_trigger(fx, r->effect, r->position);
    sbfx_trigger_desc d = {.version = SBFX_TRIGGER_DESC_VERSION, .effect = r->effect, .identity = r->identity,
                           .start_time = isnan(r->start) ? sbfx_time(fx) : r->start};
    memcpy(d.position, r->position, sizeof(d.position));
    int expired_before = sbfx_triggers_expired(fx);
    sbfx_result result = sbfx_trigger_identified(fx, &d);
    if (sbfx_triggers_expired(fx) > expired_before) q->expired[r->kind]++;
    return result;
}

int trigger_queue_fire(struct trigger_queue *q, sbfx *fx)
{
    int started = 0;
    for (int i = 0; i < q->count; i++) {
        const struct trigger_request *r = &q->pending[i];
        q->firing = r->kind; /* the listener logs the call under this kind */
        if (start_one(q, fx, r) == SBFX_OK) started += !r->stop;
        else q->pool_full[r->kind]++;
    }
    q->count = 0;
    return started;
}

static enum trigger_kind kind_of(const struct trigger_queue *q, sbfx_trigger_origin origin)
{
    switch (origin) {
    case SBFX_TRIGGER_TIMELINE: return TRIGGER_TIMELINE;
    case SBFX_TRIGGER_SCHEDULE: return TRIGGER_CLI; /* the player schedules --trigger entries only */
    case SBFX_TRIGGER_CALL: break;
    }
    return q->firing;
}

void trigger_queue_listen(const char *effect, const float position[3], double time, sbfx_trigger_origin origin,
                          void *user)
{
    struct trigger_queue *q = user;
    enum trigger_kind kind = kind_of(q, origin);
    struct trigger_log_entry *e = &q->log[q->logged++ % TRIGGER_LOG_MAX];
    e->kind = kind;
    snprintf(e->effect, sizeof(e->effect), "%s", effect);
    memcpy(e->at, position, sizeof(e->at));
    e->time = time;
    q->fired[kind]++;
}

int trigger_queue_log(const struct trigger_queue *q, struct trigger_log_entry out[TRIGGER_LOG_MAX])
{
    int count = q->logged < TRIGGER_LOG_MAX ? (int)q->logged : TRIGGER_LOG_MAX;
    uint64_t first = q->logged - (uint64_t)count;
    for (int i = 0; i < count; i++) out[i] = q->log[(first + (uint64_t)i) % TRIGGER_LOG_MAX];
    return count;
}

uint64_t trigger_queue_refused(const struct trigger_queue *q)
{
    uint64_t n = 0;
    for (int k = 0; k < TRIGGER_KIND_COUNT; k++) n += q->full[k] + q->limited[k];
    return n;
}

const char *trigger_kind_name(enum trigger_kind kind)
{
    static const char *const names[TRIGGER_KIND_COUNT] = {
        [TRIGGER_GPIO] = "gpio", [TRIGGER_DIS] = "dis", [TRIGGER_MQTT] = "mqtt",
        [TRIGGER_TIMELINE] = "timeline", [TRIGGER_CLI] = "cli", [TRIGGER_CIGI] = "cigi",
    };
    return (unsigned)kind < TRIGGER_KIND_COUNT ? names[kind] : "?";
}
