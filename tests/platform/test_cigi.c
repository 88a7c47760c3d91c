/* CIGI 3.3 on the image generator's side (platform/net/cigi/): the packet parser against
 * messages encoded here from the standard's layout (cigi_packet.h's table), in both byte orders,
 * every field; truncated, oversized and garbage messages; Start of Frame's bytes; the entity
 * table's starts and stops, identities and placement; the receiver's queue and counts; the
 * receiver over loopback (Start of Frame back to the sender, or to a given host); the scene's
 * cigi group. */
#include <arpa/inet.h>
#include <errno.h>
#include <math.h>
#include <poll.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "check.h"
#include "net/cigi/cigi_config.h"
#include "net/cigi/cigi_entities.h"
#include "net/cigi/cigi_packet.h"
#include "net/cigi/cigi_receiver.h"

#define LAT 48.137154
#define LON 11.576124
#define ALT 519.0

/* ---- an encoder of the test's own: by offset, in either byte order ---- */

static bool le;

static void w16(uint8_t *p, unsigned v)
{
    p[le ? 0 : 1] = (uint8_t)v, p[le ? 1 : 0] = (uint8_t)(v >> 8);
}

static void w32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++) p[le ? i : 3 - i] = (uint8_t)(v >> (8 * i));
}

static void wf(uint8_t *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    w32(p, u);
}

static void wd(uint8_t *p, double d)
{
    uint64_t u;
    memcpy(&u, &d, 8);
    for (int i = 0; i < 8; i++) p[le ? i : 7 - i] = (uint8_t)(u >> (8 * i));
}

/* IG Control: database 5, mode operate, timestamp valid, minor version 3 */
static size_t ig(uint8_t *p, uint32_t frame, uint32_t timestamp)
{
    memset(p, 0, 24);
    p[0] = 1, p[1] = 24, p[2] = 3, p[3] = (uint8_t)-3;
    p[4] = 1 | 4 | 8 | 3 << 4;
    w16(p + 6, 0x8000);
    w32(p + 8, frame);
    w32(p + 12, timestamp);
    w32(p + 16, 77);
    return 24;
}

struct ent {
    unsigned id, type, state, anim, parent;
    bool attached;
    double pos[3];
    float roll, pitch, yaw;
};

static size_t entity(uint8_t *p, const struct ent *e)
{
    memset(p, 0, 48);
    p[0] = 2, p[1] = 48;
    w16(p + 2, e->id);
    p[4] = (uint8_t)(e->state | (e->attached ? 4 : 0));
    p[5] = (uint8_t)(e->anim << 2);
    p[6] = 200;
    w16(p + 8, e->type);
    w16(p + 10, e->parent);
    wf(p + 12, e->roll), wf(p + 16, e->pitch), wf(p + 20, e->yaw);
    for (int k = 0; k < 3; k++) wd(p + 24 + 8 * k, e->pos[k]);
    return 48;
}

static size_t view_def(uint8_t *p, unsigned view, unsigned group, float l, float r, float b, float t)
{
    memset(p, 0, 32);
    p[0] = 21, p[1] = 32;
    w16(p + 2, view);
    p[4] = (uint8_t)group;
    p[5] = 0x3f | 1 << 6;          /* all six enabled, mirror mode 1 */
    p[6] = 2 | 1 << 3 | 1 << 4 | 3 << 5; /* pixel replication 2, orthographic, reorder, view type 3 */
    wf(p + 8, 0.25f), wf(p + 12, 9000.0f), wf(p + 16, l), wf(p + 20, r), wf(p + 24, t), wf(p + 28, b);
    return 32;
}

static size_t view_ctrl(uint8_t *p, unsigned view, unsigned group, unsigned ent)
{
    memset(p, 0, 32);
    p[0] = 16, p[1] = 32;
    w16(p + 2, view);
    p[4] = (uint8_t)group;
    p[5] = 0x2a; /* y, roll, yaw */
    w16(p + 6, ent);
    wf(p + 8, 1.5f), wf(p + 12, -2.5f), wf(p + 16, 3.5f), wf(p + 20, 4.0f), wf(p + 24, -5.0f), wf(p + 28, 60.0f);
    return 32;
}

static const struct ent effect_at_origin = {.id = 9, .type = 1001, .state = 1, .pos = {LAT, LON, ALT}};

/* ---- the parser ---- */

static void check_fields(const uint8_t *buf, size_t n, bool little)
{
    struct cigi_message m;
    struct cigi_packet p;
    enum cigi_status s;
    cigi_message_init(&m, buf, n);
    CHECK(cigi_message_next(&m, &p, &s) && s == CIGI_PACKET && p.id == 1 && m.little_endian == little);
    const struct cigi_ig_control *g = &p.ig_control;
    CHECK(g->version == 3 && g->minor_version == 3 && g->database == -3 && g->ig_mode == 1 && g->timestamp_valid &&
          g->extrapolation && g->host_frame == 0x01020304u && g->timestamp == 0xA0B0C0D0u && g->last_ig_frame == 77,
          "little %d: frame %x timestamp %x", little, g->host_frame, g->timestamp);
    CHECK(cigi_message_next(&m, &p, &s) && s == CIGI_PACKET && p.id == 2);
    const struct cigi_entity_control *e = &p.entity;
    CHECK(e->entity_id == 0xBEEF && e->entity_type == 0x1234 && e->parent_id == 0x0102 && e->state == 1 &&
          e->animation == 2 && e->alpha == 200 && !e->attached, "id %x type %x", e->entity_id, e->entity_type);
    CHECK(e->roll == 1.25f && e->pitch == -2.5f && e->yaw == 359.75f);
    CHECK(e->position[0] == LAT && e->position[1] == LON && e->position[2] == ALT);
    CHECK(cigi_message_next(&m, &p, &s) && s == CIGI_PACKET && p.id == 21);
    const struct cigi_view_definition *v = &p.view_definition;
    CHECK(v->view_id == 0x0203 && v->group_id == 4 && v->enable == 0x3f && v->mirror == 1 && v->pixel_replication == 2 &&
          v->orthographic && v->reorder && v->view_type == 3);
    CHECK(v->near_m == 0.25f && v->far_m == 9000.0f && v->left == -31.5f && v->right == 12.0f && v->bottom == -7.0f &&
          v->top == 22.0f);
    CHECK(cigi_message_next(&m, &p, &s) && s == CIGI_PACKET && p.id == 16);
    const struct cigi_view_control *c = &p.view_control;
    CHECK(c->view_id == 0x0203 && c->group_id == 0 && c->entity_id == 0x0405 && c->enable == 0x2a);
    CHECK(c->offset[0] == 1.5f && c->offset[1] == -2.5f && c->offset[2] == 3.5f && c->roll == 4.0f &&
          c->pitch == -5.0f && c->yaw == 60.0f);
    CHECK(cigi_message_next(&m, &p, &s) && s == CIGI_OTHER && p.id == 200 && p.size == 16, "skipped by its size");
    CHECK(!cigi_message_next(&m, &p, &s) && m.at == n);
}

static size_t full_message(uint8_t *buf)
{
    const struct ent e = {.id = 0xBEEF, .type = 0x1234, .state = 1, .anim = 2, .parent = 0x0102,
                          .pos = {LAT, LON, ALT}, .roll = 1.25f, .pitch = -2.5f, .yaw = 359.75f};
    size_t n = ig(buf, 0x01020304u, 0xA0B0C0D0u);
    n += entity(buf + n, &e);
    n += view_def(buf + n, 0x0203, 4, -31.5f, 12.0f, -7.0f, 22.0f);
    n += view_ctrl(buf + n, 0x0203, 0, 0x0405);
    memset(buf + n, 0, 16);
    buf[n] = 200, buf[n + 1] = 16;
    return n + 16;
}

CHECK_TEST(every_field_in_both_byte_orders)
{
    uint8_t buf[256];
    for (int order = 0; order < 2; order++) {
        le = order == 1;
        size_t n = full_message(buf);
        CHECK(buf[6] == (le ? 0x00 : 0x80) && buf[7] == (le ? 0x80 : 0x00), "the magic as the wire has it");
        check_fields(buf, n, le);
    }
    le = false;
}

/* Every cut of a message: no read past it, the packets before the cut read, the cut one truncated. */
CHECK_TEST(truncated_messages_at_every_length)
{
    uint8_t buf[256], copy[256];
    size_t n = full_message(buf);
    const size_t ends[] = {24, 72, 104, 136, 152};
    for (size_t cut = 1; cut < n; cut++) {
        memcpy(copy, buf, cut); /* a copy of exactly cut bytes: ASan sees any read past it */
        uint8_t *exact = malloc(cut);
        memcpy(exact, copy, cut);
        struct cigi_message m;
        struct cigi_packet p;
        enum cigi_status s;
        cigi_message_init(&m, exact, cut);
        int whole = 0, truncated = 0, other = 0;
        while (cigi_message_next(&m, &p, &s)) {
            if (s == CIGI_PACKET || s == CIGI_OTHER) whole++;
            else if (s == CIGI_TRUNCATED) truncated++;
            else other++;
        }
        int expect = 0;
        while (expect < 5 && ends[expect] <= cut) expect++;
        bool boundary = expect > 0 && ends[expect - 1] == cut;
        CHECK(whole == expect && truncated == !boundary && other == 0, "cut at %zu: %d whole, %d truncated, %d other", cut,
              whole, truncated, other);
        free(exact);
    }
}

static enum cigi_status first_status(const uint8_t *buf, size_t n)
{
    struct cigi_message m;
    struct cigi_packet p;
    enum cigi_status s = CIGI_STATUS_COUNT;
    cigi_message_init(&m, buf, n);
    cigi_message_next(&m, &p, &s);
    return s;
}

/* The status of the n-th packet (0: the first) and how many packets the message had. */
static enum cigi_status nth_status(const uint8_t *buf, size_t len, int nth, int *count)
{
    struct cigi_message m;
    struct cigi_packet p;
    enum cigi_status s, found = CIGI_STATUS_COUNT;
    cigi_message_init(&m, buf, len);
    *count = 0;
    while (cigi_message_next(&m, &p, &s))
        if ((*count)++ == nth) found = s;
    return found;
}

CHECK_TEST(malformed_messages_are_named)
{
    uint8_t buf[256];
    size_t n = full_message(buf);
    int count;
    buf[0] = 2;
    CHECK(first_status(buf, n) == CIGI_NO_IG_CONTROL && nth_status(buf, n, 0, &count) && count == 1,
          "no IG Control first: the whole message");
    buf[0] = 1, buf[2] = 2;
    CHECK(first_status(buf, n) == CIGI_BAD_VERSION, "CIGI 2");
    buf[2] = 3, buf[6] = 0x12;
    CHECK(first_status(buf, n) == CIGI_BAD_MAGIC && (nth_status(buf, n, 0, &count), count == 1), "magic 0x1200");
    buf[6] = 0x80, buf[1] = 16;
    CHECK(first_status(buf, n) == CIGI_BAD_SIZE, "a CIGI 3.0 IG Control (16 bytes)");
    buf[1] = 0;
    CHECK(first_status(buf, n) == CIGI_BAD_SIZE && (nth_status(buf, n, 0, &count), count == 1), "size 0: no way on");
    buf[1] = 24;
    uint8_t odd[96] = {0};
    size_t k = ig(odd, 1, 1);
    odd[k] = 2, odd[k + 1] = 40; /* Entity Control, 40 bytes: a wrong size, skipped by it */
    odd[k + 40] = 99, odd[k + 41] = 8;
    CHECK(nth_status(odd, k + 48, 1, &count) == CIGI_BAD_SIZE && count == 3, "%d packets", count);
    CHECK(nth_status(odd, k + 48, 2, &count) == CIGI_OTHER, "the next packet starts 40 bytes on");
    uint8_t big[128] = {0};
    k = ig(big, 1, 1);
    big[k] = 21, big[k + 1] = 40; /* View Definition, 40 bytes: oversized, skipped by its size */
    big[k + 40] = 99, big[k + 41] = 8;
    CHECK(nth_status(big, k + 48, 1, &count) == CIGI_BAD_SIZE && count == 3 &&
          nth_status(big, k + 48, 2, &count) == CIGI_OTHER, "an oversized View Definition");
    buf[72 + 1] = 1; /* size 1 */
    CHECK(nth_status(buf, n, 2, &count) == CIGI_BAD_SIZE && count == 3);
    buf[72 + 1] = 255; /* past the end */
    CHECK(nth_status(buf, n, 2, &count) == CIGI_TRUNCATED && count == 3);
    CHECK(first_status(buf, 0) == CIGI_STATUS_COUNT && first_status(buf, 1) == CIGI_TRUNCATED, "empty, one byte");
}

CHECK_TEST(values_that_are_not_numbers_or_out_of_range)
{
    uint8_t buf[128];
    int count;
    struct ent e = effect_at_origin;
    const double bad_positions[][3] = {{NAN, LON, ALT}, {LAT, INFINITY, ALT}, {LAT, LON, -NAN}, {90.5, LON, ALT},
                                       {LAT, -180.5, ALT}, {LAT, LON, 1e300}, {LAT, LON, -2e7}};
    for (size_t i = 0; i < sizeof(bad_positions) / sizeof(bad_positions[0]); i++) {
        memcpy(e.pos, bad_positions[i], sizeof(e.pos));
        size_t n = ig(buf, 1, 1);
        n += entity(buf + n, &e);
        CHECK(nth_status(buf, n, 1, &count) == CIGI_BAD_VALUE, "position %zu", i);
    }
    e = effect_at_origin;
    e.attached = true, e.pos[0] = 500.0; /* an offset from the parent, not a latitude */
    size_t n = ig(buf, 1, 1) + 0;
    n += entity(buf + n, &e);
    CHECK(nth_status(buf, n, 1, &count) == CIGI_PACKET, "an attached entity's 500 m x offset");
    e = effect_at_origin, e.yaw = NAN;
    n = ig(buf, 1, 1);
    n += entity(buf + n, &e);
    CHECK(nth_status(buf, n, 1, &count) == CIGI_BAD_VALUE, "yaw NaN");
    const float frusta[][4] = {{10, -10, -5, 5}, {-10, 10, 5, -5}, {-90, 10, -5, 5}, {-10, NAN, -5, 5}};
    for (size_t i = 0; i < 4; i++) {
        n = ig(buf, 1, 1);
        n += view_def(buf + n, 1, 0, frusta[i][0], frusta[i][1], frusta[i][2], frusta[i][3]);
        CHECK(nth_status(buf, n, 1, &count) == CIGI_BAD_VALUE, "frustum %zu", i);
    }
}

CHECK_TEST(start_of_frame_bytes)
{
    const struct cigi_start_of_frame sof = {.database = -2, .ig_status = 7, .ig_mode = 1, .timestamp_valid = true,
                                            .ig_frame = 0x11223344u, .timestamp = 0x55667788u,
                                            .last_host_frame = 0x99AABBCCu};
    uint8_t b[CIGI_START_OF_FRAME_SIZE];
    const uint8_t be_bytes[24] = {101, 24, 3, 0xFE, 7, 1 | 4 | 3 << 4, 0x80, 0x00, 0x11, 0x22, 0x33, 0x44,
                                  0x55, 0x66, 0x77, 0x88, 0x99, 0xAA, 0xBB, 0xCC, 0, 0, 0, 0};
    CHECK(cigi_sof_encode(&sof, false, b) == 24 && memcmp(b, be_bytes, 24) == 0, "big-endian, byte by byte");
    cigi_sof_encode(&sof, true, b);
    CHECK(b[6] == 0x00 && b[7] == 0x80 && b[8] == 0x44 && b[11] == 0x11 && b[16] == 0xCC && b[19] == 0x99,
          "little-endian");
    struct cigi_start_of_frame back;
    bool little = false;
    CHECK(cigi_sof_decode(b, 24, &back, &little) == CIGI_PACKET && little);
    CHECK(back.database == -2 && back.ig_status == 7 && back.ig_mode == 1 && back.timestamp_valid &&
          back.ig_frame == sof.ig_frame && back.timestamp == sof.timestamp && back.last_host_frame == sof.last_host_frame);
    CHECK(cigi_sof_decode(b, 23, &back, &little) == CIGI_TRUNCATED);
}

/* ---- the receiver ---- */

static struct cigi_settings settings(void)
{
    struct cigi_settings s = {.have_origin = true, .origin = {LAT, LON, ALT}, .view_id = CIGI_ANY_VIEW};
    s.effects.count = 2;
    s.effects.rules[0] = (struct cigi_effect_rule){.entity_type = 1001, .effect = "explosion"};
    s.effects.rules[1] = (struct cigi_effect_rule){.entity_type = 1002, .effect = "smoke"};
    return s;
}

static struct cigi_receiver *made(const struct cigi_settings *s)
{
    struct cigi_receiver *r = NULL;
    char err[256];
    CHECK(cigi_receiver_make(&r, s, err, sizeof(err)) == 0, "%s", err);
    return r;
}

/* One message: IG Control (frame) and an Entity Control. */
static void send_entity(struct cigi_receiver *r, uint32_t frame, const struct ent *e)
{
    uint8_t buf[128];
    size_t n = ig(buf, frame, frame * 1667u);
    n += entity(buf + n, e);
    cigi_receiver_datagram(r, buf, n, false, NULL, frame);
}

/* The events waiting: the effect starts and stops only, into out; how many. */
static int effects(struct cigi_receiver *r, struct cigi_event *out, int max)
{
    struct cigi_event e;
    int n = 0;
    while (cigi_receiver_next(r, &e))
        if ((e.kind == CIGI_EVENT_EFFECT_START || e.kind == CIGI_EVENT_EFFECT_STOP) && n < max) out[n++] = e;
    return n;
}

static bool counts_add_up(const struct cigi_counts *c)
{
    return c->packets == c->used + c->ignored + c->malformed;
}

CHECK_TEST(effect_starts_and_stops_with_generations)
{
    struct cigi_settings s = settings();
    struct cigi_receiver *r = made(&s);
    struct cigi_event ev[4];
    struct ent e = effect_at_origin;
    send_entity(r, 10, &e);
    CHECK(effects(r, ev, 4) == 1 && ev[0].kind == CIGI_EVENT_EFFECT_START && ev[0].effect.generation == 1 &&
          ev[0].effect.activation_frame == 10 && !strcmp(ev[0].effect.effect, "explosion"));
    CHECK(ev[0].effect.identity == (UINT64_C(1) << 62) + (UINT64_C(9) << 32) + 10);
    CHECK(ev[0].time.host_frame == 10 && ev[0].time.timestamp == 16670 && ev[0].time.timestamp_valid);
    send_entity(r, 11, &e);
    CHECK(effects(r, ev, 4) == 0, "Active again: still the same effect");
    e.state = 2;
    send_entity(r, 12, &e);
    CHECK(effects(r, ev, 4) == 1 && ev[0].kind == CIGI_EVENT_EFFECT_STOP && ev[0].effect.reason == CIGI_STOP_DESTROYED &&
          ev[0].effect.generation == 1 && ev[0].effect.activation_frame == 10, "Destroyed: its identity in the stop");
    send_entity(r, 13, &e);
    CHECK(effects(r, ev, 4) == 0, "Destroyed again: nothing");
    e.state = 1, e.type = 1002;
    send_entity(r, 20, &e);
    CHECK(effects(r, ev, 4) == 1 && ev[0].effect.generation == 2 && ev[0].effect.activation_frame == 20 &&
          !strcmp(ev[0].effect.effect, "smoke"), "re-activated: generation 2, a new identity");
    e.state = 0;
    send_entity(r, 21, &e);
    CHECK(effects(r, ev, 4) == 1 && ev[0].effect.reason == CIGI_STOP_INACTIVE);
    const struct cigi_counts *c = cigi_receiver_counts(r);
    CHECK(c->entities == 2 && c->stops == 2 && c->active == 0 && counts_add_up(c));
    cigi_receiver_close(r);
}

CHECK_TEST(animation_stop_ends_and_play_restarts)
{
    struct cigi_settings s = settings();
    struct cigi_receiver *r = made(&s);
    struct cigi_event ev[4];
    struct ent e = effect_at_origin;
    e.anim = CIGI_ANIMATION_PLAY;
    send_entity(r, 1, &e);
    CHECK(effects(r, ev, 4) == 1 && ev[0].kind == CIGI_EVENT_EFFECT_START);
    e.anim = CIGI_ANIMATION_STOP;
    send_entity(r, 2, &e);
    CHECK(effects(r, ev, 4) == 1 && ev[0].kind == CIGI_EVENT_EFFECT_STOP && ev[0].effect.reason == CIGI_STOP_ANIMATION);
    send_entity(r, 3, &e);
    CHECK(effects(r, ev, 4) == 0, "stopped, Active: stays off");
    e.anim = CIGI_ANIMATION_PLAY;
    send_entity(r, 4, &e);
    CHECK(effects(r, ev, 4) == 1 && ev[0].kind == CIGI_EVENT_EFFECT_START && ev[0].effect.generation == 2 &&
          ev[0].effect.activation_frame == 4, "played again");
    /* a host that never plays an animation: Active to Destroyed */
    struct ent quiet = effect_at_origin;
    quiet.id = 10;
    send_entity(r, 5, &quiet);
    send_entity(r, 6, &quiet);
    CHECK(effects(r, ev, 4) == 1 && ev[0].kind == CIGI_EVENT_EFFECT_START, "animation 0 from the start: runs");
    cigi_receiver_close(r);
}

CHECK_TEST(what_is_ignored)
{
    struct cigi_settings s = settings();
    struct cigi_receiver *r = made(&s);
    struct cigi_event ev[4];
    struct ent e = effect_at_origin;
    e.type = 5; /* a tank, not an effect */
    send_entity(r, 1, &e);
    e.type = 1001, e.attached = true, e.pos[0] = 3.0;
    send_entity(r, 2, &e);
    CHECK(effects(r, ev, 4) == 0);
    uint8_t buf[64];
    size_t n = ig(buf, 3, 3);
    memset(buf + n, 0, 24);
    buf[n] = 101, buf[n + 1] = 24; /* a Start of Frame, from another IG */
    cigi_receiver_datagram(r, buf, n + 24, false, NULL, 3);
    const struct cigi_counts *c = cigi_receiver_counts(r);
    CHECK(c->ignored_by[CIGI_IGNORED_NOT_EFFECT] == 1 && c->ignored_by[CIGI_IGNORED_ATTACHED] == 1 &&
          c->ignored_by[CIGI_IGNORED_TYPE] == 1 && c->ignored == 3 && c->used == 3 && counts_add_up(c),
          "used %llu ignored %llu", (unsigned long long)c->used, (unsigned long long)c->ignored);
    cigi_receiver_close(r);
}

CHECK_TEST(placement_through_the_origin)
{
    struct cigi_settings s = settings();
    struct cigi_receiver *r = made(&s);
    struct cigi_event ev[2];
    struct ent e = effect_at_origin;
    e.pos[2] = ALT + 50.0;
    send_entity(r, 1, &e);
    CHECK(effects(r, ev, 2) == 1);
    CHECK_NEAR(ev[0].effect.position[0], 0.0, 1e-4);
    CHECK_NEAR(ev[0].effect.position[1], 50.0, 1e-4);
    CHECK_NEAR(ev[0].effect.position[2], 0.0, 1e-4);
    /* 0.001° north: the meridian's radius of curvature at the latitude, M = a (1 - e²) / w³ */
    double f = 1.0 / 298.257223563, e2 = f * (2 - f), sl = sin(LAT * M_PI / 180), w = sqrt(1 - e2 * sl * sl);
    double north = 6378137.0 * (1 - e2) / (w * w * w) * 0.001 * M_PI / 180;
    e = effect_at_origin, e.id = 11, e.pos[0] = LAT + 0.001;
    send_entity(r, 2, &e);
    CHECK(effects(r, ev, 2) == 1);
    CHECK_NEAR(ev[0].effect.position[2], -north, 0.01);
    CHECK_NEAR(ev[0].effect.position[0], 0.0, 0.01);
    CHECK(ev[0].effect.geodetic[0] == LAT + 0.001, "as sent");
    cigi_receiver_close(r);
}

CHECK_TEST(ownship_and_views)
{
    struct cigi_settings s = settings();
    s.view_id = 2;
    struct cigi_receiver *r = made(&s);
    uint8_t buf[256];
    struct ent own = {.id = 0, .type = 7, .state = 1, .pos = {LAT, LON, ALT + 1000.0}, .yaw = 90.0f, .pitch = 5.0f};
    size_t n = ig(buf, 1, 1);
    n += entity(buf + n, &own);
    n += view_def(buf + n, 1, 0, -30, 30, -20, 20);   /* another view: ignored */
    n += view_def(buf + n, 2, 6, -10, 50, -15, 25);   /* ours, in group 6 */
    n += view_ctrl(buf + n, 1, 0, 0);                 /* another view */
    n += view_ctrl(buf + n, 9, 6, 0);                 /* our group */
    cigi_receiver_datagram(r, buf, n, false, NULL, 1);
    struct cigi_event e;
    int kinds[8] = {0};
    while (cigi_receiver_next(r, &e)) {
        kinds[e.kind]++;
        if (e.kind == CIGI_EVENT_OWNSHIP) {
            CHECK_NEAR(e.ownship.position[1], 1000.0, 1e-3);
            CHECK(e.ownship.yaw == 90.0f && e.ownship.pitch == 5.0f);
        }
        if (e.kind == CIGI_EVENT_VIEW_DEFINITION)
            CHECK(e.view_definition.view_id == 2 && e.view_definition.left == -10.0f && e.view_definition.right == 50.0f &&
                  e.view_definition.bottom == -15.0f && e.view_definition.top == 25.0f);
        if (e.kind == CIGI_EVENT_VIEW_CONTROL) CHECK(e.view_control.group_id == 6 && e.view_control.yaw == 60.0f);
    }
    CHECK(kinds[CIGI_EVENT_FRAME] == 1 && kinds[CIGI_EVENT_OWNSHIP] == 1 && kinds[CIGI_EVENT_VIEW_DEFINITION] == 1 &&
          kinds[CIGI_EVENT_VIEW_CONTROL] == 1);
    CHECK(cigi_receiver_counts(r)->ignored_by[CIGI_IGNORED_VIEW] == 2);
    cigi_receiver_close(r);
}

/* A full queue: the start that finds no room is counted, not lost: the next Active starts it. */
CHECK_TEST(a_full_queue_counts_and_retries)
{
    struct cigi_settings s = settings();
    struct cigi_receiver *r = made(&s);
    struct ent e = effect_at_origin;
    for (uint32_t f = 1; cigi_receiver_pending(r) < CIGI_EVENTS_MAX; f++) {
        e.id = 100 + f;
        send_entity(r, f, &e);
    }
    const struct cigi_counts *c = cigi_receiver_counts(r);
    uint64_t started = c->entities;
    e.id = 7;
    send_entity(r, 5000, &e);
    CHECK(c->events_dropped >= 1 && c->entities == started, "dropped %llu", (unsigned long long)c->events_dropped);
    struct cigi_event ev[1];
    effects(r, ev, 0);
    send_entity(r, 5001, &e);
    CHECK(effects(r, ev, 1) == 1 && ev[0].effect.entity_id == 7 && ev[0].effect.generation == 1 &&
          ev[0].effect.activation_frame == 5001);
    cigi_receiver_close(r);
}

CHECK_TEST(the_host_clock_unwraps)
{
    struct cigi_settings s = settings();
    struct cigi_receiver *r = made(&s);
    const uint32_t ticks[] = {0xFFFFFF00u, 0x00000100u, 0xFFFFFF80u /* late, from before the wrap */, 0x00000200u};
    double seconds[4];
    for (int i = 0; i < 4; i++) {
        uint8_t buf[32];
        cigi_receiver_datagram(r, buf, ig(buf, (uint32_t)i, ticks[i]), false, NULL, i);
        struct cigi_event e;
        CHECK(cigi_receiver_next(r, &e) && e.kind == CIGI_EVENT_FRAME);
        seconds[i] = e.time.seconds;
    }
    CHECK_NEAR(seconds[1] - seconds[0], 0x200 * 1e-5, 1e-9);
    CHECK_NEAR(seconds[2] - seconds[0], 0x80 * 1e-5, 1e-9);
    CHECK_NEAR(seconds[3] - seconds[1], 0x100 * 1e-5, 1e-9);
    cigi_receiver_close(r);
}

/* Garbage: random bytes, and random edits of a good message; every packet counted once. */
CHECK_TEST(garbage_is_counted_never_a_crash)
{
    struct cigi_settings s = settings();
    struct cigi_receiver *r = made(&s);
    uint8_t good[256], buf[256];
    size_t n = full_message(good);
    uint32_t x = 12345;
    for (int i = 0; i < 20000; i++) {
        size_t len = i % 2 ? n : 1 + (x % 255);
        memcpy(buf, good, n);
        for (int k = 0; k < 4; k++) {
            x = x * 1664525u + 1013904223u;
            buf[(x >> 8) % (i % 2 ? n : sizeof(buf))] = (uint8_t)(x >> 24);
        }
        cigi_receiver_datagram(r, buf, len, false, NULL, i);
        struct cigi_event e;
        while (cigi_receiver_next(r, &e)) {}
    }
    cigi_receiver_datagram(r, buf, 9000, true, NULL, 0);
    const struct cigi_counts *c = cigi_receiver_counts(r);
    CHECK(c->messages == 20001 && counts_add_up(c) && c->malformed_by[CIGI_OVERSIZED] == 1 && c->malformed > 0,
          "messages %llu packets %llu", (unsigned long long)c->messages, (unsigned long long)c->packets);
    cigi_receiver_close(r);
}

/* ---- over loopback ---- */

static struct cigi_receiver *open_on_loopback(struct cigi_settings *s, int *port)
{
    char err[512];
    for (int attempt = 0; attempt < 50; attempt++) {
        *port = 20000 + (int)((getpid() * 7919u + (unsigned)attempt * 104729u) % 40000u);
        char text[32];
        snprintf(text, sizeof(text), "127.0.0.1:%d", *port);
        if (udp_endpoint_parse(text, &s->listen, err, sizeof(err)) != 0) break;
        struct cigi_receiver *r = NULL;
        if (cigi_receiver_open(&r, s, err, sizeof(err)) == 0) return r;
    }
    CHECK(0, "no port: %s", err);
    return NULL;
}

static int host_socket(int *port)
{
    int fd = socket(AF_INET, SOCK_DGRAM, 0);
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t len = sizeof(a);
    if (fd < 0 || bind(fd, (struct sockaddr *)&a, sizeof(a)) != 0 || getsockname(fd, (struct sockaddr *)&a, &len) != 0)
        return -1;
    *port = ntohs(a.sin_port);
    return fd;
}

static bool wait_readable(int fd)
{
    struct pollfd p = {.fd = fd, .events = POLLIN};
    return poll(&p, 1, 5000) == 1;
}

static void loopback(bool to_given_host)
{
    struct cigi_settings s = settings();
    int port = 0, host_port = 0, other_port = 0;
    int host = host_socket(&host_port), other = host_socket(&other_port);
    if (to_given_host) {
        char text[32];
        snprintf(text, sizeof(text), "127.0.0.1:%d", other_port);
        char err[128];
        s.have_host = udp_endpoint_parse(text, &s.host, err, sizeof(err)) == 0;
    }
    struct cigi_receiver *r = open_on_loopback(&s, &port);
    if (!r || host < 0 || other < 0) return;
    struct cigi_sof_info info = {.ig_frame = 1, .timestamp = 42, .timestamp_valid = true};
    char err[256];
    CHECK(to_given_host || cigi_receiver_send_sof(r, &info, err, sizeof(err)) == 0, "no host known yet");
    le = true;
    uint8_t buf[128];
    size_t n = ig(buf, 500, 1000);
    n += entity(buf + n, &effect_at_origin);
    le = false;
    struct sockaddr_in to = {.sin_family = AF_INET, .sin_port = htons((uint16_t)port),
                             .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    CHECK(sendto(host, buf, n, 0, (struct sockaddr *)&to, sizeof(to)) == (ssize_t)n);
    CHECK(wait_readable(cigi_receiver_fd(r)) && cigi_receiver_service(r, 1) == 1);
    struct cigi_event ev[2];
    CHECK(effects(r, ev, 2) == 1 && ev[0].effect.activation_frame == 500);
    CHECK(cigi_receiver_send_sof(r, &info, err, sizeof(err)) == 1, "%s", err);
    int reply_to = to_given_host ? other : host;
    uint8_t back[64];
    CHECK(wait_readable(reply_to) && recv(reply_to, back, sizeof(back), 0) == 24);
    CHECK(back[0] == 101 && back[1] == 24 && back[6] == 0x00 && back[7] == 0x80, "in the host's (little-endian) order");
    CHECK(back[16] == 0xF4 && back[17] == 0x01 && back[18] == 0 && back[19] == 0, "last host frame 500");
    CHECK(back[3] == (uint8_t)-3 && (back[5] & 3) == 1, "the database and IG mode the host asked for");
    const struct cigi_counts *c = cigi_receiver_counts(r);
    CHECK(c->sof_sent == 1 && c->sof_unaddressed == (to_given_host ? 0u : 1u) && c->messages == 1);
    cigi_receiver_close(r);
    close(host), close(other);
}

CHECK_TEST(loopback_start_of_frame_to_the_sender) { loopback(false); }
CHECK_TEST(loopback_start_of_frame_to_the_given_host) { loopback(true); }

/* ---- the scene's cigi group ---- */

static const char *scene_file(const char *text)
{
    static char path[64];
    snprintf(path, sizeof(path), "/tmp/test_cigi_%d.cfg", (int)getpid());
    FILE *f = fopen(path, "w");
    fputs(text, f);
    fclose(f);
    return path;
}

static int known_effect(const char *name, char *why, size_t n, void *user)
{
    (void)user;
    if (!strcmp(name, "explosion") || !strcmp(name, "smoke")) return 0;
    snprintf(why, n, "the scene has no effect of that name (its effects: explosion, smoke)");
    return -1;
}

static int read_scene(const char *text, struct cigi_settings *s, bool *found, char *err, size_t n)
{
    memset(s, 0, sizeof(*s));
    int rc = cigi_config_read(scene_file(text), s, found, known_effect, NULL, err, n);
    unlink(scene_file(""));
    return rc;
}

CHECK_TEST(scene_cigi_effects)
{
    struct cigi_settings s;
    bool found;
    char err[512] = "";
    CHECK(read_scene("dis = { origin = [48.1, 11.5, 500.0]; };\ncigi = { effects = (\n { entity_type = 1001; "
                     "effect = \"explosion\"; },\n { entity_type = 7; effect = \"smoke\"; } ); };\n",
                     &s, &found, err, sizeof(err)) == 0, "%s", err);
    CHECK(found && s.have_origin && s.origin[0] == 48.1 && s.origin[2] == 500.0 && s.effects.count == 2);
    const char *seven = cigi_effect_find(&s.effects, 7);
    CHECK(seven && !strcmp(seven, "smoke") && !cigi_effect_find(&s.effects, 8));
    CHECK(read_scene("cigi = { effects = (\n { entity_type = 1; effect = \"fireworks\"; } ); };\n", &s, &found, err,
                     sizeof(err)) == -EINVAL && strstr(err, ":2: cigi.effects: entity_type 1 sets off 'fireworks': "
                                                             "the scene has no effect of that name"), "%s", err);
    CHECK(read_scene("cigi = { effects = ( { entity_type = 70000; effect = \"smoke\"; } ); };", &s, &found, err,
                     sizeof(err)) == -EINVAL && strstr(err, "0..65535"), "%s", err);
    CHECK(read_scene("cigi = { effects = ( { entity_type = 3; effect = \"smoke\"; }, { entity_type = 3; effect = "
                     "\"explosion\"; } ); };", &s, &found, err, sizeof(err)) == -EINVAL && strstr(err, "twice"), "%s", err);
    CHECK(read_scene("cigi = { effect = (); };", &s, &found, err, sizeof(err)) == -EINVAL &&
          strstr(err, "unknown key 'effect' in cigi"), "%s", err);
    CHECK(read_scene("cigi = { effects = ( { entity_type = 3; } ); };", &s, &found, err, sizeof(err)) == -EINVAL &&
          strstr(err, "effect = \"NAME\""), "%s", err);
    CHECK(read_scene("scene = 1;", &s, &found, err, sizeof(err)) == 0 && !found && !s.have_origin);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
