/* libFuzzer target: a datagram of DIS PDUs must never crash the parser or the receiver, nor
 * break what they promise (make fuzz; seeds: v6 and v7 Detonation PDUs, a bundle, an Entity
 * State PDU, written by tests/net/dis_send):
 *   - the cursor moves forward and ends at the datagram's end, one status per PDU;
 *   - a detonation is exactly 104 + 16 x its records long and its location is finite;
 *   - the receiver counts every PDU once: pdus = detonations + ignored + malformed. */
#include <math.h>
#include <stdlib.h>

#include "net/dis/dis_pdu.h"
#include "net/dis/dis_receiver.h"

/* an Entity State PDU's fields (--follow): finite, as dis_entity_state_parse promises */
static void entity(const struct dis_entity_state *e, void *user)
{
    (void)user;
    for (int k = 0; k < 3; k++)
        if (!isfinite(e->location[k]) || !isfinite(e->orientation[k])) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_cursor(const uint8_t *data, size_t size)
{
    struct dis_cursor c;
    struct dis_pdu pdu;
    enum dis_status status;
    dis_cursor_init(&c, data, size);
    size_t before = c.at;
    while (dis_cursor_next(&c, &pdu, &status)) {
        if (c.at <= before || c.at > size || (unsigned)status >= DIS_STATUS_COUNT) abort();
        before = c.at;
        if (status != DIS_DETONATION) continue;
        const struct dis_detonation *d = &pdu.detonation;
        if (pdu.header.length != DIS_DETONATION_SIZE + DIS_VARIABLE_PARAMETER_SIZE * d->variable_parameters) abort();
        for (int k = 0; k < 3; k++)
            if (!isfinite(d->location[k])) abort();
    }
    if (c.at != size) abort();
}

static void fire(const char *effect, const float position[3], void *user)
{
    (void)user;
    if (!effect || !isfinite(position[0]) || !isfinite(position[1]) || !isfinite(position[2])) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static struct dis_receiver *r;
    static int64_t now;
    if (!r) {
        static struct dis_settings s = {.have_origin = true, .origin = {48.137154, 11.576124, 519.0},
                                        .range_m = 20000.0, .exercise = DIS_ANY};
        const char *why;
        s.effects.count = 1;
        dis_munition_parse("2.9.*.*.*.*.*", s.effects.rules[0].munition, &why);
        s.effects.rules[0].result = DIS_ANY;
        s.effects.rules[0].effect[0] = 'x';
        char err[256];
        if (dis_receiver_make(&r, &s, err, sizeof(err)) != 0) abort();
    }
    check_cursor(data, size);
    const struct dis_sink sink = {fire, NULL, NULL, NULL, NULL, entity};
    dis_receiver_datagram(r, data, size, size > DIS_MAX_PDU_SIZE, NULL, now += 1000000, &sink);
    const struct dis_counts *c = dis_receiver_counts(r);
    if (c->pdus != c->detonations + c->ignored + c->malformed) abort();
    return 0;
}
