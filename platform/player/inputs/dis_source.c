/* DIS detonations as a trigger source (dis_source.h): the settings from the flags, the board and
 * the scene's dis group, then the receiver behind the trigger-source contract (inputs.h). */
#include "player/inputs/dis_source.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "gpio/effect_names.h"
#include "net/dis/dis_config.h"

static int check_effect(const struct dis_source *d, const sbfx *fx, const char *effect, const char *where, char *err,
                        size_t n)
{
    if (sbfx_has_effect(fx, effect)) return 0;
    char names[256];
    snprintf(err, n, "%s: %s sets off '%s', but the scene has no effect of that name (its effects: %s)",
             d->scene_path, where, effect, effect_names(fx, names, sizeof(names)));
    return -EINVAL;
}

/* What the scene's dis group sets, as a scene without those keys has it: a reloaded scene that
 * drops dis.exercise or dis.range goes back to the defaults. */
static void scene_defaults(struct dis_settings *s)
{
    s->exercise = DIS_ANY;
    s->range_m = DIS_DEFAULT_RANGE_M;
    s->have_origin = false;
    memset(s->origin, 0, sizeof(s->origin));
    memset(&s->effects, 0, sizeof(s->effects));
}

/* The scene's dis group into s, its effects checked against the module. */
static int read_scene_dis(const struct dis_source *d, const sbfx *fx, struct dis_settings *s, char *err, size_t n)
{
    bool found = false;
    int rc = dis_config_read(d->scene_path, s, &found, err, n);
    if (rc) return rc;
    if (!found || !s->have_origin) {
        snprintf(err, n, "%s has no dis.origin: DIS places detonations relative to it (dis = { origin = "
                 "[latitude, longitude, height]; ... }; docs/triggers.md)", d->scene_path);
        return -EINVAL;
    }
    for (int i = 0; i < s->effects.count && !rc; i++)
        rc = check_effect(d, fx, s->effects.rules[i].effect, "dis.effects", err, n);
    if (!rc && s->effects.fallback[0]) rc = check_effect(d, fx, s->effects.fallback, "dis.default", err, n);
    if (!rc && d->exercise_flag) s->exercise = d->exercise_flag;
    return rc;
}

static void say_listening(const struct dis_source *d, bool quiet)
{
    const struct dis_settings *s = &d->settings;
    if (!s->effects.count && !s->effects.fallback[0])
        d->log("dis: the scene has neither dis.effects nor dis.default: every detonation is counted and ignored",
               d->log_user);
    if (quiet) return;
    char exercise[24] = "any", msg[384];
    if (s->exercise != DIS_ANY) snprintf(exercise, sizeof(exercise), "%d", s->exercise);
    snprintf(msg, sizeof(msg), "dis: listening on %s%s%s (exercise %s); origin %.6f, %.6f, %.1f m, range %.1f km, "
             "%d effect rules%s%s", s->listen.text, s->interface[0] ? " on " : "", s->interface, exercise,
             s->origin[0], s->origin[1], s->origin[2], s->range_m / 1000.0, s->effects.count,
             s->effects.fallback[0] ? ", default " : "", s->effects.fallback);
    d->log(msg, d->log_user);
}

static double world_clock_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec / 1e9;
}

/* ---- the trigger-source contract ---- */

static int dis_pollfds(const struct trigger_source *s, struct pollfd *fds, int max)
{
    int fd = dis_receiver_fd(((const struct dis_source *)s)->receiver);
    if (fd < 0 || max < 1) return 0;
    fds[0] = (struct pollfd){.fd = fd, .events = POLLIN};
    return 1;
}

/* What the receiver's sink reaches during one service: the queue, the arrival time, the log. */
struct sink_context {
    struct dis_source *source;
    struct trigger_queue *queue;
    int64_t now_ns;
    double world_now;           /* the system clock (world time), when timestamps are used */
};

static void sink_fire(const char *effect, const float position[3], void *user)
{
    struct sink_context *c = user;
    trigger_queue_push(c->queue, TRIGGER_DIS, effect, position, c->now_ns);
}

/* A DIS timestamp's seconds past the hour (IEEE 1278.1: 2^31 units an hour in its upper 31 bits;
 * bit 0 set: absolute, the sender's clock) put in the hour nearest the world clock's `now`. */
double dis_timestamp_world(uint32_t timestamp, double now)
{
    double past_hour = (double)(timestamp >> 1) * 3600.0 / 2147483648.0;
    double hour = floor(now / 3600.0) * 3600.0, t = hour + past_hour;
    if (t - now > 1800.0) t -= 3600.0;
    else if (now - t > 1800.0) t += 3600.0;
    return t;
}

/* Identified by the event ID (site, application, event number) under DIS's tag, 2^61; started at
 * the PDU's absolute timestamp where the world clock is the system's, else when it fires. */
static void sink_fire_event(const char *effect, const float position[3], const struct dis_entity_id *event,
                            uint32_t timestamp, void *user)
{
    struct sink_context *c = user;
    uint64_t identity = (UINT64_C(1) << 61) | (uint64_t)event->site << 32 | (uint64_t)event->application << 16 |
                        event->entity;
    double start = NAN;
    if (c->source->world_timestamps && (timestamp & 1)) start = dis_timestamp_world(timestamp, c->world_now);
    trigger_queue_push_identified(c->queue, TRIGGER_DIS, effect, position, identity, start, c->now_ns);
}

static void sink_heard(uint32_t timestamp, void *user)
{
    struct sink_context *c = user;
    if (!(timestamp & 1)) return; /* relative: the sender's own count, no world time */
    struct dis_source *d = c->source;
    d->have_time = true;
    d->last_timestamp = timestamp;
    d->last_timestamp_ns = c->now_ns;
    d->last_timestamp_system = c->world_now;
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

void dis_orientation_local(const struct geo_frame *f, const float euler[3], float out[3])
{
    double cp = cos(euler[0]), sp = sin(euler[0]), ct = cos(euler[1]), st = sin(euler[1]);
    double cr = cos(euler[2]), sr = sin(euler[2]);
    /* the body's x (forward), y (right) and z (down) axes in ECEF: R = Rz(psi) Ry(theta) Rx(phi) */
    const double forward[3] = {ct * cp, ct * sp, -st};
    const double right[3] = {-cr * sp + sr * st * cp, cr * cp + sr * st * sp, sr * ct};
    const double down[3] = {sr * sp + cr * st * cp, -sr * cp + cr * st * sp, cr * ct};
    const double deg = 180.0 / M_PI;
    out[0] = (float)(atan2(dot3(forward, f->east), dot3(forward, f->north)) * deg);
    double up = dot3(forward, f->up);
    out[1] = (float)(asin(up > 1.0 ? 1.0 : up < -1.0 ? -1.0 : up) * deg);
    out[2] = (float)(atan2(-dot3(right, f->up), -dot3(down, f->up)) * deg);
}

static void sink_entity(const struct dis_entity_state *es, void *user)
{
    struct dis_source *d = ((struct sink_context *)user)->source;
    const struct dis_entity_id *id = &es->id, *want = &d->follow_id;
    if (!d->follow || id->site != want->site || id->application != want->application || id->entity != want->entity)
        return;
    double scene[3];
    geo_frame_scene(&d->frame, es->location, scene);
    for (int k = 0; k < 3; k++) d->pose_position[k] = (float)scene[k];
    dis_orientation_local(&d->frame, es->orientation, d->pose_angles);
    if (!d->have_pose) {
        char msg[256];
        snprintf(msg, sizeof(msg), "dis: following %u:%u:%u at %.3f, %.3f, %.3f (heading %.3f, pitch %.3f, roll %.3f)",
                 id->site, id->application, id->entity, d->pose_position[0], d->pose_position[1], d->pose_position[2],
                 d->pose_angles[0], d->pose_angles[1], d->pose_angles[2]);
        d->log(msg, d->log_user);
    }
    d->have_pose = true;
    d->poses++;
}

bool dis_source_time(const struct dis_source *d, int64_t now_ns, double *seconds)
{
    if (!d->receiver || !d->have_time) return false;
    *seconds = dis_timestamp_world(d->last_timestamp, d->last_timestamp_system) +
               (double)(now_ns - d->last_timestamp_ns) / 1e9;
    return true;
}

static void sink_log(const char *message, void *user)
{
    const struct sink_context *c = user;
    c->source->log(message, c->source->log_user);
}

static void dis_service(struct trigger_source *s, struct trigger_queue *q, const sbfx *fx, int64_t now_ns)
{
    (void)fx; /* the dis group's effects were checked when it was read */
    struct dis_source *d = (struct dis_source *)s;
    struct sink_context context = {d, q, now_ns, world_clock_now()};
    const struct dis_sink sink = {sink_fire, sink_log, &context, sink_fire_event, sink_heard, sink_entity};
    int rc = dis_receiver_service(d->receiver, now_ns, &sink);
    if (rc < 0 && d->read_errors++ == 0) {
        char msg[160];
        snprintf(msg, sizeof(msg), "dis: reading the socket failed: %s (counted once, tried again each frame)",
                 strerror(-rc));
        d->log(msg, d->log_user);
    }
}

static void dis_reload(struct trigger_source *s, const sbfx *fx)
{
    struct dis_source *d = (struct dis_source *)s;
    d->next = d->settings; /* the address and interface stay */
    scene_defaults(&d->next);
    char why[512];
    if (read_scene_dis(d, fx, &d->next, why, sizeof(why)) != 0) {
        char msg[640];
        snprintf(msg, sizeof(msg), "dis: the reloaded scene's dis group is not taken: %s (the previous one goes on)",
                 why);
        d->log(msg, d->log_user);
        return;
    }
    d->settings = d->next;
    dis_receiver_configure(d->receiver, &d->settings);
}

static void dis_close(struct trigger_source *s)
{
    struct dis_source *d = (struct dis_source *)s;
    dis_receiver_close(d->receiver);
    d->receiver = NULL;
}

static const struct trigger_source_ops dis_ops = {
    .pollfds = dis_pollfds, .service = dis_service, .reload = dis_reload, .close = dis_close,
};

/* ---- opening ---- */

/* The listening address (--dis over the board's dis.listen) and the scene's dis group. */
static int settle(struct dis_source *d, const char *listen, const struct player_options *opt,
                  const struct board_profile *b, const sbfx *fx, char *err, size_t n)
{
    struct dis_settings *s = &d->settings;
    memset(s, 0, sizeof(*s));
    scene_defaults(s);
    char why[256];
    if (udp_endpoint_parse(listen, &s->listen, why, sizeof(why)) != 0) {
        snprintf(err, n, "%s: %s", opt->dis ? "--dis" : "the board's dis.listen", why);
        return -EINVAL;
    }
    snprintf(s->interface, sizeof(s->interface), "%s", b->dis_interface);
    return read_scene_dis(d, fx, s, err, n);
}

int dis_source_open(struct dis_source *d, struct trigger_sources *all, const struct player_options *opt,
                    const struct board_profile *b, const sbfx *fx, input_log_fn log, void *user, char *err, size_t n)
{
    d->source = (struct trigger_source){.ops = &dis_ops, .name = "dis", .realtime = true};
    d->log = log;
    d->log_user = user;
    d->scene_path = opt->scene_path;
    d->exercise_flag = opt->dis_exercise;
    d->world_timestamps = opt->world_clock == PLAYER_CLOCK_SYSTEM || opt->world_clock == PLAYER_CLOCK_DIS;
    if (opt->world_clock == PLAYER_CLOCK_DIS && !opt->dis && !b->dis_listen[0]) {
        snprintf(err, n, "--world-clock dis needs --dis [ADDR:]PORT (or a board profile's dis.listen)");
        return -EINVAL;
    }
    const char *listen = opt->dis ? opt->dis : b->dis_listen[0] ? b->dis_listen : NULL;
    if (!listen) {
        if (opt->follow_set) {
            snprintf(err, n, "--follow needs --dis [ADDR:]PORT (or a board profile's dis.listen)");
            return -EINVAL;
        }
        if (!opt->dis_exercise) return 0;
        snprintf(err, n, "--dis-exercise needs --dis [ADDR:]PORT (or a board profile's dis.listen)");
        return -EINVAL;
    }
    if (!opt->scene_path) {
        snprintf(err, n, "--dis needs --scene FILE with a dis group: where the scene is on the Earth (dis.origin) "
                 "and which effect a munition sets off (dis.effects; docs/triggers.md)");
        return -EINVAL;
    }
    int rc = settle(d, listen, opt, b, fx, err, n);
    if (rc == 0) rc = dis_receiver_open(&d->receiver, &d->settings, err, n);
    if (rc == 0) geo_frame_init(&d->frame, d->settings.origin[0], d->settings.origin[1], d->settings.origin[2]);
    d->follow = opt->follow_set;
    d->follow_id = (struct dis_entity_id){opt->follow[0], opt->follow[1], opt->follow[2]};
    if (rc) return rc;
    say_listening(d, opt->quiet);
    rc = trigger_sources_add(all, &d->source, err, n);
    if (rc) dis_close(&d->source);
    return rc;
}

const struct dis_counts *dis_source_counts(const struct dis_source *d)
{
    return d->receiver ? dis_receiver_counts(d->receiver) : NULL;
}
