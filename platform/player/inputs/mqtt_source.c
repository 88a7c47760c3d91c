/* MQTT messages as a trigger source (mqtt_source.h): the broker from the flags and the board,
 * then the client behind the trigger-source contract (inputs.h). */
#include "player/inputs/mqtt_source.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "gpio/effect_at.h"
#include "gpio/effect_names.h"
#include "net/common/net_address.h"

/* The 1st, 10th, 100th... of a kind of trouble is worth a line. */
static bool worth_saying(uint64_t count)
{
    while (count % 10 == 0) count /= 10;
    return count == 1;
}

static void bad_payload(const struct mqtt_source *m, const struct mqtt_payload *p, size_t len, const char *why,
                        uint64_t count)
{
    if (!worth_saying(count)) return;
    char shown[48], msg[512];
    size_t k = 0;
    for (; k < len && k < sizeof(shown) - 4; k++) shown[k] = p->data[k] >= 0x20 && p->data[k] < 0x7f ? p->data[k] : '?';
    snprintf(shown + k, sizeof(shown) - k, "%s", k < len ? "..." : "");
    snprintf(msg, sizeof(msg), "mqtt: a bad payload '%s': %s; a payload is EFFECT or EFFECT@X,Y,Z (%llu so far)",
             shown, why, (unsigned long long)count);
    m->log(msg, m->log_user);
}

/* One payload: its effect and place into the queue, or counted and logged. */
static void queue_payload(struct mqtt_source *m, const struct mqtt_payload *p, struct trigger_queue *q, const sbfx *fx,
                          int64_t now_ns)
{
    size_t len = p->length < MQTT_PAYLOAD_MAX ? p->length : MQTT_PAYLOAD_MAX;
    while (len && (p->data[len - 1] == '\n' || p->data[len - 1] == '\r' || p->data[len - 1] == ' ')) len--;
    char effect[EFFECT_NAME_MAX], names[192], what[256];
    float position[3];
    const char *why = p->length > MQTT_PAYLOAD_MAX ? "too long" : effect_at_parse(p->data, len, effect, position);
    if (!why && !sbfx_has_effect(fx, effect)) {
        snprintf(what, sizeof(what), "the scene has no effect '%s' (its effects: %s)", effect,
                 effect_names(fx, names, sizeof(names)));
        why = what;
    }
    if (why) bad_payload(m, p, len, why, why == what ? ++m->bad_effect : ++m->bad_syntax);
    else trigger_queue_push(q, TRIGGER_MQTT, effect, position, now_ns);
}

/* ---- the trigger-source contract ---- */

static int mqtt_pollfds(const struct trigger_source *s, struct pollfd *fds, int max)
{
    (void)s, (void)fds, (void)max;
    return 0; /* the client's socket is its thread's */
}

static void mqtt_service(struct trigger_source *s, struct trigger_queue *q, const sbfx *fx, int64_t now_ns)
{
    struct mqtt_source *m = (struct mqtt_source *)s;
    int count = mqtt_client_take(m->client, m->payloads, MQTT_RING_SLOTS);
    for (int i = 0; i < count; i++) queue_payload(m, &m->payloads[i], q, fx, now_ns);
}

static void mqtt_close(struct trigger_source *s)
{
    struct mqtt_source *m = (struct mqtt_source *)s;
    mqtt_client_stop(m->client); /* "offline" on the status topic */
    m->client = NULL;
}

static const struct trigger_source_ops mqtt_ops = {
    .pollfds = mqtt_pollfds, .service = mqtt_service, .reload = NULL, .close = mqtt_close,
};

/* ---- opening ---- */

/* The broker: --mqtt over the board's mqtt.host, --mqtt-topic over its topic, then defaults. */
static int settle(struct mqtt_settings *s, const struct player_options *opt, const struct board_profile *b, char *err,
                  size_t n)
{
    *s = b->mqtt;
    if (opt->mqtt) {
        char why[256];
        if (mqtt_endpoint_parse(opt->mqtt, s->host, sizeof(s->host), &s->port, why, sizeof(why)) != 0) {
            snprintf(err, n, "--mqtt: %s", why);
            return -EINVAL;
        }
    }
    if (!s->host[0]) {
        if (!opt->mqtt_topic) return 0;
        snprintf(err, n, "--mqtt-topic needs --mqtt HOST[:PORT] (or a board profile's mqtt.host)");
        return -EINVAL;
    }
    if (opt->mqtt_topic) snprintf(s->topic, sizeof(s->topic), "%s", opt->mqtt_topic);
    if (!s->topic[0]) snprintf(s->topic, sizeof(s->topic), "%s", MQTT_DEFAULT_TOPIC);
    if (!s->status_topic[0]) snprintf(s->status_topic, sizeof(s->status_topic), "%s", MQTT_DEFAULT_STATUS_TOPIC);
    return 0;
}

int mqtt_source_open(struct mqtt_source *m, struct trigger_sources *all, const struct player_options *opt,
                     const struct board_profile *b, input_log_fn log, void *user, char *err, size_t n)
{
    m->source = (struct trigger_source){.ops = &mqtt_ops, .name = "mqtt", .realtime = true};
    m->log = log;
    m->log_user = user;
    static struct mqtt_settings s; /* large (paths): off the stack */
    int rc = settle(&s, opt, b, err, n);
    if (rc || !s.host[0]) return rc;
    rc = mqtt_client_start(&m->client, &s, log, user, err, n);
    if (rc) return rc;
    trigger_queue_limit(&all->queue, TRIGGER_MQTT, b->mqtt_min_interval_ms);
    rc = trigger_sources_add(all, &m->source, err, n);
    if (rc) mqtt_close(&m->source);
    return rc;
}

void mqtt_source_counts(const struct mqtt_source *m, struct mqtt_counts *out)
{
    memset(out, 0, sizeof(*out));
    if (m->client) mqtt_client_counts(m->client, out);
}
