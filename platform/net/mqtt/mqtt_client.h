/* An MQTT client for trigger messages (libmosquitto): it subscribes to the trigger topic at
 * QoS 1, publishes a retained "online" on the status topic once connected, leaves "offline" as
 * its last will (the broker publishes it when the connection dies without a goodbye: a crash, a
 * kill, a cable) and publishes it itself when stopped; when the broker goes away it reconnects
 * with back-off (0.5 s doubling to 30 s) and logs the loss, the reconnect and the outage's length.
 *
 * Threads: libmosquitto runs on a thread of its own, made here. DNS lookups, TCP connects that
 * time out, TLS handshakes and reconnects block; on the frame loop's thread they would stall
 * frames whenever the broker is slow or gone. The thread hands each message's payload to the
 * frame loop through a lock-free single-producer single-consumer ring of fixed slots
 * (MQTT_RING_SLOTS): the frame loop takes what waits once a frame and never waits for a lock.
 * A payload that does not fit a slot is still handed over, marked by its length, so the reader
 * counts it as malformed. Nothing of ours is allocated per message (libmosquitto allocates each
 * packet it reads, on its thread). Clean sessions: messages sent while the player was away are
 * not delivered later (an explosion an hour late is not wanted). */
#ifndef SBFX_MQTT_CLIENT_H
#define SBFX_MQTT_CLIENT_H

#include <limits.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define MQTT_DEFAULT_PORT 1883
#define MQTT_DEFAULT_TLS_PORT 8883
#define MQTT_DEFAULT_TOPIC "sbfx/trigger"
#define MQTT_DEFAULT_STATUS_TOPIC "sbfx/status"
#define MQTT_KEEPALIVE_S 10
#define MQTT_RETRY_MIN_MS 500
#define MQTT_RETRY_MAX_MS 30000
#define MQTT_PAYLOAD_MAX 160   /* a slot; EFFECT@X,Y,Z fits many times over */
#define MQTT_RING_SLOTS 256

struct mqtt_settings {
    char host[256];
    int port;                  /* 0: 1883, or 8883 with a CA file */
    char topic[256], status_topic[256];
    char username[128];
    char password_file[PATH_MAX]; /* its first line is the password */
    char ca_file[PATH_MAX];    /* TLS, the broker's certificate checked against it */
};

struct mqtt_payload {
    char data[MQTT_PAYLOAD_MAX];
    size_t length;             /* the message's: more than MQTT_PAYLOAD_MAX means cut */
};

struct mqtt_counts {
    uint64_t messages;         /* on the trigger topic */
    uint64_t connects;         /* connections accepted by the broker */
    uint64_t reconnects;       /* of them, after a lost connection */
    uint64_t overflows;        /* messages the ring had no slot for (the frame loop fell behind) */
};

struct mqtt_client;

typedef void (*mqtt_log_fn)(const char *message, void *user);

/* Checks the settings (the password and CA files are read now), makes the client and starts its
 * thread, which connects. A broker that is not there yet is not an error: it is retried. */
int mqtt_client_start(struct mqtt_client **out, const struct mqtt_settings *s, mqtt_log_fn log, void *user,
                      char *err, size_t n);
/* Takes up to max waiting payloads (the frame loop's thread); never blocks. */
int mqtt_client_take(struct mqtt_client *c, struct mqtt_payload *out, int max);
void mqtt_client_counts(const struct mqtt_client *c, struct mqtt_counts *out);
/* Publishes "offline" (retained), disconnects and joins the thread (within about a second). */
void mqtt_client_stop(struct mqtt_client *c);

#endif
