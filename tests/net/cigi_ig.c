/* tests/cigi.sh's image generator: the player's CIGI receiver (platform/net/cigi/) alone, on a
 * socket, as the player's frame loop drives it: each turn reads what waits, prints every event as
 * a line, and answers each turn that heard an IG Control with one Start of Frame.
 *
 *   cigi_ig --listen [ADDR:]PORT --origin LAT,LON,ALT [--effect TYPE=NAME]... [--host ADDR:PORT]
 *           [--view V] [--frames N] [--quiet-s S]
 * stops after N IG Controls (--frames, default 1), or when S seconds (--quiet-s, 10) pass
 * without a message (exit 3); prints "listening" on stderr once the socket is open, and at the
 * end "counts messages=... packets=... used=... ignored=... malformed=... entities=... stops=...
 * active=... sof_sent=... sof_unaddressed=... dropped=...". The Start of Frame: ig_frame the
 * turns answered (1, 2...), the timestamp of the host's last IG Control, IG status 0.
 *
 *   cigi_ig --bench FILE N --origin LAT,LON,ALT [--effect TYPE=NAME]...
 * the receiver's cost without a socket: FILE's message (cigi_send --file) handed to it N times,
 * its events drained each time; prints "bench messages=N packets=P ns_per_message=X
 * ns_per_packet=Y". */
#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "net/cigi/cigi_receiver.h"

static const char *const stop_names[] = {"destroyed", "inactive", "animation"};

static void print_effect(const char *what, const struct cigi_effect *e)
{
    printf("%s entity=%u type=%u gen=%u activation=%u identity=%llu effect=%s", what, e->entity_id, e->entity_type,
           e->generation, e->activation_frame, (unsigned long long)e->identity, e->effect);
    if (!strcmp(what, "stop")) printf(" reason=%s\n", stop_names[e->reason]);
    else printf(" pos=%.3f,%.3f,%.3f geo=%.9f,%.9f,%.4f ypr=%g,%g,%g\n", e->position[0], e->position[1],
                e->position[2], e->geodetic[0], e->geodetic[1], e->geodetic[2], e->yaw, e->pitch, e->roll);
}

static void print_event(const struct cigi_event *e)
{
    const struct cigi_time *t = &e->time;
    switch (e->kind) {
    case CIGI_EVENT_FRAME:
        printf("frame host_frame=%u timestamp=%u valid=%d seconds=%.5f db=%d mode=%u minor=%u order=%s\n",
               t->host_frame, t->timestamp, t->timestamp_valid, t->seconds, e->frame.database, e->frame.ig_mode,
               e->frame.minor_version, e->frame.little_endian ? "le" : "be");
        break;
    case CIGI_EVENT_EFFECT_START: print_effect("start", &e->effect); break;
    case CIGI_EVENT_EFFECT_STOP: print_effect("stop", &e->effect); break;
    case CIGI_EVENT_OWNSHIP:
        printf("ownship pos=%.3f,%.3f,%.3f geo=%.9f,%.9f,%.4f ypr=%g,%g,%g\n", e->ownship.position[0],
               e->ownship.position[1], e->ownship.position[2], e->ownship.geodetic[0], e->ownship.geodetic[1],
               e->ownship.geodetic[2], e->ownship.yaw, e->ownship.pitch, e->ownship.roll);
        break;
    case CIGI_EVENT_VIEW_DEFINITION: {
        const struct cigi_view_definition *v = &e->view_definition;
        printf("view-def view=%u group=%u enable=0x%02x left=%g right=%g bottom=%g top=%g near=%g far=%g\n", v->view_id,
               v->group_id, v->enable, v->left, v->right, v->bottom, v->top, v->near_m, v->far_m);
        break;
    }
    case CIGI_EVENT_VIEW_CONTROL: {
        const struct cigi_view_control *v = &e->view_control;
        printf("view-ctrl view=%u group=%u entity=%u enable=0x%02x xyz=%g,%g,%g ypr=%g,%g,%g\n", v->view_id, v->group_id,
               v->entity_id, v->enable, v->offset[0], v->offset[1], v->offset[2], v->yaw, v->pitch, v->roll);
        break;
    }
    }
}

static void log_line(const char *message, void *user)
{
    (void)user;
    fprintf(stderr, "%s\n", message);
}

static int64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

static const char *bench_file;
static long bench_count;

static int options(int argc, char **argv, struct cigi_settings *s, int *frames, int *quiet_s)
{
    char err[256];
    for (int i = 1; i + 1 < argc; i += 2) {
        const char *k = argv[i], *v = argv[i + 1];
        struct cigi_effect_rule *rule = &s->effects.rules[s->effects.count];
        unsigned type = 0;
        int used = 0;
        if (!strcmp(k, "--listen") && udp_endpoint_parse(v, &s->listen, err, sizeof(err)) == 0) continue;
        if (!strcmp(k, "--bench") && i + 2 < argc) {
            bench_file = v;
            bench_count = atol(argv[++i + 1]);
            continue;
        }
        if (!strcmp(k, "--host") && udp_endpoint_parse(v, &s->host, err, sizeof(err)) == 0) s->have_host = true;
        else if (!strcmp(k, "--origin") && sscanf(v, "%lf,%lf,%lf", &s->origin[0], &s->origin[1], &s->origin[2]) == 3)
            s->have_origin = true;
        else if (!strcmp(k, "--view")) s->view_id = atoi(v);
        else if (!strcmp(k, "--frames")) *frames = atoi(v);
        else if (!strcmp(k, "--quiet-s")) *quiet_s = atoi(v);
        else if (!strcmp(k, "--effect") && s->effects.count < CIGI_EFFECTS_MAX && sscanf(v, "%u=%n", &type, &used) == 1 &&
                 used > 0 && v[used]) {
            rule->entity_type = (uint16_t)type;
            snprintf(rule->effect, sizeof(rule->effect), "%s", v + used);
            s->effects.count++;
        } else {
            fprintf(stderr, "cigi_ig: bad option %s %s\n", k, v);
            return 2;
        }
    }
    return 0;
}

/* One turn: read, print, answer. The number of IG Controls heard. */
static int turn(struct cigi_receiver *r, int *answered)
{
    int rc = cigi_receiver_service(r, now_ns());
    if (rc < 0) fprintf(stderr, "cigi_ig: reading: %s\n", strerror(-rc));
    struct cigi_event e;
    int frames = 0;
    uint32_t timestamp = 0;
    while (cigi_receiver_next(r, &e)) {
        print_event(&e);
        if (e.kind == CIGI_EVENT_FRAME) {
            frames++;
            timestamp = e.time.timestamp;
        }
    }
    if (frames) {
        const struct cigi_sof_info info = {.ig_frame = (uint32_t)++*answered, .timestamp = timestamp,
                                           .timestamp_valid = true};
        char err[256];
        if (cigi_receiver_send_sof(r, &info, err, sizeof(err)) < 0) fprintf(stderr, "%s\n", err);
    }
    fflush(stdout);
    return frames;
}

static int bench(const struct cigi_settings *s)
{
    static uint8_t message[CIGI_MAX_MESSAGE];
    FILE *f = fopen(bench_file, "rb");
    size_t n = f ? fread(message, 1, sizeof(message), f) : 0;
    if (f) fclose(f);
    struct cigi_receiver *r;
    char err[512];
    if (!n || bench_count < 1 || cigi_receiver_make(&r, s, err, sizeof(err)) != 0) {
        fprintf(stderr, "cigi_ig: --bench %s %ld: no message, no count, or %s\n", bench_file, bench_count, err);
        return 2;
    }
    struct cigi_event e;
    int64_t t0 = now_ns();
    for (long i = 0; i < bench_count; i++) {
        cigi_receiver_datagram(r, message, n, false, NULL, i);
        while (cigi_receiver_next(r, &e)) {}
    }
    int64_t t1 = now_ns();
    const struct cigi_counts *c = cigi_receiver_counts(r);
    printf("bench messages=%ld packets=%llu ns_per_message=%.1f ns_per_packet=%.1f\n", bench_count,
           (unsigned long long)c->packets, (double)(t1 - t0) / (double)bench_count,
           (double)(t1 - t0) / (double)c->packets);
    cigi_receiver_close(r);
    return 0;
}

int main(int argc, char **argv)
{
    static struct cigi_settings s = {.view_id = CIGI_ANY_VIEW};
    int frames = 1, quiet_s = 10, heard = 0, answered = 0;
    int rc = options(argc, argv, &s, &frames, &quiet_s);
    if (rc == 0 && bench_file) return bench(&s);
    if (rc != 0 || !s.listen.port) {
        fprintf(stderr, "usage: cigi_ig --listen [ADDR:]PORT --origin LAT,LON,ALT [--effect TYPE=NAME]... "
                "[--host ADDR:PORT] [--view V] [--frames N] [--quiet-s S], or --bench FILE N --origin ...\n");
        return 2;
    }
    struct cigi_receiver *r;
    char err[512];
    if (cigi_receiver_open(&r, &s, err, sizeof(err)) != 0) {
        fprintf(stderr, "cigi_ig: %s\n", err);
        return 1;
    }
    cigi_receiver_set_log(r, log_line, NULL);
    fprintf(stderr, "listening\n");
    int64_t last = now_ns();
    while (heard < frames) {
        struct pollfd pfd = {.fd = cigi_receiver_fd(r), .events = POLLIN};
        poll(&pfd, 1, 20);
        int got = turn(r, &answered);
        if (got) last = now_ns();
        heard += got;
        if (now_ns() - last > (int64_t)quiet_s * 1000000000) break;
    }
    const struct cigi_counts *c = cigi_receiver_counts(r);
    printf("counts messages=%llu packets=%llu used=%llu ignored=%llu malformed=%llu entities=%llu stops=%llu active=%llu "
           "sof_sent=%llu sof_unaddressed=%llu dropped=%llu\n", (unsigned long long)c->messages,
           (unsigned long long)c->packets, (unsigned long long)c->used, (unsigned long long)c->ignored,
           (unsigned long long)c->malformed, (unsigned long long)c->entities, (unsigned long long)c->stops,
           (unsigned long long)c->active, (unsigned long long)c->sof_sent, (unsigned long long)c->sof_unaddressed,
           (unsigned long long)c->events_dropped);
    cigi_receiver_close(r);
    return heard < frames ? 3 : 0;
}
