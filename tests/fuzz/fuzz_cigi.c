/* libFuzzer target: a datagram as a CIGI 3.3 host's message must never crash the parser or the
 * receiver, nor break what they promise (make fuzz; seeds: messages in both byte orders with
 * every packet the receiver reads, written by tests/net/cigi_send):
 *   - the message moves forward, one status per packet, and ends at the message's end unless a
 *     packet could not be delimited or the first was no IG Control;
 *   - a packet read has its standard size; its positions and angles are finite numbers;
 *   - the receiver counts every packet once (packets = used + ignored + malformed), its events'
 *     scene positions are finite, and the effects running never exceed the starts heard. */
#include <math.h>
#include <stdlib.h>

#include "net/cigi/cigi_packet.h"
#include "net/cigi/cigi_receiver.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_packet(const struct cigi_packet *p)
{
    if (p->id == CIGI_ENTITY_CONTROL) {
        if (p->size != CIGI_ENTITY_CONTROL_SIZE) abort();
        for (int k = 0; k < 3; k++)
            if (!isfinite(p->entity.position[k])) abort();
        if (!isfinite(p->entity.yaw) || !isfinite(p->entity.pitch) || !isfinite(p->entity.roll)) abort();
    } else if (p->id == CIGI_VIEW_DEFINITION) {
        const struct cigi_view_definition *v = &p->view_definition;
        if (!isfinite(v->left) || !isfinite(v->right) || !isfinite(v->top) || !isfinite(v->bottom)) abort();
    }
}

static void check_message(const uint8_t *data, size_t size)
{
    struct cigi_message m;
    struct cigi_packet p;
    enum cigi_status status;
    cigi_message_init(&m, data, size);
    size_t before = m.at;
    while (cigi_message_next(&m, &p, &status)) {
        if ((unsigned)status >= CIGI_STATUS_COUNT) abort();
        if (m.at <= before && !m.stopped) abort();
        if (m.at > size && !m.stopped) abort();
        before = m.at;
        if (status == CIGI_PACKET) check_packet(&p);
    }
    if (!m.stopped && m.at != size) abort();
}

static void drain(struct cigi_receiver *r)
{
    struct cigi_event e;
    while (cigi_receiver_next(r, &e)) {
        const float *pos = e.kind == CIGI_EVENT_EFFECT_START ? e.effect.position
                           : e.kind == CIGI_EVENT_OWNSHIP   ? e.ownship.position
                                                            : NULL;
        if (pos && (!isfinite(pos[0]) || !isfinite(pos[1]) || !isfinite(pos[2]))) abort();
        if (e.kind == CIGI_EVENT_EFFECT_START && (!e.effect.effect[0] || e.effect.generation == 0)) abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static struct cigi_receiver *r;
    static int64_t now;
    if (!r) {
        static struct cigi_settings s = {.have_origin = true, .origin = {48.137154, 11.576124, 519.0},
                                         .view_id = CIGI_ANY_VIEW};
        s.effects.count = 2;
        s.effects.rules[0] = (struct cigi_effect_rule){.entity_type = 1001, .effect = "explosion"};
        s.effects.rules[1] = (struct cigi_effect_rule){.entity_type = 0, .effect = "smoke"};
        char err[256];
        if (cigi_receiver_make(&r, &s, err, sizeof(err)) != 0) abort();
    }
    check_message(data, size);
    struct cigi_start_of_frame sof;
    bool little;
    (void)cigi_sof_decode(data, size, &sof, &little);
    cigi_receiver_datagram(r, data, size, size > CIGI_MAX_MESSAGE, NULL, now += 1000000);
    drain(r);
    const struct cigi_counts *c = cigi_receiver_counts(r);
    if (c->packets != c->used + c->ignored + c->malformed) abort();
    if (c->active > c->entities || c->stops > c->entities) abort();
    return 0;
}
