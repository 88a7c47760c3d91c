/* CIGI as an input of the player (cigi_source.h). */
#include "player/inputs/cigi_source.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gpio/effect_names.h"
#include "net/cigi/cigi_config.h"

static int check_effect(const char *name, char *why, size_t n, void *user)
{
    const sbfx *fx = user;
    if (sbfx_has_effect(fx, name)) return 0;
    char names[256];
    snprintf(why, n, "the scene has no effect named '%s' (its effects: %s)", name, effect_names(fx, names, sizeof(names)));
    return -EINVAL;
}

static int read_scene(struct cigi_source *c, const sbfx *fx, struct cigi_settings *s, char *err, size_t n)
{
    bool found = false;
    int rc = cigi_config_read(c->scene_path, s, &found, check_effect, (void *)fx, err, n);
    if (rc) return rc;
    if (!s->have_origin) {
        snprintf(err, n, "%s has no dis.origin: CIGI places entities relative to it (dis = { origin = [latitude, "
                 "longitude, height]; }; docs/simulators.md)", c->scene_path);
        return -EINVAL;
    }
    if (!found || !s->effects.count)
        c->log("cigi: the scene has no cigi.effects: entities are counted and ignored, the view and clock are used",
               c->log_user);
    return 0;
}

/* ---- events ---- */

static void on_view_definition(struct cigi_source *c, const struct cigi_view_definition *v)
{
    float *f = c->view.frustum;
    if (!c->view.have_frustum) f[0] = -30.0f, f[1] = 30.0f, f[2] = -20.0f, f[3] = 20.0f; /* until all are given */
    if (v->enable & CIGI_FOV_LEFT) f[0] = v->left;
    if (v->enable & CIGI_FOV_RIGHT) f[1] = v->right;
    if (v->enable & CIGI_FOV_BOTTOM) f[2] = v->bottom;
    if (v->enable & CIGI_FOV_TOP) f[3] = v->top;
    const char *why = player_channel_check_frustum(f);
    c->view.have_frustum = why == NULL;
    if (why && c->read_errors++ == 0) {
        char msg[160];
        snprintf(msg, sizeof(msg), "cigi: a View Definition's frustum is not used: %s (logged once)", why);
        c->log(msg, c->log_user);
    }
}

static void on_view_control(struct cigi_source *c, const struct cigi_view_control *v)
{
    if (v->enable & CIGI_VIEW_YAW) c->view.offset[0] = v->yaw;
    if (v->enable & CIGI_VIEW_PITCH) c->view.offset[1] = v->pitch;
    if (v->enable & CIGI_VIEW_ROLL) c->view.offset[2] = v->roll;
    c->view.have_offset = true;
}

static void on_event(struct cigi_source *c, struct trigger_queue *q, const struct cigi_event *e, int64_t now_ns)
{
    switch (e->kind) {
    case CIGI_EVENT_FRAME:
        if (!e->time.timestamp_valid) break;
        c->have_time = true;
        c->host_seconds = e->time.seconds;
        c->host_received_ns = e->received_ns;
        break;
    case CIGI_EVENT_EFFECT_START: {
        double start = c->world_clock && e->time.timestamp_valid ? e->time.seconds : NAN;
        trigger_queue_push_identified(q, TRIGGER_CIGI, e->effect.effect, e->effect.position, e->effect.identity, start,
                                      now_ns);
        break;
    }
    case CIGI_EVENT_EFFECT_STOP: trigger_queue_push_stop(q, TRIGGER_CIGI, e->effect.identity, now_ns); break;
    case CIGI_EVENT_OWNSHIP:
        c->ownship = e->ownship;
        if (!c->have_ownship) {
            char msg[256];
            const struct cigi_pose *o = &e->ownship;
            snprintf(msg, sizeof(msg), "cigi: the eyepoint rides on entity 0 at %.3f, %.3f, %.3f (yaw %.3f, pitch %.3f, "
                     "roll %.3f)", o->position[0], o->position[1], o->position[2], o->yaw, o->pitch, o->roll);
            c->log(msg, c->log_user);
        }
        c->have_ownship = true;
        break;
    case CIGI_EVENT_VIEW_DEFINITION: on_view_definition(c, &e->view_definition); break;
    case CIGI_EVENT_VIEW_CONTROL: on_view_control(c, &e->view_control); break;
    }
}

/* ---- the trigger-source contract ---- */

static int cigi_pollfds(const struct trigger_source *s, struct pollfd *fds, int max)
{
    int fd = cigi_receiver_fd(((const struct cigi_source *)s)->receiver);
    if (fd < 0 || max < 1) return 0;
    fds[0] = (struct pollfd){.fd = fd, .events = POLLIN};
    return 1;
}

static void cigi_service(struct trigger_source *s, struct trigger_queue *q, const sbfx *fx, int64_t now_ns)
{
    (void)fx; /* cigi.effects were checked when read */
    struct cigi_source *c = (struct cigi_source *)s;
    struct cigi_event e;
    /* the queue first: the receiver reads no more than its room allows */
    for (int round = 0; round < 4; round++) {
        int rc = cigi_receiver_service(c->receiver, now_ns);
        if (rc < 0 && c->read_errors++ == 0) {
            char msg[160];
            snprintf(msg, sizeof(msg), "cigi: reading the socket failed: %s (counted once, tried again each frame)",
                     strerror(-rc));
            c->log(msg, c->log_user);
        }
        while (cigi_receiver_next(c->receiver, &e)) on_event(c, q, &e, now_ns);
        if (rc <= 0) break;
    }
}

static void cigi_reload(struct trigger_source *s, const sbfx *fx)
{
    struct cigi_source *c = (struct cigi_source *)s;
    struct cigi_settings next = c->settings;
    memset(&next.effects, 0, sizeof(next.effects));
    next.have_origin = false;
    char why[512];
    if (read_scene(c, fx, &next, why, sizeof(why)) != 0) {
        char msg[640];
        snprintf(msg, sizeof(msg), "cigi: the reloaded scene's cigi group is not taken: %s (the previous one goes on)",
                 why);
        c->log(msg, c->log_user);
        return;
    }
    c->settings = next;
    cigi_receiver_configure(c->receiver, &c->settings);
}

static void cigi_close(struct trigger_source *s)
{
    struct cigi_source *c = (struct cigi_source *)s;
    cigi_receiver_close(c->receiver);
    c->receiver = NULL;
}

static const struct trigger_source_ops cigi_ops = {
    .pollfds = cigi_pollfds, .service = cigi_service, .reload = cigi_reload, .close = cigi_close,
};

static void receiver_log(const char *message, void *user)
{
    const struct cigi_source *c = user;
    c->log(message, c->log_user);
}

/* ---- opening ---- */

static int settle(struct cigi_source *c, const struct player_options *opt, const sbfx *fx, char *err, size_t n)
{
    struct cigi_settings *s = &c->settings;
    memset(s, 0, sizeof(*s));
    s->view_id = CIGI_ANY_VIEW;
    char why[256];
    if (udp_endpoint_parse(opt->cigi, &s->listen, why, sizeof(why)) != 0) {
        snprintf(err, n, "--cigi: %s", why);
        return -EINVAL;
    }
    if (opt->cigi_host) {
        if (udp_endpoint_parse(opt->cigi_host, &s->host, why, sizeof(why)) != 0 || !s->host.addr.s_addr) {
            snprintf(err, n, "--cigi-host: expected ADDR:PORT (the host's address and port for Start of Frame), "
                     "got '%s'%s%s", opt->cigi_host, why[0] ? ": " : "", why);
            return -EINVAL;
        }
        s->have_host = true;
    }
    return read_scene(c, fx, s, err, n);
}

int cigi_source_open(struct cigi_source *c, struct trigger_sources *all, const struct player_options *opt,
                     const sbfx *fx, input_log_fn log, void *user, char *err, size_t n)
{
    c->source = (struct trigger_source){.ops = &cigi_ops, .name = "cigi", .realtime = true};
    c->log = log;
    c->log_user = user;
    c->scene_path = opt->scene_path;
    c->world_clock = opt->world_clock == PLAYER_CLOCK_CIGI;
    if (!opt->cigi) {
        if (opt->cigi_host || c->world_clock) {
            snprintf(err, n, "%s needs --cigi [ADDR:]PORT", opt->cigi_host ? "--cigi-host" : "--world-clock cigi");
            return -EINVAL;
        }
        return 0;
    }
    if (!opt->scene_path) {
        snprintf(err, n, "--cigi needs --scene FILE with dis.origin (where the scene is on the Earth) and cigi.effects "
                 "(which entity types are effects; docs/simulators.md)");
        return -EINVAL;
    }
    int rc = settle(c, opt, fx, err, n);
    if (rc == 0) rc = cigi_receiver_open(&c->receiver, &c->settings, err, n);
    if (rc) return rc;
    cigi_receiver_set_log(c->receiver, receiver_log, c);
    if (!opt->quiet) {
        char msg[256];
        snprintf(msg, sizeof(msg), "cigi: listening on %s; Start of Frame to %s; %d effect entity types",
                 c->settings.listen.text, c->settings.have_host ? c->settings.host.text : "the sender of IG Control",
                 c->settings.effects.count);
        log(msg, user);
    }
    rc = trigger_sources_add(all, &c->source, err, n);
    if (rc) cigi_close(&c->source);
    return rc;
}

bool cigi_source_time(const struct cigi_source *c, int64_t now_ns, double *seconds)
{
    if (!c->receiver || !c->have_time) return false;
    *seconds = c->host_seconds + (double)(now_ns - c->host_received_ns) / 1e9;
    return true;
}

void cigi_source_frame_done(struct cigi_source *c, int64_t now_ns)
{
    if (!c->receiver) return;
    double seconds = (double)now_ns / 1e9;
    struct cigi_sof_info info = {
        .ig_frame = c->ig_frame++,
        .timestamp = (uint32_t)(uint64_t)(fmod(seconds, 42949.67296) * 1e5), /* 10 us ticks, wrapping as CIGI's */
        .timestamp_valid = true,
    };
    char err[256];
    if (cigi_receiver_send_sof(c->receiver, &info, err, sizeof(err)) < 0 && c->send_errors++ == 0) {
        char msg[352];
        snprintf(msg, sizeof(msg), "cigi: Start of Frame not sent: %s (counted, tried again each frame)", err);
        c->log(msg, c->log_user);
    }
}

const struct cigi_counts *cigi_source_counts(const struct cigi_source *c)
{
    return c->receiver ? cigi_receiver_counts(c->receiver) : NULL;
}
