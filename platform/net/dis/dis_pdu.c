/* DIS PDUs from a datagram's bytes (dis_pdu.h): big-endian fields read by offset, no struct
 * overlays (no alignment or padding assumptions), every read inside the PDU's checked length. */
#include "net/dis/dis_pdu.h"

#include <math.h>
#include <string.h>

#define BUNDLE_ALIGN 8 /* bundled PDUs may be padded with zeros to 8-byte boundaries */

static uint16_t be16(const uint8_t *p)
{
    return (uint16_t)(p[0] << 8 | p[1]);
}

static uint32_t be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static float be_float(const uint8_t *p)
{
    uint32_t bits = be32(p);
    float v;
    memcpy(&v, &bits, sizeof(v));
    return v;
}

static double be_double(const uint8_t *p)
{
    uint64_t bits = (uint64_t)be32(p) << 32 | be32(p + 4);
    double v;
    memcpy(&v, &bits, sizeof(v));
    return v;
}

static struct dis_entity_id entity_id(const uint8_t *p)
{
    return (struct dis_entity_id){be16(p), be16(p + 2), be16(p + 4)};
}

static void floats(const uint8_t *p, float out[3])
{
    for (int k = 0; k < 3; k++) out[k] = be_float(p + 4 * k);
}

static enum dis_status parse_detonation(const uint8_t *p, size_t length, struct dis_detonation *d)
{
    if (length < DIS_DETONATION_SIZE) return DIS_BAD_LENGTH;
    d->variable_parameters = p[101];
    if (length != DIS_DETONATION_SIZE + (size_t)DIS_VARIABLE_PARAMETER_SIZE * d->variable_parameters)
        return DIS_BAD_LENGTH;
    d->firing = entity_id(p + 12);
    d->target = entity_id(p + 18);
    d->munition = entity_id(p + 24);
    d->event = entity_id(p + 30);
    floats(p + 36, d->velocity);
    for (int k = 0; k < 3; k++) d->location[k] = be_double(p + 48 + 8 * k);
    if (!isfinite(d->location[0]) || !isfinite(d->location[1]) || !isfinite(d->location[2]))
        return DIS_BAD_LOCATION;
    d->munition_type = (struct dis_entity_type){p[72], p[73], be16(p + 74), p[76], p[77], p[78], p[79]};
    d->warhead = be16(p + 80);
    d->fuse = be16(p + 82);
    d->quantity = be16(p + 84);
    d->rate = be16(p + 86);
    floats(p + 88, d->entity_location);
    d->result = p[100];
    return DIS_DETONATION;
}

enum dis_status dis_pdu_parse(const uint8_t *buf, size_t len, struct dis_pdu *out, size_t *used)
{
    memset(out, 0, sizeof(*out));
    *used = len;
    if (len < DIS_HEADER_SIZE) return DIS_TRUNCATED;
    struct dis_header *h = &out->header;
    *h = (struct dis_header){buf[0], buf[1], buf[2], buf[3], be32(buf + 4), be16(buf + 8)};
    if (h->version != 6 && h->version != 7) return DIS_BAD_VERSION;
    if (h->length < DIS_HEADER_SIZE) return DIS_BAD_LENGTH;
    if (h->length > len) return DIS_TRUNCATED;
    *used = h->length; /* from here on the next PDU of a bundle can be found */
    if (h->type != DIS_PDU_DETONATION) return DIS_OTHER;
    if (h->family != DIS_FAMILY_WARFARE) return DIS_BAD_FAMILY;
    return parse_detonation(buf, h->length, &out->detonation);
}

void dis_cursor_init(struct dis_cursor *c, const uint8_t *data, size_t len)
{
    *c = (struct dis_cursor){data, len, 0};
}

/* Zero bytes up to the next 8-byte boundary (a version byte is never 0). */
static void skip_padding(struct dis_cursor *c)
{
    size_t n = 0;
    while (c->at + n < c->len && n < BUNDLE_ALIGN - 1 && c->data[c->at + n] == 0) n++;
    c->at += n;
}

bool dis_entity_state_parse(const uint8_t *buf, size_t len, struct dis_entity_state *out)
{
    if (len < DIS_ENTITY_STATE_SIZE) return false;
    out->id = (struct dis_entity_id){be16(buf + 12), be16(buf + 14), be16(buf + 16)};
    for (int k = 0; k < 3; k++) {
        out->location[k] = be_double(buf + 48 + 8 * k);
        out->orientation[k] = be_float(buf + 72 + 4 * k);
        if (!isfinite(out->location[k]) || !isfinite(out->orientation[k])) return false;
    }
    return true;
}

bool dis_cursor_next(struct dis_cursor *c, struct dis_pdu *out, enum dis_status *status)
{
    if (c->at > 0) skip_padding(c);
    if (c->at >= c->len) return false;
    size_t used = 0;
    *status = dis_pdu_parse(c->data + c->at, c->len - c->at, out, &used);
    c->at += used;
    return true;
}

const char *dis_status_name(enum dis_status status)
{
    static const char *const names[DIS_STATUS_COUNT] = {
        [DIS_DETONATION] = "detonation", [DIS_OTHER] = "another PDU type",
        [DIS_TRUNCATED] = "truncated", [DIS_BAD_VERSION] = "not protocol version 6 or 7",
        [DIS_BAD_LENGTH] = "wrong length", [DIS_BAD_FAMILY] = "detonation outside the warfare family",
        [DIS_BAD_LOCATION] = "location not finite", [DIS_OVERSIZED] = "oversized datagram",
    };
    return (unsigned)status < DIS_STATUS_COUNT ? names[status] : "?";
}

bool dis_status_malformed(enum dis_status status)
{
    return status != DIS_DETONATION && status != DIS_OTHER;
}
