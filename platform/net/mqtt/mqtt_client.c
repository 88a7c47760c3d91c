/* The MQTT trigger client (mqtt_client.h). */
#include "net/mqtt/mqtt_client.h"

#include <errno.h>
#include <mosquitto.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define LOOP_TIMEOUT_MS 100 /* how often the thread looks at the stop flag while connected */
#define GOODBYE_MS 1000     /* at most this long to get "offline" out when stopping */
#define STATUS_ONLINE "online"
#define STATUS_OFFLINE "offline"

struct mqtt_client {
    struct mqtt_settings s;
    struct mosquitto *mosq;
    pthread_t thread;
    atomic_bool stop;
    mqtt_log_fn log;
    void *user;
    /* the ring: the thread writes head, the frame loop tail */
    struct mqtt_payload ring[MQTT_RING_SLOTS];
    atomic_uint head, tail;
    atomic_uint_fast64_t messages, connects, reconnects, overflows;
    /* the thread's own state */
    bool connected, refused, outage_said;
    int backoff_ms, goodbye_mid;
    bool goodbye_sent;
    int64_t lost_ns;
    char where[300];       /* "host:port", for messages */
};

static int64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

static void say(struct mqtt_client *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static void say(struct mqtt_client *c, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof(msg), fmt, ap);
    va_end(ap);
    if (c->log) c->log(msg, c->user);
}

/* ---- the ring ------------------------------------------------------------------------- */

static void ring_put(struct mqtt_client *c, const void *payload, int length)
{
    unsigned head = atomic_load_explicit(&c->head, memory_order_relaxed);
    unsigned tail = atomic_load_explicit(&c->tail, memory_order_acquire);
    if (head - tail == MQTT_RING_SLOTS) {
        atomic_fetch_add_explicit(&c->overflows, 1, memory_order_relaxed);
        return;
    }
    struct mqtt_payload *slot = &c->ring[head % MQTT_RING_SLOTS];
    size_t len = length > 0 ? (size_t)length : 0;
    memcpy(slot->data, payload, len < MQTT_PAYLOAD_MAX ? len : MQTT_PAYLOAD_MAX);
    slot->length = len;
    atomic_store_explicit(&c->head, head + 1, memory_order_release);
}

int mqtt_client_take(struct mqtt_client *c, struct mqtt_payload *out, int max)
{
    unsigned tail = atomic_load_explicit(&c->tail, memory_order_relaxed);
    unsigned head = atomic_load_explicit(&c->head, memory_order_acquire);
    int count = 0;
    for (; tail != head && count < max; tail++) out[count++] = c->ring[tail % MQTT_RING_SLOTS];
    atomic_store_explicit(&c->tail, tail, memory_order_release);
    return count;
}

void mqtt_client_counts(const struct mqtt_client *c, struct mqtt_counts *out)
{
    out->messages = atomic_load_explicit(&c->messages, memory_order_relaxed);
    out->connects = atomic_load_explicit(&c->connects, memory_order_relaxed);
    out->reconnects = atomic_load_explicit(&c->reconnects, memory_order_relaxed);
    out->overflows = atomic_load_explicit(&c->overflows, memory_order_relaxed);
}

/* ---- libmosquitto's callbacks (on the thread) ------------------------------------------- */

static void on_connect(struct mosquitto *mosq, void *user, int rc)
{
    struct mqtt_client *c = user;
    if (rc != 0) {
        if (!c->outage_said)
            say(c, "mqtt: the broker at %s refused the connection: %s; retrying with back-off", c->where,
                mosquitto_connack_string(rc));
        c->outage_said = true;
        c->refused = true;
        return;
    }
    int sub = mosquitto_subscribe(mosq, NULL, c->s.topic, 1);
    int pub = mosquitto_publish(mosq, NULL, c->s.status_topic, (int)strlen(STATUS_ONLINE), STATUS_ONLINE, 1, true);
    if (sub != MOSQ_ERR_SUCCESS || pub != MOSQ_ERR_SUCCESS)
        say(c, "mqtt: subscribing to %s or publishing on %s failed: %s", c->s.topic, c->s.status_topic,
            mosquitto_strerror(sub != MOSQ_ERR_SUCCESS ? sub : pub));
    uint64_t connects = atomic_fetch_add_explicit(&c->connects, 1, memory_order_relaxed) + 1;
    c->connected = true;
    c->backoff_ms = MQTT_RETRY_MIN_MS;
    if (connects == 1 || !c->lost_ns) {
        say(c, "mqtt: connected to %s: triggers from %s (QoS 1), status on %s", c->where, c->s.topic,
            c->s.status_topic);
    } else {
        uint64_t n = atomic_fetch_add_explicit(&c->reconnects, 1, memory_order_relaxed) + 1;
        say(c, "mqtt: reconnected to %s after %.1f s (reconnect %llu)", c->where,
            (double)(now_ns() - c->lost_ns) / 1e9, (unsigned long long)n);
    }
    c->outage_said = false;
}

static void on_message(struct mosquitto *mosq, void *user, const struct mosquitto_message *m)
{
    (void)mosq;
    struct mqtt_client *c = user;
    bool ours = false; /* the trigger topic may hold wildcards (sbfx/+/trigger) */
    if (!m->topic || mosquitto_topic_matches_sub(c->s.topic, m->topic, &ours) != MOSQ_ERR_SUCCESS || !ours) return;
    atomic_fetch_add_explicit(&c->messages, 1, memory_order_relaxed);
    ring_put(c, m->payload, m->payloadlen);
}

static void on_publish(struct mosquitto *mosq, void *user, int mid)
{
    (void)mosq;
    struct mqtt_client *c = user;
    if (mid == c->goodbye_mid) c->goodbye_sent = true;
}

/* ---- the thread ------------------------------------------------------------------------- */

/* Sleeps up to ms, waking early to stop. */
static void pause_ms(struct mqtt_client *c, int ms)
{
    for (int slept = 0; slept < ms && !atomic_load(&c->stop); slept += 50) {
        struct timespec ts = {0, 50 * 1000000L};
        nanosleep(&ts, NULL);
    }
}

static void back_off(struct mqtt_client *c)
{
    pause_ms(c, c->backoff_ms);
    c->backoff_ms = c->backoff_ms * 2 < MQTT_RETRY_MAX_MS ? c->backoff_ms * 2 : MQTT_RETRY_MAX_MS;
}

static void connect_failed(struct mqtt_client *c, int rc)
{
    if (!c->outage_said)
        say(c, "mqtt: cannot reach the broker at %s: %s; retrying with back-off (%.1f s doubling to %d s)", c->where,
            rc == MOSQ_ERR_ERRNO ? strerror(errno) : mosquitto_strerror(rc), MQTT_RETRY_MIN_MS / 1000.0,
            MQTT_RETRY_MAX_MS / 1000);
    c->outage_said = true;
}

/* Connected: the loop runs until the connection is lost or stop is asked. */
static void serve(struct mqtt_client *c)
{
    int rc = MOSQ_ERR_SUCCESS;
    while (!atomic_load(&c->stop) && !c->refused && rc == MOSQ_ERR_SUCCESS) rc = mosquitto_loop(c->mosq, LOOP_TIMEOUT_MS, 1);
    if (atomic_load(&c->stop) || !c->connected) return;
    c->connected = false;
    c->lost_ns = now_ns();
    say(c, "mqtt: lost the broker at %s (%s); reconnecting with back-off", c->where,
        rc == MOSQ_ERR_ERRNO ? strerror(errno) : mosquitto_strerror(rc));
    c->outage_said = true;
}

static void goodbye(struct mqtt_client *c)
{
    if (!c->connected) return;
    c->goodbye_mid = -1;
    if (mosquitto_publish(c->mosq, &c->goodbye_mid, c->s.status_topic, (int)strlen(STATUS_OFFLINE), STATUS_OFFLINE, 1,
                          true) == MOSQ_ERR_SUCCESS)
        for (int waited = 0; !c->goodbye_sent && waited < GOODBYE_MS; waited += LOOP_TIMEOUT_MS)
            if (mosquitto_loop(c->mosq, LOOP_TIMEOUT_MS, 1) != MOSQ_ERR_SUCCESS) break;
    mosquitto_disconnect(c->mosq);
    mosquitto_loop(c->mosq, LOOP_TIMEOUT_MS, 1);
}

static void *run(void *arg)
{
    struct mqtt_client *c = arg;
    while (!atomic_load(&c->stop)) {
        c->refused = false;
        int rc = mosquitto_connect(c->mosq, c->s.host, c->s.port, MQTT_KEEPALIVE_S);
        if (rc != MOSQ_ERR_SUCCESS) connect_failed(c, rc);
        else serve(c);
        if (!atomic_load(&c->stop)) back_off(c);
    }
    goodbye(c);
    return NULL;
}

/* ---- setup ------------------------------------------------------------------------------ */

static int read_password(const char *path, char *out, size_t size, char *err, size_t n)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        int rc = -errno;
        snprintf(err, n, "mqtt: the password file %s: %s", path, strerror(errno));
        return rc;
    }
    bool ok = fgets(out, (int)size, f) != NULL;
    fclose(f);
    out[ok ? strcspn(out, "\r\n") : 0] = '\0';
    if (!ok || !out[0]) {
        snprintf(err, n, "mqtt: the password file %s is empty (its first line is the password)", path);
        return -EINVAL;
    }
    return 0;
}

static int check(int rc, const char *what, char *err, size_t n)
{
    if (rc == MOSQ_ERR_SUCCESS) return 0;
    snprintf(err, n, "mqtt: %s: %s", what, rc == MOSQ_ERR_ERRNO ? strerror(errno) : mosquitto_strerror(rc));
    return -EINVAL;
}

static int configure(struct mqtt_client *c, char *err, size_t n)
{
    struct mosquitto *m = c->mosq;
    if (mosquitto_sub_topic_check(c->s.topic) != MOSQ_ERR_SUCCESS || !c->s.topic[0]) {
        snprintf(err, n, "mqtt: '%s' is not a topic to subscribe to (+ and # only as whole levels)", c->s.topic);
        return -EINVAL;
    }
    if (mosquitto_pub_topic_check(c->s.status_topic) != MOSQ_ERR_SUCCESS || !c->s.status_topic[0]) {
        snprintf(err, n, "mqtt: the status topic '%s' is not a topic to publish on (no + or #)", c->s.status_topic);
        return -EINVAL;
    }
    int rc = check(mosquitto_will_set(m, c->s.status_topic, (int)strlen(STATUS_OFFLINE), STATUS_OFFLINE, 1, true),
                   "the last will on the status topic", err, n);
    if (!rc && c->s.username[0]) {
        char password[256] = "";
        if (c->s.password_file[0]) rc = read_password(c->s.password_file, password, sizeof(password), err, n);
        if (!rc) rc = check(mosquitto_username_pw_set(m, c->s.username, password[0] ? password : NULL),
                            "the user name and password", err, n);
        memset(password, 0, sizeof(password));
    }
    if (!rc && c->s.ca_file[0])
        rc = check(mosquitto_tls_set(m, c->s.ca_file, NULL, NULL, NULL, NULL), c->s.ca_file, err, n);
    mosquitto_connect_callback_set(m, on_connect);
    mosquitto_message_callback_set(m, on_message);
    mosquitto_publish_callback_set(m, on_publish);
    return rc;
}

static void client_free(struct mqtt_client *c)
{
    if (c->mosq) mosquitto_destroy(c->mosq);
    free(c);
}

int mqtt_client_start(struct mqtt_client **out, const struct mqtt_settings *s, mqtt_log_fn log, void *user,
                      char *err, size_t n)
{
    *out = NULL;
    struct mqtt_client *c = calloc(1, sizeof(*c));
    if (!c) {
        snprintf(err, n, "mqtt: out of memory");
        return -ENOMEM;
    }
    c->s = *s;
    if (!c->s.port) c->s.port = c->s.ca_file[0] ? MQTT_DEFAULT_TLS_PORT : MQTT_DEFAULT_PORT;
    c->log = log, c->user = user;
    c->backoff_ms = MQTT_RETRY_MIN_MS;
    snprintf(c->where, sizeof(c->where), strchr(c->s.host, ':') ? "[%s]:%d" : "%s:%d", c->s.host, c->s.port);
    mosquitto_lib_init(); /* once per process is enough; more calls are counted and harmless */
    char id[24];
    snprintf(id, sizeof(id), "sbfx-play-%d", (int)getpid());
    c->mosq = mosquitto_new(id, true, c);
    int rc = c->mosq ? configure(c, err, n) : (snprintf(err, n, "mqtt: mosquitto_new: %s", strerror(errno)), -ENOMEM);
    if (!rc && (rc = -pthread_create(&c->thread, NULL, run, c)) != 0)
        snprintf(err, n, "mqtt: pthread_create: %s", strerror(-rc));
    if (rc) {
        client_free(c);
        mosquitto_lib_cleanup();
        return rc;
    }
    *out = c;
    return 0;
}

void mqtt_client_stop(struct mqtt_client *c)
{
    if (!c) return;
    atomic_store(&c->stop, true);
    pthread_join(c->thread, NULL);
    client_free(c);
    mosquitto_lib_cleanup();
}
