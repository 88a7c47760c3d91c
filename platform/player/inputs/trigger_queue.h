/* The one trigger path of sbfx-play (inputs.h): GPIO lines, DIS detonations, MQTT messages, the
 * scene's timeline and --trigger all end here, so they share one queue, one set of limits and
 * one log.
 *
 *   trigger_queue_push   a trigger source asks for an effect at a place (between frames, on the
 *                        frame loop's thread, from its service); refused when the frame's queue
 *                        is full or when the source's rate limit holds it back
 *   trigger_queue_fire   once per frame, before the frame's simulation: every queued trigger
 *                        goes to sbfx_trigger, so one that arrived during frame N starts at the
 *                        first step of frame N+1 (the latency from packet to effect is under a
 *                        frame); the pool refuses what it cannot hold (counted per kind)
 *   trigger_queue_listen the module's trigger listener (sbfx_set_trigger_listener): every
 *                        instance started, the timeline's and --trigger's included (they are
 *                        scheduled inside the module), goes into the log with the clock of its
 *                        first step
 *
 * Limits per kind: GPIO lines are debounced and rate limited per line before they get here
 * (gpio/gpio_triggers.h); MQTT is rate limited here per effect (trigger_queue_limit: the board's
 * mqtt.min_interval_ms, as a GPIO line's); DIS has no rate limit (a salvo is many detonations at
 * once), only its repeat filter (net/dis/dis_events.h); every kind shares the queue's
 * TRIGGER_QUEUE_MAX per frame and the particle pool. Nothing here allocates. */
#ifndef SBFX_PLAYER_TRIGGER_QUEUE_H
#define SBFX_PLAYER_TRIGGER_QUEUE_H

#include <stdbool.h>
#include <stdint.h>

#include "gpio/trigger_filter.h"
#include "sbfx.h"

#define TRIGGER_QUEUE_MAX 64   /* triggers started per frame at most */
#define TRIGGER_LOG_MAX 16     /* the log keeps the last 16 */
#define TRIGGER_LIMITS_MAX 64  /* effects a rate limit is kept for */
#define TRIGGER_EFFECT_MAX 64

/* Where a trigger came from: the log's "source" (trigger_kind_name). */
enum trigger_kind { TRIGGER_GPIO, TRIGGER_DIS, TRIGGER_MQTT, TRIGGER_TIMELINE, TRIGGER_CLI, TRIGGER_CIGI,
                    TRIGGER_KIND_COUNT };

struct trigger_request {
    enum trigger_kind kind;
    char effect[TRIGGER_EFFECT_MAX];
    float position[3];
    uint64_t identity;          /* 0: a plain trigger (sbfx_trigger); else sbfx_trigger_identified */
    double start;               /* its start on the module's clock; NAN: the clock when it fires */
    bool stop;                  /* end the identified instance instead (sbfx_stop_identified) */
};

struct trigger_log_entry {
    enum trigger_kind kind;
    char effect[TRIGGER_EFFECT_MAX];
    float at[3];
    double time; /* the module's clock (sbfx_time) at the effect's first step */
};

struct trigger_limit {
    enum trigger_kind kind;
    char effect[TRIGGER_EFFECT_MAX];
    struct trigger_filter filter;
};

struct trigger_queue {
    struct trigger_request pending[TRIGGER_QUEUE_MAX];
    int count;
    enum trigger_kind firing;                   /* whose sbfx_trigger call is under way */
    struct trigger_log_entry log[TRIGGER_LOG_MAX];
    uint64_t logged;                            /* entries ever logged: the next goes at logged % MAX */
    int min_interval_ms[TRIGGER_KIND_COUNT];    /* the rate limit per effect of a kind (0: none) */
    struct trigger_limit limits[TRIGGER_LIMITS_MAX];
    int limit_count;
    uint64_t fired[TRIGGER_KIND_COUNT];         /* instances started */
    uint64_t full[TRIGGER_KIND_COUNT];          /* refused: the frame's queue was full */
    uint64_t limited[TRIGGER_KIND_COUNT];       /* refused: within the rate limit */
    uint64_t pool_full[TRIGGER_KIND_COUNT];     /* refused by the module (the particle pool) */
    uint64_t expired[TRIGGER_KIND_COUNT];       /* identified, over before they were heard */
    uint64_t stopped[TRIGGER_KIND_COUNT];       /* identified instances ended (particles there were) */
};

/* An empty queue, no rate limit. */
void trigger_queue_init(struct trigger_queue *q);
/* A kind's triggers of one effect at most once per min_interval_ms (0: no limit). */
void trigger_queue_limit(struct trigger_queue *q, enum trigger_kind kind, int min_interval_ms);
/* False when refused (counted): the queue is full, or the kind's rate limit holds it back
 * (now_ns: the monotonic clock at the trigger's arrival). */
bool trigger_queue_push(struct trigger_queue *q, enum trigger_kind kind, const char *effect, const float position[3],
                        int64_t now_ns);
/* The same for an identified instance (sbfx_trigger_identified): identity 1..2^63-1, start on
 * the module's clock (NAN: the clock when it fires). */
bool trigger_queue_push_identified(struct trigger_queue *q, enum trigger_kind kind, const char *effect,
                                   const float position[3], uint64_t identity, double start, int64_t now_ns);
/* Ends an identified instance at the next frame (CIGI's Destroyed), in the queue's order. */
bool trigger_queue_push_stop(struct trigger_queue *q, enum trigger_kind kind, uint64_t identity, int64_t now_ns);
/* Starts every queued trigger (sbfx_trigger, or sbfx_trigger_identified); returns how many started. */
int trigger_queue_fire(struct trigger_queue *q, sbfx *fx);
/* The listener to give sbfx_set_trigger_listener, with the queue as user. */
void trigger_queue_listen(const char *effect, const float position[3], double time, sbfx_trigger_origin origin,
                          void *user);
/* The log, oldest first: the number of entries copied into out (at most TRIGGER_LOG_MAX). */
int trigger_queue_log(const struct trigger_queue *q, struct trigger_log_entry out[TRIGGER_LOG_MAX]);
/* Triggers the queue refused (full or rate limited), every kind. */
uint64_t trigger_queue_refused(const struct trigger_queue *q);
/* "gpio", "dis", "mqtt", "timeline", "cli", "cigi": the log's source names (a contract: trigger_log). */
const char *trigger_kind_name(enum trigger_kind kind);

#endif
