/* MQTT messages as a trigger source (inputs.h; docs/triggers.md): --mqtt HOST[:PORT] (or the
 * board's mqtt.host) starts a client (platform/net/mqtt/mqtt_client.h does the protocol, on a thread
 * of its own; this is the player's side of it) that subscribes to --mqtt-topic (the board's
 * mqtt.topic, sbfx/trigger). Each payload, EFFECT or EFFECT@X,Y,Z (--gpio's syntax,
 * gpio/effect_at.h), of an effect the module has, goes to the trigger queue, rate limited per
 * effect (the board's mqtt.min_interval_ms); a bad one is counted and logged (the 1st, 10th,
 * 100th...). The client has no descriptor to poll: its messages are taken when the loop services
 * its sources, and at the latest when a frame starts. */
#ifndef SBFX_PLAYER_MQTT_SOURCE_H
#define SBFX_PLAYER_MQTT_SOURCE_H

#include "net/mqtt/mqtt_client.h"
#include "player/inputs/inputs.h"
#include "player/options/board.h"
#include "player/options/options.h"

struct mqtt_source {
    struct trigger_source source;    /* what the loop sees */
    struct mqtt_client *client;      /* NULL: no --mqtt */
    uint64_t bad_syntax;             /* payloads that are not EFFECT[@X,Y,Z] */
    uint64_t bad_effect;             /* those naming an effect the scene does not have */
    struct mqtt_payload payloads[MQTT_RING_SLOTS]; /* taken from the client's ring */
    input_log_fn log;
    void *log_user;
};

/* Starts the client when --mqtt or the board's mqtt.host names a broker (a broker not there yet
 * is retried, not an error), sets MQTT's rate limit on the run's queue and adds the source to the
 * run's: 0, or an error naming the flag or key and what to do. */
int mqtt_source_open(struct mqtt_source *m, struct trigger_sources *all, const struct player_options *opt,
                     const struct board_profile *b, input_log_fn log, void *user, char *err, size_t n);
/* Its client's counters (zero without --mqtt). */
void mqtt_source_counts(const struct mqtt_source *m, struct mqtt_counts *out);

#endif
