/* CIGI 3.3 packets (cigi_packet.h): read field by field at the standard's offsets, in the
 * message's byte order; never a cast of the buffer (unaligned, and either byte order). */
#include "net/cigi/cigi_packet.h"

#include <math.h>
#include <string.h>

/* ---- fields in either byte order -------------------------------------------------------- */

static uint16_t get16(const uint8_t *p, bool le)
{
    return le ? (uint16_t)(p[0] | p[1] << 8) : (uint16_t)(p[0] << 8 | p[1]);
}

static uint32_t get32(const uint8_t *p, bool le)
{
    uint32_t v = 0;
    for (int i = 0; i < 4; i++) v = v << 8 | p[le ? 3 - i : i];
    return v;
}

static uint64_t get64(const uint8_t *p, bool le)
{
    uint64_t v = 0;
    for (int i = 0; i < 8; i++) v = v << 8 | p[le ? 7 - i : i];
    return v;
}

static float getf(const uint8_t *p, bool le)
{
    uint32_t u = get32(p, le);
    float f;
    memcpy(&f, &u, sizeof(f));
    return f;
}

static double getd(const uint8_t *p, bool le)
{
    uint64_t u = get64(p, le);
    double d;
    memcpy(&d, &u, sizeof(d));
    return d;
}

static void put16(uint8_t *p, uint16_t v, bool le)
{
    for (int i = 0; i < 2; i++) p[le ? i : 1 - i] = (uint8_t)(v >> (8 * i));
}

static void put32(uint8_t *p, uint32_t v, bool le)
{
    for (int i = 0; i < 4; i++) p[le ? i : 3 - i] = (uint8_t)(v >> (8 * i));
}

static bool angle_ok(float a)
{
    return isfinite(a) && a >= -360.0f && a <= 360.0f;
}

/* ---- the packets ------------------------------------------------------------------------- */

/* IG Control's byte order from its magic: 0, or CIGI_BAD_MAGIC. */
static enum cigi_status byte_order(const uint8_t *p, bool *le)
{
    uint16_t magic = (uint16_t)(p[6] << 8 | p[7]);
    if (magic != CIGI_BYTE_SWAP_MAGIC && magic != 0x0080u) return CIGI_BAD_MAGIC;
    *le = magic == 0x0080u;
    return CIGI_PACKET;
}

static enum cigi_status ig_control(const uint8_t *p, bool le, struct cigi_ig_control *o)
{
    o->version = p[2];
    if (o->version != CIGI_VERSION) return CIGI_BAD_VERSION;
    o->database = (int8_t)p[3];
    o->ig_mode = p[4] & 3;
    o->timestamp_valid = p[4] >> 2 & 1;
    o->extrapolation = p[4] >> 3 & 1;
    o->minor_version = p[4] >> 4;
    o->host_frame = get32(p + 8, le);
    o->timestamp = get32(p + 12, le);
    o->last_ig_frame = get32(p + 16, le);
    return CIGI_PACKET;
}

static enum cigi_status entity_control(const uint8_t *p, bool le, struct cigi_entity_control *o)
{
    o->entity_id = get16(p + 2, le);
    o->state = p[4] & 3;
    o->attached = p[4] >> 2 & 1;
    o->collision_detection = p[4] >> 3 & 1;
    o->inherit_alpha = p[4] >> 4 & 1;
    o->clamp = p[4] >> 5 & 3;
    o->animation_backward = p[5] & 1;
    o->animation_loop = p[5] >> 1 & 1;
    o->animation = p[5] >> 2 & 3;
    o->extrapolation = p[5] >> 4 & 1;
    o->alpha = p[6];
    o->entity_type = get16(p + 8, le);
    o->parent_id = get16(p + 10, le);
    o->roll = getf(p + 12, le);
    o->pitch = getf(p + 16, le);
    o->yaw = getf(p + 20, le);
    for (int k = 0; k < 3; k++) o->position[k] = getd(p + 24 + 8 * k, le);
    if (!angle_ok(o->roll) || !angle_ok(o->pitch) || !angle_ok(o->yaw)) return CIGI_BAD_VALUE;
    for (int k = 0; k < 3; k++)
        if (!isfinite(o->position[k]) || fabs(o->position[k]) > CIGI_DISTANCE_MAX) return CIGI_BAD_VALUE;
    if (!o->attached && (fabs(o->position[0]) > 90.0 || fabs(o->position[1]) > 180.0)) return CIGI_BAD_VALUE;
    return CIGI_PACKET;
}

static enum cigi_status view_control(const uint8_t *p, bool le, struct cigi_view_control *o)
{
    o->view_id = get16(p + 2, le);
    o->group_id = p[4];
    o->enable = p[5] & 0x3f;
    o->entity_id = get16(p + 6, le);
    for (int k = 0; k < 3; k++) o->offset[k] = getf(p + 8 + 4 * k, le);
    o->roll = getf(p + 20, le);
    o->pitch = getf(p + 24, le);
    o->yaw = getf(p + 28, le);
    for (int k = 0; k < 3; k++)
        if (!isfinite(o->offset[k]) || fabsf(o->offset[k]) > CIGI_DISTANCE_MAX) return CIGI_BAD_VALUE;
    if (!angle_ok(o->roll) || !angle_ok(o->pitch) || !angle_ok(o->yaw)) return CIGI_BAD_VALUE;
    return CIGI_PACKET;
}

/* A half-angle of a frustum: within a hemisphere of the view axis. */
static bool half_angle_ok(float a)
{
    return isfinite(a) && a > -90.0f && a < 90.0f;
}

static enum cigi_status view_definition(const uint8_t *p, bool le, struct cigi_view_definition *o)
{
    o->view_id = get16(p + 2, le);
    o->group_id = p[4];
    o->enable = p[5] & 0x3f;
    o->mirror = p[5] >> 6;
    o->pixel_replication = p[6] & 7;
    o->orthographic = p[6] >> 3 & 1;
    o->reorder = p[6] >> 4 & 1;
    o->view_type = p[6] >> 5;
    o->near_m = getf(p + 8, le);
    o->far_m = getf(p + 12, le);
    o->left = getf(p + 16, le);
    o->right = getf(p + 20, le);
    o->top = getf(p + 24, le);
    o->bottom = getf(p + 28, le);
    if (!(o->near_m >= 0.0f && o->near_m <= CIGI_DISTANCE_MAX) || !(o->far_m >= 0.0f && o->far_m <= CIGI_DISTANCE_MAX))
        return CIGI_BAD_VALUE;
    if (!half_angle_ok(o->left) || !half_angle_ok(o->right) || !half_angle_ok(o->top) || !half_angle_ok(o->bottom))
        return CIGI_BAD_VALUE;
    /* enabled in pairs, they must leave something to see */
    if ((o->enable & (CIGI_FOV_LEFT | CIGI_FOV_RIGHT)) == (CIGI_FOV_LEFT | CIGI_FOV_RIGHT) && o->left >= o->right)
        return CIGI_BAD_VALUE;
    if ((o->enable & (CIGI_FOV_TOP | CIGI_FOV_BOTTOM)) == (CIGI_FOV_TOP | CIGI_FOV_BOTTOM) && o->bottom >= o->top)
        return CIGI_BAD_VALUE;
    if ((o->enable & (CIGI_FOV_NEAR | CIGI_FOV_FAR)) == (CIGI_FOV_NEAR | CIGI_FOV_FAR) && o->near_m >= o->far_m)
        return CIGI_BAD_VALUE;
    return CIGI_PACKET;
}

/* The standard's size of a packet this parser reads, or 0 for any other. */
static size_t read_size(uint8_t id)
{
    switch (id) {
    case CIGI_IG_CONTROL: return CIGI_IG_CONTROL_SIZE;
    case CIGI_ENTITY_CONTROL: return CIGI_ENTITY_CONTROL_SIZE;
    case CIGI_VIEW_CONTROL: return CIGI_VIEW_CONTROL_SIZE;
    case CIGI_VIEW_DEFINITION: return CIGI_VIEW_DEFINITION_SIZE;
    default: return 0;
    }
}

static enum cigi_status body(const uint8_t *p, bool le, struct cigi_packet *out)
{
    switch (out->id) {
    case CIGI_IG_CONTROL: return ig_control(p, le, &out->ig_control);
    case CIGI_ENTITY_CONTROL: return entity_control(p, le, &out->entity);
    case CIGI_VIEW_CONTROL: return view_control(p, le, &out->view_control);
    case CIGI_VIEW_DEFINITION: return view_definition(p, le, &out->view_definition);
    default: return CIGI_OTHER;
    }
}

void cigi_message_init(struct cigi_message *m, const uint8_t *data, size_t len)
{
    *m = (struct cigi_message){.data = data, .len = len};
}

/* The first packet: IG Control, whose magic gives the message's byte order. */
static enum cigi_status first(struct cigi_message *m, const uint8_t *p, struct cigi_packet *out)
{
    enum cigi_status s = CIGI_PACKET;
    if (out->id != CIGI_IG_CONTROL) s = CIGI_NO_IG_CONTROL;
    else if (out->size != CIGI_IG_CONTROL_SIZE) s = CIGI_BAD_SIZE;
    else if ((s = byte_order(p, &m->little_endian)) == CIGI_PACKET) s = ig_control(p, m->little_endian, &out->ig_control);
    if (s != CIGI_PACKET) m->stopped = true; /* without its byte order, the rest cannot be read */
    return s;
}

bool cigi_message_next(struct cigi_message *m, struct cigi_packet *out, enum cigi_status *status)
{
    if (m->stopped || m->at >= m->len) return false;
    size_t left = m->len - m->at;
    const uint8_t *p = m->data + m->at;
    memset(out, 0, sizeof(*out));
    if (left < 2 || p[1] > left) {
        *status = CIGI_TRUNCATED;
        m->stopped = true;
        return true;
    }
    out->id = p[0];
    out->size = p[1];
    if (out->size < 2) {
        *status = CIGI_BAD_SIZE;
        m->stopped = true;
        return true;
    }
    bool was_first = m->at == 0;
    m->at += out->size;
    if (was_first) *status = first(m, p, out);
    else if (read_size(out->id) && out->size != read_size(out->id)) *status = CIGI_BAD_SIZE;
    else *status = body(p, m->little_endian, out);
    return true;
}

/* ---- Start of Frame ---------------------------------------------------------------------- */

size_t cigi_sof_encode(const struct cigi_start_of_frame *sof, bool little_endian,
                       uint8_t out[CIGI_START_OF_FRAME_SIZE])
{
    memset(out, 0, CIGI_START_OF_FRAME_SIZE);
    out[0] = CIGI_START_OF_FRAME;
    out[1] = CIGI_START_OF_FRAME_SIZE;
    out[2] = CIGI_VERSION;
    out[3] = (uint8_t)sof->database;
    out[4] = sof->ig_status;
    out[5] = (uint8_t)((sof->ig_mode & 3) | (sof->timestamp_valid ? 4 : 0) | CIGI_MINOR_VERSION << 4);
    put16(out + 6, CIGI_BYTE_SWAP_MAGIC, little_endian);
    put32(out + 8, sof->ig_frame, little_endian);
    put32(out + 12, sof->timestamp, little_endian);
    put32(out + 16, sof->last_host_frame, little_endian);
    return CIGI_START_OF_FRAME_SIZE;
}

enum cigi_status cigi_sof_decode(const uint8_t *buf, size_t len, struct cigi_start_of_frame *out,
                                 bool *little_endian)
{
    memset(out, 0, sizeof(*out));
    if (len < 2 || buf[1] > len) return CIGI_TRUNCATED;
    if (buf[0] != CIGI_START_OF_FRAME) return CIGI_OTHER;
    if (buf[1] != CIGI_START_OF_FRAME_SIZE) return CIGI_BAD_SIZE;
    if (buf[2] != CIGI_VERSION) return CIGI_BAD_VERSION;
    bool le = false;
    enum cigi_status s = byte_order(buf, &le);
    if (s != CIGI_PACKET) return s;
    *little_endian = le;
    out->database = (int8_t)buf[3];
    out->ig_status = buf[4];
    out->ig_mode = buf[5] & 3;
    out->timestamp_valid = buf[5] >> 2 & 1;
    out->ig_frame = get32(buf + 8, le);
    out->timestamp = get32(buf + 12, le);
    out->last_host_frame = get32(buf + 16, le);
    return CIGI_PACKET;
}

static const char *const status_names[CIGI_STATUS_COUNT] = {
    [CIGI_PACKET] = "a packet read", [CIGI_OTHER] = "another packet type",
    [CIGI_TRUNCATED] = "truncated", [CIGI_BAD_SIZE] = "a wrong size",
    [CIGI_NO_IG_CONTROL] = "a message that does not start with IG Control",
    [CIGI_BAD_VERSION] = "not CIGI version 3", [CIGI_BAD_MAGIC] = "a byte-swap magic other than 0x8000",
    [CIGI_BAD_VALUE] = "a value that is not a number or out of its range",
    [CIGI_OVERSIZED] = "a message over 8192 bytes",
};

const char *cigi_status_name(enum cigi_status status)
{
    return (unsigned)status < CIGI_STATUS_COUNT ? status_names[status] : "?";
}

bool cigi_status_malformed(enum cigi_status status)
{
    return status != CIGI_PACKET && status != CIGI_OTHER && (unsigned)status < CIGI_STATUS_COUNT;
}
