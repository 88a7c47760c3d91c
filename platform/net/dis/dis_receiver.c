/* DIS detonations into effects (dis_receiver.h). */
#include "net/dis/dis_receiver.h"

#include <arpa/inet.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "net/common/geodesy.h"
#include "net/dis/dis_events.h"

struct dis_receiver {
    struct dis_settings settings;
    struct geo_frame frame;
    int fd;
    struct dis_events events;
    struct dis_counts counts;
    struct udp_datagram datagrams[DIS_BATCH];
    uint8_t buffers[DIS_BATCH][DIS_MAX_PDU_SIZE];
};

static const char *const ignore_names[DIS_IGNORED_COUNT] = {
    [DIS_IGNORED_TYPE] = "another PDU type", [DIS_IGNORED_EXERCISE] = "another exercise",
    [DIS_IGNORED_REPEAT] = "a repeated event", [DIS_IGNORED_RANGE] = "out of range",
    [DIS_IGNORED_UNMAPPED] = "no effect for it",
};

void dis_receiver_configure(struct dis_receiver *r, const struct dis_settings *s)
{
    r->settings = *s;
    geo_frame_init(&r->frame, s->origin[0], s->origin[1], s->origin[2]);
}

int dis_receiver_make(struct dis_receiver **out, const struct dis_settings *s, char *err, size_t n)
{
    *out = NULL;
    if (!s->have_origin) {
        snprintf(err, n, "DIS needs the scene's dis.origin = [latitude, longitude, height] (degrees, metres, "
                 "WGS-84): where the scene's origin is on the Earth");
        return -EINVAL;
    }
    struct dis_receiver *r = calloc(1, sizeof(*r));
    if (!r) {
        snprintf(err, n, "DIS: out of memory for the receive buffers (%zu bytes)", sizeof(*r));
        return -ENOMEM;
    }
    r->fd = -1;
    dis_events_init(&r->events);
    for (int i = 0; i < DIS_BATCH; i++) r->datagrams[i] = (struct udp_datagram){.data = r->buffers[i], .capacity = DIS_MAX_PDU_SIZE};
    dis_receiver_configure(r, s);
    *out = r;
    return 0;
}

int dis_receiver_open(struct dis_receiver **out, const struct dis_settings *s, char *err, size_t n)
{
    int rc = dis_receiver_make(out, s, err, n);
    if (rc) return rc;
    char why[384];
    rc = udp_open(&s->listen, s->interface, &(*out)->fd, why, sizeof(why));
    if (rc) {
        snprintf(err, n, "--dis %s: %s", s->listen.text, why);
        dis_receiver_close(*out);
        *out = NULL;
    }
    return rc;
}

void dis_receiver_close(struct dis_receiver *r)
{
    if (!r) return;
    if (r->fd >= 0) close(r->fd);
    free(r);
}

int dis_receiver_fd(const struct dis_receiver *r)
{
    return r ? r->fd : -1;
}

const struct dis_counts *dis_receiver_counts(const struct dis_receiver *r)
{
    return &r->counts;
}

/* ---- what is logged: the 1st, 10th, 100th... of a kind ----------------------------------- */

static bool worth_saying(uint64_t count)
{
    while (count % 10 == 0) count /= 10;
    return count == 1;
}

static void say(const struct dis_sink *sink, uint64_t count, const char *what, const struct sockaddr_in *from)
{
    if (!sink->log || !worth_saying(count)) return;
    char addr[INET_ADDRSTRLEN] = "?", msg[512];
    if (from) inet_ntop(AF_INET, &from->sin_addr, addr, sizeof(addr));
    snprintf(msg, sizeof(msg), "dis: %s%s%s%s; %llu so far", from ? "[" : "", from ? addr : "", from ? "] " : "",
             what, (unsigned long long)count);
    sink->log(msg, sink->user);
}

static void malformed(struct dis_receiver *r, enum dis_status status, const struct sockaddr_in *from,
                      const struct dis_sink *sink)
{
    r->counts.malformed++;
    uint64_t count = ++r->counts.malformed_by[status];
    char what[128];
    snprintf(what, sizeof(what), "a malformed PDU dropped (%s)", dis_status_name(status));
    say(sink, count, what, from);
}

static void ignore(struct dis_receiver *r, enum dis_ignore_reason reason, const char *detail,
                   const struct sockaddr_in *from, const struct dis_sink *sink)
{
    r->counts.ignored++;
    uint64_t count = ++r->counts.ignored_by[reason];
    if (!detail) return; /* ordinary traffic: not worth a line */
    say(sink, count, detail, from);
}

/* ---- a detonation ----------------------------------------------------------------------- */

static void out_of_range(struct dis_receiver *r, const struct dis_detonation *d, double distance,
                         const struct sockaddr_in *from, const struct dis_sink *sink)
{
    double lat, lon, alt;
    ecef_to_geodetic(d->location, &lat, &lon, &alt);
    char what[256];
    snprintf(what, sizeof(what), "a detonation at %.5f, %.5f, %.0f m is %.1f km from dis.origin, beyond dis.range "
             "(%.1f km): ignored", lat, lon, alt, distance / 1000.0, r->settings.range_m / 1000.0);
    ignore(r, DIS_IGNORED_RANGE, what, from, sink);
}

static void unmapped(struct dis_receiver *r, const struct dis_detonation *d, const struct sockaddr_in *from,
                     const struct dis_sink *sink)
{
    const struct dis_entity_type *t = &d->munition_type;
    char what[256];
    snprintf(what, sizeof(what), "no dis.effects rule matches munition %u.%u.%u.%u.%u.%u.%u result %u, and there "
             "is no dis.default: ignored", t->kind, t->domain, t->country, t->category, t->subcategory, t->specific,
             t->extra, d->result);
    ignore(r, DIS_IGNORED_UNMAPPED, what, from, sink);
}

/* The reason a well-formed detonation is not used, or DIS_IGNORED_COUNT when it is. */
static enum dis_ignore_reason screen(struct dis_receiver *r, const struct dis_pdu *pdu, int64_t now_ns,
                                     double *distance)
{
    const struct dis_detonation *d = &pdu->detonation;
    const struct dis_settings *s = &r->settings;
    if (s->exercise != DIS_ANY && pdu->header.exercise != s->exercise) return DIS_IGNORED_EXERCISE;
    if (dis_events_repeat(&r->events, &d->event, now_ns)) return DIS_IGNORED_REPEAT;
    *distance = geo_frame_distance(&r->frame, d->location);
    if (*distance > s->range_m) return DIS_IGNORED_RANGE;
    return DIS_IGNORED_COUNT;
}

static void detonation(struct dis_receiver *r, const struct dis_pdu *pdu, const struct sockaddr_in *from,
                       int64_t now_ns, const struct dis_sink *sink)
{
    const struct dis_detonation *d = &pdu->detonation;
    double distance = 0.0;
    enum dis_ignore_reason reason = screen(r, pdu, now_ns, &distance);
    const char *effect = reason == DIS_IGNORED_COUNT ? dis_effect_find(&r->settings.effects, &d->munition_type, d->result)
                                                     : NULL;
    if (reason == DIS_IGNORED_RANGE) out_of_range(r, d, distance, from, sink);
    else if (reason != DIS_IGNORED_COUNT) ignore(r, reason, NULL, from, sink);
    else if (!effect) unmapped(r, d, from, sink);
    if (!effect) return;
    double scene[3];
    geo_frame_scene(&r->frame, d->location, scene); /* double until here: metres from the origin */
    const float position[3] = {(float)scene[0], (float)scene[1], (float)scene[2]};
    r->counts.detonations++;
    if (sink->fire_event) sink->fire_event(effect, position, &d->event, pdu->header.timestamp, sink->user);
    else if (sink->fire) sink->fire(effect, position, sink->user);
}

/* The Entity State PDU the cursor just passed (its length field was trusted: it ends at c->at). */
static void entity_state(const struct dis_receiver *r, const struct dis_cursor *c, const struct dis_pdu *pdu,
                         const struct dis_sink *sink)
{
    struct dis_entity_state es;
    if (r->settings.exercise != DIS_ANY && pdu->header.exercise != r->settings.exercise) return;
    if (dis_entity_state_parse(c->data + c->at - pdu->header.length, pdu->header.length, &es))
        sink->entity(&es, sink->user);
}

void dis_receiver_datagram(struct dis_receiver *r, const uint8_t *data, size_t length, bool truncated,
                           const struct sockaddr_in *from, int64_t now_ns, const struct dis_sink *sink)
{
    r->counts.datagrams++;
    if (truncated || length > DIS_MAX_PDU_SIZE || length == 0) {
        r->counts.pdus++;
        malformed(r, truncated || length ? DIS_OVERSIZED : DIS_TRUNCATED, from, sink);
        return;
    }
    struct dis_cursor c;
    struct dis_pdu pdu;
    enum dis_status status;
    dis_cursor_init(&c, data, length);
    while (dis_cursor_next(&c, &pdu, &status)) {
        r->counts.pdus++;
        if (!dis_status_malformed(status) && sink->heard) sink->heard(pdu.header.timestamp, sink->user);
        if (status == DIS_OTHER && pdu.header.type == DIS_PDU_ENTITY_STATE && sink->entity)
            entity_state(r, &c, &pdu, sink);
        if (dis_status_malformed(status)) malformed(r, status, from, sink);
        else if (status == DIS_OTHER) ignore(r, DIS_IGNORED_TYPE, NULL, from, sink);
        else detonation(r, &pdu, from, now_ns, sink);
    }
}

int dis_receiver_service(struct dis_receiver *r, int64_t now_ns, const struct dis_sink *sink)
{
    int total = 0;
    while (total < DIS_SERVICE_MAX) {
        int got = udp_receive(r->fd, r->datagrams, DIS_BATCH);
        if (got < 0) return got;
        for (int i = 0; i < got; i++) {
            const struct udp_datagram *d = &r->datagrams[i];
            dis_receiver_datagram(r, d->data, d->length, d->truncated, &d->from, now_ns, sink);
        }
        total += got;
        if (got < DIS_BATCH) break;
    }
    return total;
}

const char *dis_ignore_name(enum dis_ignore_reason reason)
{
    return (unsigned)reason < DIS_IGNORED_COUNT ? ignore_names[reason] : "?";
}
