/* A CIGI 3.3 host for tests (tests/cigi.sh, the player's CIGI tests): messages encoded here from
 * the standard's layout (SISO-STD-013; the offsets Wireshark's CIGI dissector reads), independent
 * of the player's parser, sent over UDP; the image generator's Start of Frame read back and
 * decoded here too.
 *
 *   cigi_send --port P [options] PACKET...   one message: IG Control, then the packets, to
 *                                            127.0.0.1:P (--to ADDR for another address)
 *   cigi_send --file PATH [options] PACKET...  the message appended to PATH instead of sent
 *                                            (the fuzzer's seeds, tshark's captures)
 *   cigi_send --origin LAT,LON,ALT --enu E,N,U geodetic   the point's latitude, longitude and
 *                                            height (printed: the test's own conversion)
 * PACKET:
 *   entity=ID,TYPE,STATE,ANIM@E,N,U[/YAW,PITCH,ROLL]   Entity Control at E m east, N m north,
 *                     U m up of --origin (STATE 0 inactive, 1 active, 2 destroyed; ANIM 0 stop,
 *                     1 pause, 2 play, 3 continue)
 *   entity-geo=ID,TYPE,STATE,ANIM@LAT,LON,ALT          Entity Control at a geodetic position
 *   view-def=VIEW,GROUP,LEFT,RIGHT,BOTTOM,TOP,NEAR,FAR View Definition, all six fields enabled
 *   view-ctrl=VIEW,GROUP,ENTITY,X,Y,Z,YAW,PITCH,ROLL   View Control, all six offsets enabled
 *   other=ID,SIZE     a packet of another type, SIZE bytes (zeros after its ID and size)
 *   raw=HEX           bytes as given (malformed packets on purpose)
 * Options:
 *   --frame N (1) host frame number of the first message; --timestamp T (N x 1667) its
 *   timestamp in 10 µs ticks; --no-timestamp (timestamp valid cleared); --ig-mode M (1 operate);
 *   --database D (0); --little-endian; --version V (3) and --magic M (0x8000) as written, wrong on
 *   purpose; --no-ig-control (the packets alone); --cut N (the first N bytes only);
 *   --count N messages, frame +1 and timestamp +--step (1667) each, entity IDs +--id-step (0)
 *   each; --interval-ms MS between them;
 *   --sof-wait MS: after each message, wait up to MS for the IG's Start of Frame on the sending
 *   socket (--bind PORT: its local port), decode it and print
 *   "sof version=3 minor=3 order=be|le db=D status=S mode=M timestamp_valid=V ig_frame=F
 *    timestamp=T last_host_frame=H"; --sof-file PATH: the last one's bytes. Exit 3 when one does
 *   not come.
 * Positions: geodetic -> ECEF in closed form; E east, N north, U up are walked along the ellipsoid
 * (latitude + N / M, longitude + E / (N' cos lat), height + U): what the player computes from it
 * is checked, not repeated. */
#define _GNU_SOURCE
#include <arpa/inet.h>
#include <errno.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
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
#define MAX_PACKETS 256
#define MESSAGE_MAX 16384

static bool le;                      /* --little-endian */
static double origin[3];

/* ---- encoding, by offset, in the message's byte order --------------------------------------- */

static void put16(uint8_t *p, unsigned v)
{
    p[le ? 0 : 1] = (uint8_t)v;
    p[le ? 1 : 0] = (uint8_t)(v >> 8);
}

static void put32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++) p[le ? i : 3 - i] = (uint8_t)(v >> (8 * i));
}

static void put64(uint8_t *p, uint64_t v)
{
    for (int i = 0; i < 8; i++) p[le ? i : 7 - i] = (uint8_t)(v >> (8 * i));
}

static void put_float(uint8_t *p, double d)
{
    float f = (float)d;
    uint32_t bits;
    memcpy(&bits, &f, sizeof(bits));
    put32(p, bits);
}

static void put_double(uint8_t *p, double d)
{
    uint64_t bits;
    memcpy(&bits, &d, sizeof(bits));
    put64(p, bits);
}

static uint32_t get32(const uint8_t *p, bool little)
{
    uint32_t v = 0;
    for (int i = 0; i < 4; i++) v = v << 8 | p[little ? 3 - i : i];
    return v;
}

/* ---- the geodesy of its own -------------------------------------------------------------- */

/* The point e m east, n m north, u m up of the origin, walked along the ellipsoid. */
static void enu_to_geodetic(const double enu[3], double out[3])
{
    double lat = origin[0] * DEG, s = sin(lat), w = sqrt(1 - E2 * s * s);
    double prime = A / w, meridian = A * (1 - E2) / (w * w * w), h = origin[2];
    out[0] = origin[0] + enu[1] / (meridian + h) / DEG;
    out[1] = origin[1] + enu[0] / ((prime + h) * cos(lat)) / DEG;
    out[2] = h + enu[2];
}

/* ---- the packets ------------------------------------------------------------------------- */

struct message_spec {
    uint32_t frame, timestamp, step;
    int ig_mode, database, version, id_step;
    unsigned magic;
    bool timestamp_valid, ig_control;
};

static size_t ig_control(uint8_t *p, const struct message_spec *m)
{
    memset(p, 0, 24);
    p[0] = 1;
    p[1] = 24;
    p[2] = (uint8_t)m->version;
    p[3] = (uint8_t)(int8_t)m->database;
    p[4] = (uint8_t)((m->ig_mode & 3) | (m->timestamp_valid ? 4 : 0) | 3 << 4); /* minor version 3 */
    put16(p + 6, m->magic); /* in the message's order: a little-endian reader sees 0x8000 swapped */
    put32(p + 8, m->frame);
    put32(p + 12, m->timestamp);
    put32(p + 16, m->frame ? m->frame - 1 : 0); /* the last IG frame heard: any number */
    return 24;
}

/* "ID,TYPE,STATE,ANIM@..." -> Entity Control; geo: the position is geodetic, else E,N,U. */
static size_t entity(uint8_t *p, const char *v, bool geo, int id_offset)
{
    int id, type, state, anim;
    double pos[3], ypr[3] = {0, 0, 0}, where[3];
    const char *at = strchr(v, '@');
    if (sscanf(v, "%d,%d,%d,%d", &id, &type, &state, &anim) != 4 || !at ||
        sscanf(at + 1, "%lf,%lf,%lf", &pos[0], &pos[1], &pos[2]) != 3)
        return 0;
    const char *angles = strchr(at, '/');
    if (angles && sscanf(angles + 1, "%lf,%lf,%lf", &ypr[0], &ypr[1], &ypr[2]) != 3) return 0;
    if (geo) memcpy(where, pos, sizeof(where));
    else enu_to_geodetic(pos, where);
    memset(p, 0, 48);
    p[0] = 2;
    p[1] = 48;
    put16(p + 2, (unsigned)(id + id_offset) & 0xffff);
    p[4] = (uint8_t)(state & 3);
    p[5] = (uint8_t)((anim & 3) << 2);
    p[6] = 255; /* alpha: opaque */
    put16(p + 8, (unsigned)type);
    put_float(p + 12, ypr[2]);
    put_float(p + 16, ypr[1]);
    put_float(p + 20, ypr[0]);
    for (int k = 0; k < 3; k++) put_double(p + 24 + 8 * k, where[k]);
    return 48;
}

static size_t view_definition(uint8_t *p, const char *v)
{
    int view, group;
    double l, r, b, t, n, f;
    if (sscanf(v, "%d,%d,%lf,%lf,%lf,%lf,%lf,%lf", &view, &group, &l, &r, &b, &t, &n, &f) != 8) return 0;
    memset(p, 0, 32);
    p[0] = 21;
    p[1] = 32;
    put16(p + 2, (unsigned)view);
    p[4] = (uint8_t)group;
    p[5] = 0x3f; /* near, far, left, right, top, bottom enabled */
    put_float(p + 8, n);
    put_float(p + 12, f);
    put_float(p + 16, l);
    put_float(p + 20, r);
    put_float(p + 24, t);
    put_float(p + 28, b);
    return 32;
}

static size_t view_control(uint8_t *p, const char *v)
{
    int view, group, ent;
    double x, y, z, yaw, pitch, roll;
    if (sscanf(v, "%d,%d,%d,%lf,%lf,%lf,%lf,%lf,%lf", &view, &group, &ent, &x, &y, &z, &yaw, &pitch, &roll) != 9)
        return 0;
    memset(p, 0, 32);
    p[0] = 16;
    p[1] = 32;
    put16(p + 2, (unsigned)view);
    p[4] = (uint8_t)group;
    p[5] = 0x3f; /* x, y, z, roll, pitch, yaw enabled */
    put16(p + 6, (unsigned)ent);
    put_float(p + 8, x);
    put_float(p + 12, y);
    put_float(p + 16, z);
    put_float(p + 20, roll);
    put_float(p + 24, pitch);
    put_float(p + 28, yaw);
    return 32;
}

static size_t raw(uint8_t *p, const char *hex, size_t room)
{
    size_t n = 0;
    unsigned byte;
    while (hex[0] && hex[1] && n < room && sscanf(hex, "%2x", &byte) == 1) {
        p[n++] = (uint8_t)byte;
        hex += 2;
    }
    return n;
}

static size_t packet(uint8_t *p, const char *spec, size_t room, int id_offset)
{
    const char *eq = strchr(spec, '=');
    if (!eq || room < 64) return 0;
    size_t name = (size_t)(eq - spec);
    const char *v = eq + 1;
    if (!strncmp(spec, "entity", name) && name == 6) return entity(p, v, false, id_offset);
    if (!strncmp(spec, "entity-geo", name) && name == 10) return entity(p, v, true, id_offset);
    if (!strncmp(spec, "view-def", name) && name == 8) return view_definition(p, v);
    if (!strncmp(spec, "view-ctrl", name) && name == 9) return view_control(p, v);
    if (!strncmp(spec, "raw", name) && name == 3) return raw(p, v, room);
    int id, size;
    if (!strncmp(spec, "other", name) && name == 5 && sscanf(v, "%d,%d", &id, &size) == 2 && size >= 2 &&
        size <= 255) {
        memset(p, 0, (size_t)size);
        p[0] = (uint8_t)id;
        p[1] = (uint8_t)size;
        return (size_t)size;
    }
    return 0;
}

/* ---- Start of Frame, read back ------------------------------------------------------------ */

static int read_sof(int sock, int wait_ms, const char *path)
{
    struct pollfd pfd = {.fd = sock, .events = POLLIN};
    uint8_t b[512];
    if (poll(&pfd, 1, wait_ms) != 1) return -1;
    ssize_t n = recv(sock, b, sizeof(b), 0);
    if (n < 24 || b[0] != 101 || b[1] != 24) {
        fprintf(stderr, "cigi_send: %zd bytes came back, not a Start of Frame\n", n);
        return -1;
    }
    bool little = b[6] == 0x00 && b[7] == 0x80;
    if (!little && !(b[6] == 0x80 && b[7] == 0x00)) {
        fprintf(stderr, "cigi_send: Start of Frame with the magic %02x%02x\n", b[6], b[7]);
        return -1;
    }
    printf("sof version=%u minor=%u order=%s db=%d status=%u mode=%u timestamp_valid=%u ig_frame=%u timestamp=%u "
           "last_host_frame=%u\n", b[2], b[5] >> 4, little ? "le" : "be", (int8_t)b[3], b[4], b[5] & 3, b[5] >> 2 & 1,
           get32(b + 8, little), get32(b + 12, little), get32(b + 16, little));
    fflush(stdout);
    FILE *f = path ? fopen(path, "wb") : NULL;
    if (f) {
        fwrite(b, 1, 24, f);
        fclose(f);
    }
    return 0;
}

/* ---- the command line -------------------------------------------------------------------- */

struct run {
    struct message_spec m;
    int port, count, interval_ms, sof_wait_ms, cut, bind_port;
    const char *file, *sof_file, *to;
};

static bool option(struct run *r, const char *k, const char *v)
{
    if (!strcmp(k, "port")) r->port = atoi(v);
    else if (!strcmp(k, "to")) r->to = v;
    else if (!strcmp(k, "bind")) r->bind_port = atoi(v);
    else if (!strcmp(k, "file")) r->file = v;
    else if (!strcmp(k, "frame")) r->m.frame = (uint32_t)strtoul(v, NULL, 0);
    else if (!strcmp(k, "timestamp")) r->m.timestamp = (uint32_t)strtoul(v, NULL, 0);
    else if (!strcmp(k, "step")) r->m.step = (uint32_t)strtoul(v, NULL, 0);
    else if (!strcmp(k, "ig-mode")) r->m.ig_mode = atoi(v);
    else if (!strcmp(k, "database")) r->m.database = atoi(v);
    else if (!strcmp(k, "version")) r->m.version = atoi(v);
    else if (!strcmp(k, "magic")) r->m.magic = (unsigned)strtoul(v, NULL, 0);
    else if (!strcmp(k, "count")) r->count = atoi(v);
    else if (!strcmp(k, "id-step")) r->m.id_step = atoi(v);
    else if (!strcmp(k, "interval-ms")) r->interval_ms = atoi(v);
    else if (!strcmp(k, "sof-wait")) r->sof_wait_ms = atoi(v);
    else if (!strcmp(k, "sof-file")) r->sof_file = v;
    else if (!strcmp(k, "cut")) r->cut = atoi(v);
    else if (!strcmp(k, "origin")) return sscanf(v, "%lf,%lf,%lf", &origin[0], &origin[1], &origin[2]) == 3;
    else return false;
    return true;
}

static size_t message(uint8_t *buf, const struct run *r, char **specs, int nspecs, int index)
{
    size_t n = r->m.ig_control ? ig_control(buf, &r->m) : 0;
    for (int i = 0; i < nspecs; i++) {
        size_t k = packet(buf + n, specs[i], MESSAGE_MAX - n, index * r->m.id_step);
        if (!k) {
            fprintf(stderr, "cigi_send: bad packet '%s'\n", specs[i]);
            return 0;
        }
        n += k;
    }
    return r->cut >= 0 && (size_t)r->cut < n ? (size_t)r->cut : n;
}

static int open_socket(const struct run *r, struct sockaddr_in *to)
{
    int sock = socket(AF_INET, SOCK_DGRAM, 0);
    struct sockaddr_in local = {.sin_family = AF_INET, .sin_port = htons((uint16_t)r->bind_port)};
    *to = (struct sockaddr_in){.sin_family = AF_INET, .sin_port = htons((uint16_t)r->port)};
    if (sock < 0 || bind(sock, (const struct sockaddr *)&local, sizeof(local)) != 0 ||
        inet_pton(AF_INET, r->to ? r->to : "127.0.0.1", &to->sin_addr) != 1) {
        fprintf(stderr, "cigi_send: socket, bind or --to: %s\n", strerror(errno));
        return -1;
    }
    return sock;
}

static int send_all(struct run *r, char **specs, int nspecs)
{
    static uint8_t buf[MESSAGE_MAX];
    struct sockaddr_in to;
    FILE *f = r->file ? fopen(r->file, "ab") : NULL;
    int sock = r->file ? -1 : open_socket(r, &to);
    if (r->file ? !f : sock < 0 || r->port <= 0) {
        fprintf(stderr, "cigi_send: no --port, or %s: %s\n", r->file ? r->file : "the socket", strerror(errno));
        return 2;
    }
    for (int i = 0; i < r->count; i++) {
        size_t n = message(buf, r, specs, nspecs, i);
        if (!n && nspecs) return 2;
        if (f ? fwrite(buf, 1, n, f) != n : sendto(sock, buf, n, 0, (const struct sockaddr *)&to, sizeof(to)) != (ssize_t)n) {
            fprintf(stderr, "cigi_send: writing the message: %s\n", strerror(errno));
            return 1;
        }
        if (sock >= 0 && r->sof_wait_ms > 0 && read_sof(sock, r->sof_wait_ms, r->sof_file) != 0) {
            fprintf(stderr, "cigi_send: no Start of Frame within %d ms of host frame %u\n", r->sof_wait_ms, r->m.frame);
            return 3;
        }
        r->m.frame++;
        r->m.timestamp += r->m.step;
        if (r->interval_ms > 0) nanosleep(&(struct timespec){r->interval_ms / 1000, (r->interval_ms % 1000) * 1000000L}, NULL);
    }
    if (f && fclose(f) != 0) return 1;
    return 0;
}

int main(int argc, char **argv)
{
    struct run r = {.m = {.frame = 1, .step = 1667, .ig_mode = 1, .version = 3, .magic = 0x8000,
                          .timestamp_valid = true, .ig_control = true},
                    .count = 1, .cut = -1};
    bool timestamp_given = false;
    double enu[3] = {0, 0, 0};
    int i = 1;
    for (; i < argc && !strncmp(argv[i], "--", 2); i++) {
        const char *k = argv[i] + 2;
        if (!strcmp(k, "little-endian")) le = true;
        else if (!strcmp(k, "no-timestamp")) r.m.timestamp_valid = false;
        else if (!strcmp(k, "no-ig-control")) r.m.ig_control = false;
        else if (i + 1 < argc && !strcmp(k, "enu") && sscanf(argv[i + 1], "%lf,%lf,%lf", &enu[0], &enu[1], &enu[2]) == 3) i++;
        else if (i + 1 < argc && option(&r, k, argv[i + 1])) {
            timestamp_given |= !strcmp(k, "timestamp");
            i++;
        }
        else {
            fprintf(stderr, "cigi_send: bad option %s\n", argv[i]);
            return 2;
        }
    }
    if (!timestamp_given) r.m.timestamp = r.m.frame * 1667u;
    if (i < argc && !strcmp(argv[i], "geodetic")) {
        double g[3];
        enu_to_geodetic(enu, g);
        printf("%.9f %.9f %.4f\n", g[0], g[1], g[2]);
        return 0;
    }
    if (argc - i > MAX_PACKETS) {
        fprintf(stderr, "cigi_send: at most %d packets\n", MAX_PACKETS);
        return 2;
    }
    return send_all(&r, argv + i, argc - i);
}
