/* tests/dis.sh's sender: DIS PDUs encoded here from the standard's layout (IEEE 1278.1, the
 * Detonation PDU; field sizes as Open-DIS marshals them: open-dis-cpp src/dis6/DetonationPdu.cpp,
 * src/dis7/Pdu.cpp), independent of the player's parser, and sent over UDP to 127.0.0.1.
 *
 *   dis_send --port P [options] detonation     one Detonation PDU
 *   dis_send --port P [options] entity-state   one Entity State PDU (type 1), 144 bytes: entity
 *                                              --site:--app:--entity at --enu, its --attitude
 *                                              (heading, pitch, roll there, degrees) as DIS's
 *                                              Euler angles
 *   dis_send --port P [options] load S ES DET  for S seconds, ES Entity State PDUs and DET
 *                                              detonations (events of their own, in range) a
 *                                              second, paced by the clock (tests/load.sh)
 *   dis_send --port P [options] storm N        N PDUs: detonations, other types, repeats and
 *                                              malformed ones mixed; prints what it sent:
 *                                              "sent N detonations D ignored I malformed M"
 *   dis_send --origin LAT,LON,ALT --enu E,N,U ecef   the ECEF point E m east, N m north, U m up of
 *                                              the origin (printed: the test's own conversion)
 *   dis_send --file PATH [options] detonation  the PDU appended to PATH instead of sent (the
 *                                              fuzzer's seeds; --count 2: a bundle of two)
 * Options: --version 6|7 --exercise E --site S --app A --event N --munition K.D.C.C.S.S.E
 *          --result R --origin LAT,LON,ALT --enu E,N,U (the location; default the origin)
 *          --ecef X,Y,Z --vp N (variable parameter records) --announce N (the record count the
 *          PDU says, wrong on purpose: a wrong length) --length L (the header's length field)
 *          --cut N (send only the first N bytes) --count N (send it N times) --timestamp T (the
 *          header's, raw: bit 0 set is absolute, seconds past the hour x 2^31 / 3600 above it).
 * The location: geodetic -> ECEF in closed form; a point E east, N north, U up is reached
 * geodetically (latitude + N / M, longitude + E / (N_prime cos lat), height + U, with the
 * meridian and prime vertical radii of curvature), not through the player's tangent-plane
 * rotation: what the player computes from it is checked, not repeated. ECEF -> geodetic here is
 * Heikkinen's closed form, used to check the conversion's round trip before anything is sent.
 * A storm is paced by the receiver's queue (/proc/net/udp): the kernel never drops, so the
 * player's counters can be compared exactly. */
#define _GNU_SOURCE
#include <arpa/inet.h>
#include <errno.h>
#include <math.h>
#include <netinet/in.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#define A 6378137.0
#define F (1.0 / 298.257223563)
#define E2 (F * (2.0 - F))
#define DEG (M_PI / 180.0)

struct pdu_spec {
    int version, exercise, type, site, app, event, result, vp, announce, length, cut;
    uint32_t timestamp;
    int munition[7];
    double ecef[3];
    int entity;                    /* entity-state: the entity number (site and app as given) */
    double attitude[3];            /* entity-state: heading, pitch, roll at its place (degrees) */
};

/* ---- geodesy of its own ----------------------------------------------------------------- */

static void to_ecef(double lat, double lon, double alt, double out[3])
{
    double s = sin(lat * DEG), c = cos(lat * DEG), n = A / sqrt(1 - E2 * s * s);
    out[0] = (n + alt) * c * cos(lon * DEG);
    out[1] = (n + alt) * c * sin(lon * DEG);
    out[2] = (n * (1 - E2) + alt) * s;
}

/* Heikkinen (1982): the closed-form inverse. */
static void to_geodetic(const double p[3], double *lat, double *lon, double *alt)
{
    double b = A * (1 - F), ep2 = (A * A - b * b) / (b * b);
    double r = hypot(p[0], p[1]), z = p[2];
    double f = 54 * b * b * z * z;
    double g = r * r + (1 - E2) * z * z - E2 * (A * A - b * b);
    double c = E2 * E2 * f * r * r / (g * g * g);
    double s = cbrt(1 + c + sqrt(c * c + 2 * c));
    double k = s + 1 + 1 / s;
    double pp = f / (3 * k * k * g * g);
    double q = sqrt(1 + 2 * E2 * E2 * pp);
    double r0 = -pp * E2 * r / (1 + q) +
                sqrt(fmax(0, A * A / 2 * (1 + 1 / q) - pp * (1 - E2) * z * z / (q * (1 + q)) - pp * r * r / 2));
    double u = hypot(r - E2 * r0, z), v = sqrt((r - E2 * r0) * (r - E2 * r0) + (1 - E2) * z * z);
    double z0 = b * b * z / (A * v);
    *alt = u * (1 - b * b / (A * v));
    *lat = atan2(z + ep2 * z0, r) / DEG;
    *lon = atan2(p[1], p[0]) / DEG;
}

/* The point e m east, n m north, u m up of the origin, reached along the ellipsoid. */
static int offset_point(const double origin[3], const double enu[3], double out[3])
{
    double lat = origin[0] * DEG, s = sin(lat), w = sqrt(1 - E2 * s * s);
    double prime = A / w, meridian = A * (1 - E2) / (w * w * w);
    double h = origin[2]; /* the radii of the circles walked grow with the height */
    to_ecef(origin[0] + enu[1] / (meridian + h) / DEG, origin[1] + enu[0] / ((prime + h) * cos(lat)) / DEG, h + enu[2], out);
    double la, lo, al, back[3];
    to_geodetic(out, &la, &lo, &al);
    to_ecef(la, lo, al, back);
    double err = hypot(hypot(back[0] - out[0], back[1] - out[1]), back[2] - out[2]);
    if (err > 1e-6) {
        fprintf(stderr, "dis_send: geodetic round trip off by %g m\n", err);
        return -1;
    }
    return 0;
}

/* ---- encoding: big-endian, by offset ------------------------------------------------------ */

static void put16(uint8_t *p, unsigned v) { p[0] = (uint8_t)(v >> 8), p[1] = (uint8_t)v; }

static void put32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++) p[i] = (uint8_t)(v >> (24 - 8 * i));
}

static void put_double(uint8_t *p, double d)
{
    uint64_t bits;
    memcpy(&bits, &d, sizeof(bits));
    put32(p, (uint32_t)(bits >> 32));
    put32(p + 4, (uint32_t)bits);
}

static void put_float(uint8_t *p, float f)
{
    uint32_t bits;
    memcpy(&bits, &f, sizeof(bits));
    put32(p, bits);
}

/* The 12-byte header: version, exercise, type, family, timestamp, length, padding. */
static void header(uint8_t *p, const struct pdu_spec *s, int type, int family, size_t length)
{
    p[0] = (uint8_t)s->version, p[1] = (uint8_t)s->exercise, p[2] = (uint8_t)type, p[3] = (uint8_t)family;
    put32(p + 4, s->timestamp); /* --timestamp: bit 0 set, absolute (the default 0x12345679: 9:46 past) */
    put16(p + 8, (unsigned)length);
    p[10] = p[11] = 0;
}

static size_t detonation(uint8_t *p, const struct pdu_spec *s)
{
    size_t length = 104 + 16 * (size_t)s->vp;
    memset(p, 0, length);
    header(p, s, 3, 2, s->length >= 0 ? (size_t)s->length : length);
    const unsigned ids[4][3] = {{(unsigned)s->site, (unsigned)s->app, 1},   /* firing entity */
                                {(unsigned)s->site, (unsigned)s->app, 2},   /* target entity */
                                {(unsigned)s->site, (unsigned)s->app, 3},   /* munition entity */
                                {(unsigned)s->site, (unsigned)s->app, (unsigned)s->event}}; /* event */
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++) put16(p + 12 + 6 * i + 2 * k, ids[i][k]);
    for (int k = 0; k < 3; k++) put_float(p + 36 + 4 * k, k == 2 ? -250.0f : 10.0f); /* velocity */
    for (int k = 0; k < 3; k++) put_double(p + 48 + 8 * k, s->ecef[k]);
    p[72] = (uint8_t)s->munition[0], p[73] = (uint8_t)s->munition[1];
    put16(p + 74, (unsigned)s->munition[2]);
    for (int k = 3; k < 7; k++) p[73 + k] = (uint8_t)s->munition[k];
    put16(p + 80, 1000), put16(p + 82, 1000), put16(p + 84, 1), put16(p + 86, 0); /* warhead, fuse, quantity, rate */
    for (int k = 0; k < 3; k++) put_float(p + 88 + 4 * k, 0.5f);  /* location in entity coordinates */
    p[100] = (uint8_t)s->result;                                   /* detonation result */
    p[101] = (uint8_t)(s->announce >= 0 ? s->announce : s->vp);    /* number of variable parameters */
    for (int i = 0; i < s->vp; i++) p[104 + 16 * i] = 1;           /* record type: attached part */
    return length;
}

/* DIS's Euler angles (psi, theta, phi: z-y-x from ECEF's axes) of a body with this heading (from
 * north, clockwise), pitch (up) and roll (right) in the local frame at ECEF point p: the body's
 * axes built in east, north, up and read back as the angles of R = Rz(psi) Ry(theta) Rx(phi). */
static void euler_angles(const double p[3], const double attitude[3], float out[3])
{
    double lat, lon, alt;
    to_geodetic(p, &lat, &lon, &alt);
    double sa = sin(lat * DEG), ca = cos(lat * DEG), so = sin(lon * DEG), co = cos(lon * DEG);
    const double east[3] = {-so, co, 0}, north[3] = {-sa * co, -sa * so, ca}, up[3] = {ca * co, ca * so, sa};
    double h = attitude[0] * DEG, t = attitude[1] * DEG, r = attitude[2] * DEG;
    /* forward, and the level right and down before the roll, in east, north, up */
    const double f[3] = {sin(h) * cos(t), cos(h) * cos(t), sin(t)};
    const double r0[3] = {cos(h), -sin(h), 0}, d0[3] = {sin(h) * sin(t), cos(h) * sin(t), -cos(t)};
    double fe[3], re[3], de[3];
    for (int k = 0; k < 3; k++) {
        const double *axis[3] = {east, north, up};
        fe[k] = re[k] = de[k] = 0;
        for (int j = 0; j < 3; j++) {
            double right = cos(r) * r0[j] + sin(r) * d0[j], down = -sin(r) * r0[j] + cos(r) * d0[j];
            fe[k] += f[j] * axis[j][k];
            re[k] += right * axis[j][k];
            de[k] += down * axis[j][k];
        }
    }
    out[0] = (float)atan2(fe[1], fe[0]);
    out[1] = (float)-asin(fe[2]);
    out[2] = (float)atan2(re[2], de[2]);
}

static size_t entity_state(uint8_t *p, const struct pdu_spec *s)
{
    memset(p, 0, 144);
    header(p, s, 1, 1, 144);
    put16(p + 12, (unsigned)s->site), put16(p + 14, (unsigned)s->app), put16(p + 16, (unsigned)s->entity);
    for (int k = 0; k < 3; k++) put_double(p + 48 + 8 * k, s->ecef[k]);
    float euler[3];
    euler_angles(s->ecef, s->attitude, euler);
    for (int k = 0; k < 3; k++) put_float(p + 72 + 4 * k, euler[k]);
    return 144;
}

/* ---- sending --------------------------------------------------------------------------- */

static int sock = -1;
static struct sockaddr_in to;
static FILE *file; /* --file: PDUs go here */

/* Bytes waiting in the receiving socket on the port (/proc/net/udp's rx_queue), -1 if unknown. */
static long receiver_queue(int port)
{
    FILE *f = fopen("/proc/net/udp", "r");
    if (!f) return -1;
    char line[512];
    long queued = -1;
    while (fgets(line, sizeof(line), f)) {
        unsigned local_port = 0;
        unsigned long tx = 0, rx = 0;
        if (sscanf(line, " %*d: %*8x:%x %*8x:%*x %*x %lx:%lx", &local_port, &tx, &rx) == 3 && (int)local_port == port)
            queued = queued < 0 ? (long)rx : queued + (long)rx;
    }
    fclose(f);
    return queued;
}

static void wait_for_room(int port)
{
    for (int i = 0; i < 20000 && receiver_queue(port) > 32768; i++) {
        struct timespec ts = {0, 500000};
        nanosleep(&ts, NULL);
    }
}

static int send_bytes(const uint8_t *p, size_t n)
{
    if (file) return fwrite(p, 1, n, file) == n ? 0 : -1;
    if (sendto(sock, p, n, 0, (const struct sockaddr *)&to, sizeof(to)) == (ssize_t)n) return 0;
    fprintf(stderr, "dis_send: sendto: %s\n", strerror(errno));
    return -1;
}

static int send_pdu(const struct pdu_spec *s, bool entity)
{
    static uint8_t buf[16384];
    size_t n = entity ? entity_state(buf, s) : detonation(buf, s);
    if (s->cut >= 0 && (size_t)s->cut < n) n = (size_t)s->cut;
    return send_bytes(buf, n);
}

/* i-th PDU of a storm, by i % 10: 0 malformed (four kinds in turn), 1 another PDU type, 3 a
 * repeat of the detonation at 2, the rest detonations with events of their own. */
static int storm_one(struct pdu_spec base, int i, int port, int counts[3])
{
    static uint8_t big[9000];
    base.event = 1 + i % 60000;
    if (i % 32 == 0) wait_for_room(port);
    switch (i % 10) {
    case 0: /* malformed, in turn: truncated, wrong version, wrong length, oversized */
        counts[2]++;
        if (i % 40 == 0) base.cut = 60;
        if (i % 40 == 10) base.version = 5;
        if (i % 40 == 20) base.vp = 1, base.announce = 0;
        if (i % 40 == 30) return send_bytes(big, sizeof(big));
        return send_pdu(&base, false);
    case 1: counts[1]++; return send_pdu(&base, true);
    case 3: counts[1]++; base.event = 1 + (i - 1) % 60000; /* the event sent just before: a repeat */
        return send_pdu(&base, false);
    default: counts[0]++; return send_pdu(&base, false);
    }
}

static int storm(struct pdu_spec base, int count, int port)
{
    int counts[3] = {0, 0, 0}; /* detonations, ignored, malformed */
    for (int i = 0; i < count; i++)
        if (storm_one(base, i, port, counts) != 0) return 1;
    printf("sent %d detonations %d ignored %d malformed %d\n", count, counts[0], counts[1], counts[2]);
    return 0;
}

/* A real exercise's load (tests/load.sh): for `seconds`, es_rate Entity State PDUs and det_rate
 * detonations a second, spread evenly (due ones sent each millisecond), each detonation an event
 * of its own (event numbers 1.., the site and application given) at one of 16 points within
 * 400 m of the origin. Prints "sent E entity-states D detonations" at the end. */
static int load(struct pdu_spec base, const double origin[3], double seconds, double es_rate, double det_rate)
{
    double points[16][3];
    for (int k = 0; k < 16; k++) {
        const double enu[3] = {(k % 4) * 100.0 - 150.0, (k / 4) * 100.0 - 150.0, 0.0};
        if (offset_point(origin, enu, points[k]) != 0) return 1;
    }
    struct timespec t0, now;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    long es = 0, det = 0;
    for (;;) {
        clock_gettime(CLOCK_MONOTONIC, &now);
        double t = (double)(now.tv_sec - t0.tv_sec) + (double)(now.tv_nsec - t0.tv_nsec) / 1e9;
        if (t > seconds) t = seconds;
        for (; es < (long)(t * es_rate); es++) {
            base.event = 1 + (int)(es % 60000);
            if (send_pdu(&base, true) != 0) return 1;
        }
        for (; det < (long)(t * det_rate); det++) {
            struct pdu_spec d = base;
            d.event = 1 + (int)(det % 65535);
            memcpy(d.ecef, points[det % 16], sizeof(d.ecef));
            if (send_pdu(&d, false) != 0) return 1;
        }
        if (t >= seconds) break;
        struct timespec tick = {0, 1000000};
        nanosleep(&tick, NULL);
    }
    printf("sent %ld entity-states %ld detonations\n", es, det);
    return 0;
}

/* ---- the command line ------------------------------------------------------------------ */

static bool triple(const char *s, double out[3])
{
    return sscanf(s, "%lf,%lf,%lf", &out[0], &out[1], &out[2]) == 3;
}

int main(int argc, char **argv)
{
    struct pdu_spec s = {.version = 7, .exercise = 1, .type = 3, .site = 1, .app = 1, .event = 1, .result = 5,
                         .timestamp = 0x12345679u,
                         .announce = -1, .length = -1, .cut = -1, .munition = {2, 9, 225, 2, 14, 1, 0}};
    double origin[3] = {0, 0, 0}, enu[3] = {0, 0, 0};
    int port = 0, count = 1, i = 1;
    const char *path = NULL;
    bool have_ecef = false;
    for (; i + 1 < argc && strncmp(argv[i], "--", 2) == 0; i += 2) {
        const char *k = argv[i] + 2, *v = argv[i + 1];
        if (!strcmp(k, "port")) port = atoi(v);
        else if (!strcmp(k, "version")) s.version = atoi(v);
        else if (!strcmp(k, "exercise")) s.exercise = atoi(v);
        else if (!strcmp(k, "site")) s.site = atoi(v);
        else if (!strcmp(k, "app")) s.app = atoi(v);
        else if (!strcmp(k, "event")) s.event = atoi(v);
        else if (!strcmp(k, "result")) s.result = atoi(v);
        else if (!strcmp(k, "vp")) s.vp = atoi(v);
        else if (!strcmp(k, "announce")) s.announce = atoi(v);
        else if (!strcmp(k, "length")) s.length = atoi(v);
        else if (!strcmp(k, "cut")) s.cut = atoi(v);
        else if (!strcmp(k, "count")) count = atoi(v);
        else if (!strcmp(k, "timestamp")) s.timestamp = (uint32_t)strtoul(v, NULL, 0);
        else if (!strcmp(k, "entity")) s.entity = atoi(v);
        else if (!strcmp(k, "attitude") && triple(v, s.attitude)) continue;
        else if (!strcmp(k, "file")) path = v;
        else if (!strcmp(k, "origin") && triple(v, origin)) continue;
        else if (!strcmp(k, "enu") && triple(v, enu)) continue;
        else if (!strcmp(k, "ecef") && triple(v, s.ecef)) have_ecef = true;
        else if (!strcmp(k, "munition") && sscanf(v, "%d.%d.%d.%d.%d.%d.%d", &s.munition[0], &s.munition[1],
                                                  &s.munition[2], &s.munition[3], &s.munition[4], &s.munition[5],
                                                  &s.munition[6]) == 7) continue;
        else {
            fprintf(stderr, "dis_send: bad option --%s %s\n", k, v);
            return 2;
        }
    }
    if (!have_ecef && offset_point(origin, enu, s.ecef) != 0) return 1;
    const char *what = i < argc ? argv[i] : "";
    if (!strcmp(what, "ecef")) {
        printf("%.4f %.4f %.4f\n", s.ecef[0], s.ecef[1], s.ecef[2]);
        return 0;
    }
    if (path && !(file = fopen(path, "ab"))) {
        fprintf(stderr, "dis_send: %s: %s\n", path, strerror(errno));
        return 1;
    }
    sock = socket(AF_INET, SOCK_DGRAM, 0);
    to = (struct sockaddr_in){.sin_family = AF_INET, .sin_port = htons((uint16_t)port),
                              .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    if (sock < 0 || (port <= 0 && !file)) {
        fprintf(stderr, "dis_send: no socket or no --port\n");
        return 2;
    }
    if (!strcmp(what, "storm") && i + 1 < argc) return storm(s, atoi(argv[i + 1]), port);
    if (!strcmp(what, "load") && i + 3 < argc)
        return load(s, origin, atof(argv[i + 1]), atof(argv[i + 2]), atof(argv[i + 3]));
    bool entity = !strcmp(what, "entity-state");
    if (!entity && strcmp(what, "detonation") != 0) {
        fprintf(stderr, "dis_send: detonation, entity-state, storm N, load S ES DET or ecef\n");
        return 2;
    }
    for (int n = 0; n < count; n++)
        if (send_pdu(&s, entity) != 0) return 1;
    return file && fclose(file) != 0;
}
