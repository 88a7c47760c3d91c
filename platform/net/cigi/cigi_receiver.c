/* CIGI 3.3 on the image generator's side (cigi_receiver.h). */
#include "net/cigi/cigi_receiver.h"

#include <arpa/inet.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "net/cigi/cigi_entities.h"
#include "net/common/geodesy.h"

/* The most events one message can make: one per packet, and the smallest packet that makes one
 * is IG Control's 24 bytes. The socket is read only while the queue has room for that many per
 * datagram. */
#define MESSAGE_EVENTS_MAX (CIGI_MAX_MESSAGE / CIGI_IG_CONTROL_SIZE + 1)

struct clock_state {
    bool known;
    uint32_t last;              /* the last timestamp that moved forward */
    uint64_t wraps;             /* times the 32-bit tick count wrapped */
};

struct cigi_receiver {
    struct cigi_settings settings;
    struct geo_frame frame;
    int fd;
    cigi_log_fn log;
    void *log_user;
    struct cigi_counts counts;
    /* the host: its last IG Control, where it came from */
    struct cigi_ig_control ig;
    bool have_ig, little_endian, have_sender;
    struct sockaddr_in sender;
    struct clock_state clock;
    struct cigi_time now;       /* the time of the message being read */
    int view_group;             /* this view's group (its View Definition's), -1 unknown */
    /* the event queue: a ring */
    struct cigi_event events[CIGI_EVENTS_MAX];
    int head, pending;
    uint8_t last_sof[CIGI_START_OF_FRAME_SIZE];
    struct cigi_entities entities;
    struct udp_datagram datagrams[CIGI_BATCH];
    uint8_t buffers[CIGI_BATCH][CIGI_MAX_MESSAGE];
};

static const char *const ignore_names[CIGI_IGNORED_COUNT] = {
    [CIGI_IGNORED_TYPE] = "another packet type", [CIGI_IGNORED_NOT_EFFECT] = "an entity type that is no effect",
    [CIGI_IGNORED_ATTACHED] = "an effect entity attached to a parent (not placed)",
    [CIGI_IGNORED_VIEW] = "another view's packet",
};

void cigi_receiver_configure(struct cigi_receiver *r, const struct cigi_settings *s)
{
    if (s->view_id != r->settings.view_id) r->view_group = -1;
    r->settings = *s;
    geo_frame_init(&r->frame, s->origin[0], s->origin[1], s->origin[2]);
}

int cigi_receiver_make(struct cigi_receiver **out, const struct cigi_settings *s, char *err, size_t n)
{
    *out = NULL;
    if (!s->have_origin) {
        snprintf(err, n, "CIGI needs the scene's dis.origin = [latitude, longitude, height] (degrees, metres, "
                 "WGS-84): where the scene's origin is on the Earth, to place Entity Control's positions");
        return -EINVAL;
    }
    struct cigi_receiver *r = calloc(1, sizeof(*r));
    if (!r) {
        snprintf(err, n, "CIGI: out of memory for the receiver (%zu bytes)", sizeof(*r));
        return -ENOMEM;
    }
    r->fd = -1;
    r->view_group = -1;
    for (int i = 0; i < CIGI_BATCH; i++)
        r->datagrams[i] = (struct udp_datagram){.data = r->buffers[i], .capacity = CIGI_MAX_MESSAGE};
    cigi_receiver_configure(r, s);
    *out = r;
    return 0;
}

int cigi_receiver_open(struct cigi_receiver **out, const struct cigi_settings *s, char *err, size_t n)
{
    int rc = cigi_receiver_make(out, s, err, n);
    if (rc) return rc;
    char why[384];
    rc = udp_open(&s->listen, s->interface, &(*out)->fd, why, sizeof(why));
    if (rc) {
        snprintf(err, n, "--cigi %s: %s", s->listen.text, why);
        cigi_receiver_close(*out);
        *out = NULL;
        return rc;
    }
    int one = 1; /* Start of Frame to a broadcast --cigi-host */
    if (setsockopt((*out)->fd, SOL_SOCKET, SO_BROADCAST, &one, sizeof(one)) != 0) {
        rc = -errno;
        snprintf(err, n, "--cigi %s: SO_BROADCAST: %s", s->listen.text, strerror(errno));
        cigi_receiver_close(*out);
        *out = NULL;
    }
    return rc;
}

void cigi_receiver_close(struct cigi_receiver *r)
{
    if (!r) return;
    if (r->fd >= 0) close(r->fd);
    free(r);
}

void cigi_receiver_set_log(struct cigi_receiver *r, cigi_log_fn log, void *user)
{
    r->log = log;
    r->log_user = user;
}

int cigi_receiver_fd(const struct cigi_receiver *r)
{
    return r ? r->fd : -1;
}

const struct cigi_counts *cigi_receiver_counts(const struct cigi_receiver *r)
{
    return &r->counts;
}

const uint8_t *cigi_receiver_last_sof(const struct cigi_receiver *r)
{
    return r->last_sof;
}

const char *cigi_ignore_name(enum cigi_ignore_reason reason)
{
    return (unsigned)reason < CIGI_IGNORED_COUNT ? ignore_names[reason] : "?";
}

/* ---- the event queue ---------------------------------------------------------------------- */

int cigi_receiver_pending(const struct cigi_receiver *r)
{
    return r->pending;
}

/* A new event at the queue's tail, its kind and time set: NULL (counted) when the queue is full. */
static struct cigi_event *push(struct cigi_receiver *r, enum cigi_event_kind kind, int64_t now_ns)
{
    if (r->pending == CIGI_EVENTS_MAX) {
        r->counts.events_dropped++;
        return NULL;
    }
    struct cigi_event *e = &r->events[(r->head + r->pending++) % CIGI_EVENTS_MAX];
    memset(e, 0, sizeof(*e));
    e->kind = kind;
    e->received_ns = now_ns;
    e->time = r->now;
    return e;
}

bool cigi_receiver_next(struct cigi_receiver *r, struct cigi_event *out)
{
    if (r->pending == 0) return false;
    *out = r->events[r->head];
    r->head = (r->head + 1) % CIGI_EVENTS_MAX;
    r->pending--;
    return true;
}

/* ---- what is logged: the 1st, 10th, 100th... of a kind ----------------------------------- */

static bool worth_saying(uint64_t count)
{
    while (count % 10 == 0) count /= 10;
    return count == 1;
}

static void say(const struct cigi_receiver *r, uint64_t count, const char *what, const struct sockaddr_in *from)
{
    if (!r->log || !worth_saying(count)) return;
    char addr[INET_ADDRSTRLEN] = "?", msg[512];
    if (from) inet_ntop(AF_INET, &from->sin_addr, addr, sizeof(addr));
    snprintf(msg, sizeof(msg), "cigi: %s%s%s%s; %llu so far", from ? "[" : "", from ? addr : "", from ? "] " : "",
             what, (unsigned long long)count);
    r->log(msg, r->log_user);
}

static void malformed(struct cigi_receiver *r, enum cigi_status status, uint8_t id, const struct sockaddr_in *from)
{
    r->counts.malformed++;
    uint64_t count = ++r->counts.malformed_by[status];
    char what[160];
    snprintf(what, sizeof(what), "a malformed packet (ID %u) dropped: %s", id, cigi_status_name(status));
    say(r, count, what, from);
}

static void ignore(struct cigi_receiver *r, enum cigi_ignore_reason reason, bool worth_a_line,
                   const struct sockaddr_in *from)
{
    r->counts.ignored++;
    uint64_t count = ++r->counts.ignored_by[reason];
    if (worth_a_line) say(r, count, cigi_ignore_name(reason), from); /* other types are ordinary traffic */
}

/* ---- the host's clock --------------------------------------------------------------------- */

/* The timestamp in seconds with its wraps counted: a step forward (modulo 2^32) that lands below
 * the last one has wrapped; a step back (a late message) is read against the same wraps. */
static double unwrapped_seconds(struct clock_state *c, uint32_t ticks)
{
    if (!c->known) {
        c->known = true;
        c->last = ticks;
    }
    int32_t step = (int32_t)(ticks - c->last);
    uint64_t wraps = c->wraps;
    if (step >= 0) {
        if (ticks < c->last) wraps = ++c->wraps;
        c->last = ticks;
    } else if (ticks > c->last && wraps > 0) {
        wraps--; /* from before the last wrap */
    }
    return ((double)wraps * 4294967296.0 + (double)ticks) * 1e-5;
}

static void ig_control(struct cigi_receiver *r, const struct cigi_ig_control *ig, bool little_endian,
                       const struct sockaddr_in *from, int64_t now_ns)
{
    r->ig = *ig;
    r->have_ig = true;
    r->little_endian = little_endian;
    if (from) {
        r->sender = *from;
        r->have_sender = true;
    }
    r->now = (struct cigi_time){.host_frame = ig->host_frame, .timestamp = ig->timestamp,
                                .timestamp_valid = ig->timestamp_valid,
                                .seconds = unwrapped_seconds(&r->clock, ig->timestamp)};
    r->counts.used++;
    struct cigi_event *e = push(r, CIGI_EVENT_FRAME, now_ns);
    if (e) e->frame = (struct cigi_frame){.database = ig->database, .ig_mode = ig->ig_mode,
                                          .minor_version = ig->minor_version, .little_endian = little_endian};
}

/* ---- entities ------------------------------------------------------------------------------ */

/* Latitude, longitude, altitude into the scene's metres from dis.origin: double until the offset. */
static void place(const struct cigi_receiver *r, const double geodetic[3], float position[3])
{
    double ecef[3], scene[3];
    geodetic_to_ecef(geodetic[0], geodetic[1], geodetic[2], ecef);
    geo_frame_scene(&r->frame, ecef, scene);
    for (int k = 0; k < 3; k++) position[k] = (float)scene[k];
}

static void ownship(struct cigi_receiver *r, const struct cigi_entity_control *e, const struct sockaddr_in *from,
                    int64_t now_ns)
{
    if (e->attached) {
        ignore(r, CIGI_IGNORED_ATTACHED, true, from);
        return;
    }
    r->counts.used++;
    struct cigi_event *ev = push(r, CIGI_EVENT_OWNSHIP, now_ns);
    if (!ev) return;
    struct cigi_pose *p = &ev->ownship;
    p->entity_id = e->entity_id;
    memcpy(p->geodetic, e->position, sizeof(p->geodetic));
    place(r, e->position, p->position);
    p->roll = e->roll;
    p->pitch = e->pitch;
    p->yaw = e->yaw;
}

static void fill_effect(const struct cigi_receiver *r, const struct cigi_entity_control *e,
                        const struct cigi_entity_slot *slot, uint32_t generation, uint32_t activation_frame,
                        struct cigi_effect *out)
{
    out->entity_id = e->entity_id;
    out->entity_type = slot->running ? slot->entity_type : e->entity_type;
    out->generation = generation;
    out->activation_frame = activation_frame;
    out->identity = (UINT64_C(1) << 62) + ((uint64_t)e->entity_id << 32) + activation_frame;
    const char *name = cigi_effect_find(&r->settings.effects, out->entity_type);
    snprintf(out->effect, sizeof(out->effect), "%s", name ? name : "");
    memcpy(out->geodetic, e->position, sizeof(out->geodetic));
    if (!e->attached) place(r, e->position, out->position);
    out->roll = e->roll;
    out->pitch = e->pitch;
    out->yaw = e->yaw;
}

static void effect_entity(struct cigi_receiver *r, const struct cigi_entity_control *e,
                          const struct sockaddr_in *from, int64_t now_ns)
{
    enum cigi_stop_reason reason = CIGI_STOP_DESTROYED;
    enum cigi_change change = cigi_entity_decide(&r->entities, e, &reason);
    if (change == CIGI_CHANGE_START && e->attached) {
        ignore(r, CIGI_IGNORED_ATTACHED, true, from);
        return;
    }
    r->counts.used++;
    const struct cigi_entity_slot *slot = cigi_entity_slot(&r->entities, e->entity_id);
    if (change != CIGI_CHANGE_NONE) {
        bool start = change == CIGI_CHANGE_START;
        struct cigi_event *ev = push(r, start ? CIGI_EVENT_EFFECT_START : CIGI_EVENT_EFFECT_STOP, now_ns);
        if (!ev) return; /* counted; the slot is left as it was, so the next message tries again */
        fill_effect(r, e, slot, start ? slot->generation + 1 : slot->generation,
                    start ? r->now.host_frame : slot->activation_frame, &ev->effect);
        ev->effect.reason = reason;
        if (start) r->counts.entities++;
        else r->counts.stops++;
    }
    cigi_entity_apply(&r->entities, e, change, r->now.host_frame);
    r->counts.active = r->entities.running;
}

static void entity_control(struct cigi_receiver *r, const struct cigi_entity_control *e,
                           const struct sockaddr_in *from, int64_t now_ns)
{
    if (e->entity_id == CIGI_OWNSHIP) ownship(r, e, from, now_ns);
    else if (cigi_effect_find(&r->settings.effects, e->entity_type) ||
             cigi_entity_slot(&r->entities, e->entity_id)->running)
        effect_entity(r, e, from, now_ns);
    else ignore(r, CIGI_IGNORED_NOT_EFFECT, false, from);
}

/* ---- views ------------------------------------------------------------------------------- */

static bool view_definition_for_us(struct cigi_receiver *r, const struct cigi_view_definition *v)
{
    if (r->settings.view_id == CIGI_ANY_VIEW) return true;
    if (v->view_id != r->settings.view_id) return false;
    r->view_group = v->group_id; /* the view's group, for View Control sent to the group */
    return true;
}

static bool view_control_for_us(const struct cigi_receiver *r, const struct cigi_view_control *v)
{
    if (r->settings.view_id == CIGI_ANY_VIEW) return true;
    if (v->group_id != 0) return r->view_group > 0 && v->group_id == r->view_group;
    return v->view_id == r->settings.view_id;
}

static void view_packet(struct cigi_receiver *r, const struct cigi_packet *p, const struct sockaddr_in *from,
                        int64_t now_ns)
{
    bool definition = p->id == CIGI_VIEW_DEFINITION;
    bool ours = definition ? view_definition_for_us(r, &p->view_definition) : view_control_for_us(r, &p->view_control);
    if (!ours) {
        ignore(r, CIGI_IGNORED_VIEW, false, from);
        return;
    }
    r->counts.used++;
    struct cigi_event *ev = push(r, definition ? CIGI_EVENT_VIEW_DEFINITION : CIGI_EVENT_VIEW_CONTROL, now_ns);
    if (!ev) return;
    if (definition) ev->view_definition = p->view_definition;
    else ev->view_control = p->view_control;
}

/* ---- messages ---------------------------------------------------------------------------- */

static void packet(struct cigi_receiver *r, const struct cigi_packet *p, bool first, bool little_endian,
                   const struct sockaddr_in *from, int64_t now_ns)
{
    switch (p->id) {
    case CIGI_IG_CONTROL:
        if (first) ig_control(r, &p->ig_control, little_endian, from, now_ns);
        else ignore(r, CIGI_IGNORED_TYPE, false, from); /* one per message: the first */
        break;
    case CIGI_ENTITY_CONTROL: entity_control(r, &p->entity, from, now_ns); break;
    case CIGI_VIEW_CONTROL:
    case CIGI_VIEW_DEFINITION: view_packet(r, p, from, now_ns); break;
    default: ignore(r, CIGI_IGNORED_TYPE, false, from); break;
    }
}

void cigi_receiver_datagram(struct cigi_receiver *r, const uint8_t *data, size_t length, bool truncated,
                            const struct sockaddr_in *from, int64_t now_ns)
{
    r->counts.messages++;
    if (truncated || length > CIGI_MAX_MESSAGE || length == 0) {
        r->counts.packets++;
        malformed(r, length ? CIGI_OVERSIZED : CIGI_TRUNCATED, length ? data[0] : 0, from);
        return;
    }
    struct cigi_message m;
    struct cigi_packet p;
    enum cigi_status status;
    cigi_message_init(&m, data, length);
    for (bool first = true; cigi_message_next(&m, &p, &status); first = false) {
        r->counts.packets++;
        if (cigi_status_malformed(status)) malformed(r, status, p.id, from);
        else if (status == CIGI_OTHER) ignore(r, CIGI_IGNORED_TYPE, false, from);
        else packet(r, &p, first, m.little_endian, from, now_ns);
    }
}

int cigi_receiver_service(struct cigi_receiver *r, int64_t now_ns)
{
    int total = 0;
    while (total < CIGI_SERVICE_MAX) {
        int room = (CIGI_EVENTS_MAX - r->pending) / MESSAGE_EVENTS_MAX;
        if (room <= 0) break; /* the rest waits in the kernel until the queue is read */
        int want = room < CIGI_BATCH ? room : CIGI_BATCH;
        int got = udp_receive(r->fd, r->datagrams, want);
        if (got < 0) return got;
        for (int i = 0; i < got; i++) {
            const struct udp_datagram *d = &r->datagrams[i];
            cigi_receiver_datagram(r, d->data, d->length, d->truncated, &d->from, now_ns);
        }
        total += got;
        if (got < want) break;
    }
    return total;
}

/* ---- Start of Frame ---------------------------------------------------------------------- */

int cigi_receiver_send_sof(struct cigi_receiver *r, const struct cigi_sof_info *info, char *err, size_t n)
{
    const struct cigi_start_of_frame sof = {
        .database = r->have_ig ? r->ig.database : 0, .ig_status = info->ig_status,
        .ig_mode = r->have_ig ? r->ig.ig_mode : 0, .timestamp_valid = info->timestamp_valid,
        .ig_frame = info->ig_frame, .timestamp = info->timestamp, .last_host_frame = r->have_ig ? r->ig.host_frame : 0,
    };
    cigi_sof_encode(&sof, r->little_endian, r->last_sof);
    struct sockaddr_in to = r->sender;
    if (r->settings.have_host)
        to = (struct sockaddr_in){.sin_family = AF_INET, .sin_port = htons(r->settings.host.port),
                                  .sin_addr = r->settings.host.addr};
    if (r->fd < 0) return 0;
    if (!r->settings.have_host && !r->have_sender) {
        r->counts.sof_unaddressed++;
        return 0;
    }
    if (sendto(r->fd, r->last_sof, sizeof(r->last_sof), MSG_DONTWAIT | MSG_NOSIGNAL, (const struct sockaddr *)&to,
               sizeof(to)) == (ssize_t)sizeof(r->last_sof)) {
        r->counts.sof_sent++;
        return 1;
    }
    int rc = errno ? -errno : -EIO;
    r->counts.sof_failed++;
    char addr[INET_ADDRSTRLEN] = "?";
    inet_ntop(AF_INET, &to.sin_addr, addr, sizeof(addr));
    snprintf(err, n, "cigi: sending Start of Frame to %s:%u: %s (tried again next frame)", addr,
             (unsigned)ntohs(to.sin_port), strerror(-rc));
    return rc;
}
