/* DIS without a network (platform/net/): the PDU parser against PDUs encoded here from the
 * standard's layout, the WGS-84 conversions, the effect table, the repeat filter, the receiver's
 * counters and placement, and the one trigger queue (platform/player/inputs/trigger_queue.c). */
#include <math.h>
#include <string.h>

#include "check.h"
#include "gpio/effect_at.h"
#include "net/common/geodesy.h"
#include "net/dis/dis_effects.h"
#include "net/dis/dis_events.h"
#include "net/dis/dis_pdu.h"
#include "net/dis/dis_receiver.h"
#include "player/inputs/trigger_queue.h"

/* ---- a Detonation PDU, big-endian by offset (IEEE 1278.1; dis_pdu.h's table) ---- */

static void be16(uint8_t *p, unsigned v) { p[0] = (uint8_t)(v >> 8), p[1] = (uint8_t)v; }

static void be64(uint8_t *p, double d)
{
    uint64_t b;
    memcpy(&b, &d, 8);
    for (int i = 0; i < 8; i++) p[i] = (uint8_t)(b >> (56 - 8 * i));
}

/* version, exercise, event, munition type, result, ECEF location, variable parameters */
static size_t encode(uint8_t *p, int version, int exercise, unsigned event, const uint8_t type[8], int result,
                     const double ecef[3], int vp)
{
    size_t len = 104 + 16 * (size_t)vp;
    memset(p, 0, len);
    p[0] = (uint8_t)version, p[1] = (uint8_t)exercise, p[2] = 3, p[3] = 2;
    be16(p + 8, (unsigned)len);
    be16(p + 30, 7), be16(p + 32, 8), be16(p + 34, event); /* event: site 7, application 8 */
    for (int k = 0; k < 3; k++) be64(p + 48 + 8 * k, ecef[k]);
    memcpy(p + 72, type, 8); /* kind, domain, country (2), category, subcategory, specific, extra */
    p[100] = (uint8_t)result, p[101] = (uint8_t)vp;
    return len;
}

static const uint8_t howitzer[8] = {2, 9, 0, 225, 2, 14, 1, 0}; /* 2.9.225.2.14.1.0 */

CHECK_TEST(detonation_fields_read_from_their_offsets)
{
    uint8_t buf[256];
    const double at[3] = {4177949.8163, 855897.7993, 4727453.7743};
    for (int version = 6; version <= 7; version++) {
        size_t len = encode(buf, version, 3, 4242, howitzer, 7, at, 2);
        struct dis_pdu pdu;
        size_t used = 0;
        CHECK(dis_pdu_parse(buf, len, &pdu, &used) == DIS_DETONATION, "version %d", version);
        const struct dis_detonation *d = &pdu.detonation;
        CHECK(used == 136 && pdu.header.version == version && pdu.header.exercise == 3 && pdu.header.length == 136);
        CHECK(d->event.site == 7 && d->event.application == 8 && d->event.entity == 4242);
        CHECK(d->location[0] == at[0] && d->location[1] == at[1] && d->location[2] == at[2]);
        const struct dis_entity_type *t = &d->munition_type;
        CHECK(t->kind == 2 && t->domain == 9 && t->country == 225 && t->category == 2 && t->subcategory == 14 &&
              t->specific == 1 && t->extra == 0, "%u.%u.%u.%u.%u.%u.%u", t->kind, t->domain, t->country,
              t->category, t->subcategory, t->specific, t->extra);
        CHECK(d->result == 7 && d->variable_parameters == 2);
    }
}

CHECK_TEST(malformed_pdus_are_named)
{
    uint8_t buf[256];
    const double at[3] = {6378137.0, 0, 0};
    struct dis_pdu pdu;
    size_t used, len = encode(buf, 7, 1, 1, howitzer, 5, at, 0);
    CHECK(dis_pdu_parse(buf, 11, &pdu, &used) == DIS_TRUNCATED && used == 11, "shorter than a header");
    CHECK(dis_pdu_parse(buf, len - 1, &pdu, &used) == DIS_TRUNCATED, "shorter than its length field");
    buf[0] = 5;
    CHECK(dis_pdu_parse(buf, len, &pdu, &used) == DIS_BAD_VERSION, "DIS 1995");
    buf[0] = 8;
    CHECK(dis_pdu_parse(buf, len, &pdu, &used) == DIS_BAD_VERSION, "version 8");
    buf[0] = 7;
    be16(buf + 8, 11);
    CHECK(dis_pdu_parse(buf, len, &pdu, &used) == DIS_BAD_LENGTH, "length under a header");
    be16(buf + 8, 100);
    CHECK(dis_pdu_parse(buf, len, &pdu, &used) == DIS_BAD_LENGTH, "a detonation of 100 bytes");
    be16(buf + 8, 104);
    buf[101] = 1; /* one variable parameter record announced, none there */
    CHECK(dis_pdu_parse(buf, len, &pdu, &used) == DIS_BAD_LENGTH && used == 104, "wrong record count");
    buf[101] = 0, buf[3] = 1;
    CHECK(dis_pdu_parse(buf, len, &pdu, &used) == DIS_BAD_FAMILY);
    buf[3] = 2;
    const double nan_at[3] = {NAN, 0, 0};
    encode(buf, 6, 1, 1, howitzer, 5, nan_at, 0);
    CHECK(dis_pdu_parse(buf, len, &pdu, &used) == DIS_BAD_LOCATION);
    buf[2] = 1; /* an Entity State PDU: another type, its body unread */
    CHECK(dis_pdu_parse(buf, len, &pdu, &used) == DIS_OTHER && used == len);
    for (int s = DIS_DETONATION; s < DIS_STATUS_COUNT; s++)
        CHECK(strcmp(dis_status_name((enum dis_status)s), "?") != 0 &&
              dis_status_malformed((enum dis_status)s) == (s != DIS_DETONATION && s != DIS_OTHER));
}

CHECK_TEST(bundled_pdus_are_read_in_turn)
{
    uint8_t buf[512];
    const double at[3] = {6378137.0, 0, 0};
    size_t a = encode(buf, 7, 1, 1, howitzer, 5, at, 0);
    memset(buf + a, 0, 4); /* padding to an 8-byte boundary */
    size_t b = encode(buf + a + 4, 6, 1, 2, howitzer, 5, at, 1);
    buf[a + 4 + b] = 0x42; /* a stray byte: a truncated PDU */
    struct dis_cursor c;
    struct dis_pdu pdu;
    enum dis_status st[4];
    int n = 0;
    dis_cursor_init(&c, buf, a + 4 + b + 1);
    while (n < 4 && dis_cursor_next(&c, &pdu, &st[n])) n++;
    CHECK(n == 3 && st[0] == DIS_DETONATION && st[1] == DIS_DETONATION && st[2] == DIS_TRUNCATED,
          "%d PDUs: %d %d %d", n, st[0], st[1], st[2]);
    dis_cursor_init(&c, buf, a + 4); /* one PDU and zero padding only */
    n = 0;
    while (n < 4 && dis_cursor_next(&c, &pdu, &st[n])) n++;
    CHECK(n == 1 && st[0] == DIS_DETONATION, "%d", n);
}

/* ---- WGS-84 ---- */

CHECK_TEST(geodetic_round_trips_to_a_micrometre)
{
    const double places[][3] = {{0, 0, 0},       {48.137154, 11.576124, 519}, {-33.86, 151.21, 40},
                                {89.9999, 10, 0}, {-90, 0, 2000},             {90, 45, -400},
                                {0, 180, 1e5},    {64.5, -179.999, 8848},     {-45, -90, -11000}};
    for (size_t i = 0; i < sizeof(places) / sizeof(places[0]); i++) {
        double ecef[3], lat, lon, alt, back[3];
        geodetic_to_ecef(places[i][0], places[i][1], places[i][2], ecef);
        ecef_to_geodetic(ecef, &lat, &lon, &alt);
        geodetic_to_ecef(lat, lon, alt, back);
        double off = hypot(hypot(back[0] - ecef[0], back[1] - ecef[1]), back[2] - ecef[2]);
        CHECK(off < 1e-6 && fabs(alt - places[i][2]) < 1e-6, "%g, %g, %g: %g m off, height %.9f", places[i][0],
              places[i][1], places[i][2], off, alt);
    }
    double equator[3];
    geodetic_to_ecef(0, 0, 0, equator);
    CHECK(equator[0] == WGS84_A && equator[1] == 0 && equator[2] == 0);
}

CHECK_TEST(scene_axes_are_east_up_and_south)
{
    struct geo_frame f;
    geo_frame_init(&f, 48.137154, 11.576124, 519.0);
    double p[3], s[3];
    for (int axis = 0; axis < 3; axis++) {
        const double *v = axis == 0 ? f.east : axis == 1 ? f.north : f.up;
        for (int k = 0; k < 3; k++) p[k] = f.origin[k] + 100.0 * v[k];
        geo_frame_scene(&f, p, s);
        const double want[3][3] = {{100, 0, 0}, {0, 0, -100}, {0, 100, 0}};
        for (int k = 0; k < 3; k++) CHECK_NEAR(s[k], want[axis][k], 1e-8);
        CHECK_NEAR(geo_frame_distance(&f, p), 100.0, 1e-8);
    }
    geo_frame_scene(&f, f.origin, s);
    CHECK(s[0] == 0 && s[1] == 0 && s[2] == 0);
}

/* ---- the effect table ---- */

CHECK_TEST(munition_patterns_parse)
{
    int f[DIS_MUNITION_FIELDS];
    const char *why = NULL;
    CHECK(dis_munition_parse("2.9.225.2.14.1.0", f, &why) == 0 && f[0] == 2 && f[2] == 225 && f[6] == 0);
    CHECK(dis_munition_parse("2.9.*.2.*.*.*", f, &why) == 0 && f[2] == DIS_ANY && f[3] == 2 && f[6] == DIS_ANY);
    CHECK(dis_munition_parse("*", f, &why) == 0 && f[0] == DIS_ANY && f[6] == DIS_ANY);
    CHECK(dis_munition_parse("2.9.65535.255.255.255.255", f, &why) == 0 && f[2] == 65535);
    const char *bad[] = {"2.9", "2.9.225.2.14.1.0.0", "2.9.65536.2.14.1.0", "256.9.225.2.14.1.0", "a.b.c.d.e.f.g",
                         "", "2..225.2.14.1.0", "-1.9.225.2.14.1.0", "2.9.225.2.14.1.0 "};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++)
        CHECK(dis_munition_parse(bad[i], f, &why) == -1 && why, "'%s' was taken", bad[i]);
    char text[48];
    dis_munition_parse("2.9.*.2.*.*.7", f, &why);
    dis_munition_format(f, text, sizeof(text));
    CHECK(strcmp(text, "2.9.*.2.*.*.7") == 0, "%s", text);
}

CHECK_TEST(first_matching_rule_wins_then_the_default)
{
    struct dis_effect_map m = {.count = 3};
    const char *why;
    dis_munition_parse("2.9.225.2.14.*.*", m.rules[0].munition, &why);
    m.rules[0].result = 7;
    snprintf(m.rules[0].effect, sizeof(m.rules[0].effect), "airburst");
    dis_munition_parse("2.9.225.2.14.*.*", m.rules[1].munition, &why);
    m.rules[1].result = DIS_ANY;
    snprintf(m.rules[1].effect, sizeof(m.rules[1].effect), "blast");
    dis_munition_parse("*", m.rules[2].munition, &why);
    m.rules[2].result = 1;
    snprintf(m.rules[2].effect, sizeof(m.rules[2].effect), "impact");
    struct dis_entity_type he = {2, 9, 225, 2, 14, 3, 0}, other = {2, 2, 13, 1, 1, 0, 0};
    CHECK(strcmp(dis_effect_find(&m, &he, 7), "airburst") == 0);
    CHECK(strcmp(dis_effect_find(&m, &he, 5), "blast") == 0);
    CHECK(strcmp(dis_effect_find(&m, &he, 1), "blast") == 0, "rule 2 comes first");
    CHECK(strcmp(dis_effect_find(&m, &other, 1), "impact") == 0);
    CHECK(dis_effect_find(&m, &other, 5) == NULL, "no rule, no default");
    snprintf(m.fallback, sizeof(m.fallback), "dust");
    CHECK(strcmp(dis_effect_find(&m, &other, 5), "dust") == 0);
}

/* ---- repeats ---- */

CHECK_TEST(a_repeated_event_within_a_second_is_one_detonation)
{
    static struct dis_events e;
    dis_events_init(&e);
    const int64_t s = 1000000000;
    struct dis_entity_id a = {1, 2, 77}, other_app = {1, 3, 77}, no_event = {1, 2, 0};
    CHECK(!dis_events_repeat(&e, &a, 10 * s));
    CHECK(dis_events_repeat(&e, &a, 10 * s + s / 2), "half a second later");
    CHECK(!dis_events_repeat(&e, &other_app, 10 * s + s / 2), "another application's event 77");
    CHECK(!dis_events_repeat(&e, &a, 11 * s), "a second after the first");
    CHECK(!dis_events_repeat(&e, &no_event, 12 * s) && !dis_events_repeat(&e, &no_event, 12 * s), "event 0: none");
    /* 3000 events in a second, then each again: every repeat found */
    int found = 0;
    for (unsigned i = 1; i <= 3000; i++) dis_events_repeat(&e, &(struct dis_entity_id){9, 9, (uint16_t)i}, 20 * s);
    for (unsigned i = 1; i <= 3000; i++) found += dis_events_repeat(&e, &(struct dis_entity_id){9, 9, (uint16_t)i}, 20 * s);
    CHECK(found == 3000, "%d of 3000 repeats found", found);
}

/* ---- the receiver, without a socket ---- */

struct caught {
    int count;
    char effect[8][64];
    float at[8][3];
};

static void catch_fire(const char *effect, const float position[3], void *user)
{
    struct caught *c = user;
    if (c->count < 8) {
        snprintf(c->effect[c->count], sizeof(c->effect[0]), "%s", effect);
        memcpy(c->at[c->count], position, sizeof(c->at[0]));
    }
    c->count++;
}

static struct dis_receiver *receiver(struct dis_settings *s)
{
    memset(s, 0, sizeof(*s));
    s->have_origin = true;
    s->origin[0] = 48.137154, s->origin[1] = 11.576124, s->origin[2] = 519.0;
    s->range_m = 20000.0;
    s->exercise = 1;
    snprintf(s->effects.fallback, sizeof(s->effects.fallback), "blast");
    struct dis_receiver *r = NULL;
    char err[256];
    CHECK(dis_receiver_make(&r, s, err, sizeof(err)) == 0, "%s", err);
    return r;
}

CHECK_TEST(receiver_counts_filters_and_places)
{
    static struct dis_settings s;
    struct dis_receiver *r = receiver(&s);
    struct caught c = {0};
    const struct dis_sink sink = {catch_fire, NULL, &c, NULL, NULL, NULL};
    struct geo_frame f;
    geo_frame_init(&f, s.origin[0], s.origin[1], s.origin[2]);
    double near[3], far[3];
    for (int k = 0; k < 3; k++) near[k] = f.origin[k] + 30.0 * f.east[k] + 40.0 * f.up[k];
    for (int k = 0; k < 3; k++) far[k] = f.origin[k] + 25000.0 * f.north[k];
    uint8_t buf[256];
    size_t len = encode(buf, 7, 1, 1, howitzer, 5, near, 0);
    dis_receiver_datagram(r, buf, len, false, NULL, 0, &sink);              /* set off */
    dis_receiver_datagram(r, buf, len, false, NULL, 1000, &sink);           /* a repeat */
    len = encode(buf, 6, 2, 2, howitzer, 5, near, 0);
    dis_receiver_datagram(r, buf, len, false, NULL, 2000, &sink);           /* exercise 2 */
    len = encode(buf, 6, 1, 3, howitzer, 5, far, 0);
    dis_receiver_datagram(r, buf, len, false, NULL, 3000, &sink);           /* 25 km away */
    dis_receiver_datagram(r, buf, 50, false, NULL, 4000, &sink);            /* truncated */
    dis_receiver_datagram(r, buf, 9000, true, NULL, 5000, &sink);           /* oversized */
    const struct dis_counts *n = dis_receiver_counts(r);
    CHECK(n->pdus == 6 && n->detonations == 1 && n->ignored == 3 && n->malformed == 2, "%llu %llu %llu %llu",
          (unsigned long long)n->pdus, (unsigned long long)n->detonations, (unsigned long long)n->ignored,
          (unsigned long long)n->malformed);
    CHECK(n->ignored_by[DIS_IGNORED_REPEAT] == 1 && n->ignored_by[DIS_IGNORED_EXERCISE] == 1 &&
          n->ignored_by[DIS_IGNORED_RANGE] == 1);
    CHECK(c.count == 1 && strcmp(c.effect[0], "blast") == 0);
    CHECK_NEAR(c.at[0][0], 30.0, 1e-4);
    CHECK_NEAR(c.at[0][1], 40.0, 1e-4);
    CHECK_NEAR(c.at[0][2], 0.0, 1e-4);
    s.effects.fallback[0] = '\0'; /* no default: counted and ignored */
    dis_receiver_configure(r, &s);
    len = encode(buf, 7, 1, 9, howitzer, 5, near, 0);
    dis_receiver_datagram(r, buf, len, false, NULL, 6000, &sink);
    CHECK(n->ignored_by[DIS_IGNORED_UNMAPPED] == 1 && c.count == 1);
    dis_receiver_close(r);
}

/* ---- the one trigger queue ---- */

CHECK_TEST(queue_limits_and_log)
{
    static struct trigger_queue q;
    trigger_queue_init(&q);
    trigger_queue_limit(&q, TRIGGER_MQTT, 250);
    const float at[3] = {1, 2, 3};
    const int64_t ms = 1000000;
    CHECK(trigger_queue_push(&q, TRIGGER_MQTT, "blast", at, 1000 * ms));
    CHECK(!trigger_queue_push(&q, TRIGGER_MQTT, "blast", at, 1100 * ms), "within MQTT's 250 ms");
    CHECK(trigger_queue_push(&q, TRIGGER_MQTT, "dust", at, 1100 * ms), "another effect has its own limit");
    CHECK(trigger_queue_push(&q, TRIGGER_MQTT, "blast", at, 1250 * ms), "250 ms later");
    for (int i = 0; i < 10; i++) CHECK(trigger_queue_push(&q, TRIGGER_DIS, "blast", at, 1250 * ms), "DIS: a salvo");
    while (trigger_queue_push(&q, TRIGGER_GPIO, "blast", at, 0)) {}
    CHECK(q.count == TRIGGER_QUEUE_MAX && q.full[TRIGGER_GPIO] == 1 && q.limited[TRIGGER_MQTT] == 1);
    CHECK(trigger_queue_refused(&q) == 2);
    /* no module: sbfx_trigger refuses each, counted per kind */
    CHECK(trigger_queue_fire(&q, NULL) == 0 && q.count == 0);
    CHECK(q.pool_full[TRIGGER_DIS] == 10 && q.pool_full[TRIGGER_MQTT] == 3, "%llu",
          (unsigned long long)q.pool_full[TRIGGER_DIS]);
    /* the log: the listener's calls, the last 16, oldest first, with their kinds */
    for (int i = 0; i < 20; i++) {
        q.firing = i % 2 ? TRIGGER_DIS : TRIGGER_GPIO;
        const float p[3] = {(float)i, 0, 0};
        trigger_queue_listen("blast", p, i * 0.5, i == 19 ? SBFX_TRIGGER_TIMELINE : SBFX_TRIGGER_CALL, &q);
    }
    trigger_queue_listen("dust", at, 10.0, SBFX_TRIGGER_SCHEDULE, &q);
    struct trigger_log_entry log[TRIGGER_LOG_MAX];
    int n = trigger_queue_log(&q, log);
    CHECK(n == 16 && log[0].at[0] == 5.0f && log[0].time == 2.5 && log[0].kind == TRIGGER_DIS, "%d", n);
    CHECK(log[14].kind == TRIGGER_TIMELINE && log[15].kind == TRIGGER_CLI && strcmp(log[15].effect, "dust") == 0);
    CHECK(q.fired[TRIGGER_GPIO] == 10 && q.fired[TRIGGER_DIS] == 9);
    const char *names[] = {"gpio", "dis", "mqtt", "timeline", "cli", "cigi"};
    for (int i = 0; i < TRIGGER_KIND_COUNT; i++) CHECK(strcmp(trigger_kind_name((enum trigger_kind)i), names[i]) == 0);
}

/* ---- EFFECT[@X,Y,Z]: --gpio's tail, an MQTT payload ---- */

CHECK_TEST(effect_at_payloads)
{
    char effect[EFFECT_NAME_MAX];
    float p[3] = {9, 9, 9};
    CHECK(effect_at_parse("blast", 5, effect, p) == NULL && strcmp(effect, "blast") == 0 && p[0] == 0 && p[2] == 0);
    CHECK(effect_at_parse("blast@1.5,-2,3e2", 16, effect, p) == NULL && p[0] == 1.5f && p[1] == -2 && p[2] == 300);
    CHECK(effect_at_parse("blast@1,2,3 and more", 5, effect, p) == NULL, "only len bytes are read");
    const char *bad[] = {"", "@1,2,3", "bl ast", "blast@1,2", "blast@1,2,3,4", "blast@x,2,3", "blast@1,2,nan",
                         "blast@1,2,1e999", "blast@ 1,2,3", "blast@1,2,3 "};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++)
        CHECK(effect_at_parse(bad[i], strlen(bad[i]), effect, p) != NULL, "'%s' was taken", bad[i]);
    CHECK(effect_at_parse("bla\0st", 6, effect, p) != NULL, "a NUL inside");
    char longer[200];
    memset(longer, 'a', sizeof(longer));
    CHECK(effect_at_parse(longer, sizeof(longer), effect, p) != NULL);
    CHECK(effect_at_parse(longer, 64, effect, p) != NULL, "a name of 64");
    CHECK(effect_at_parse(longer, 63, effect, p) == NULL, "a name of 63");
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
