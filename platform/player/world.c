/* One world, many channels (docs/simulators.md): the world clock the frames are drawn at, the
 * triggers started at world times as identified instances (sbfx_trigger_identified), and the
 * channel's view (its frustum and view offset from the eyepoint).
 *
 * World mode (--world-time, --world-clock system|cigi|dis): frames lie on the grid k / fps from world
 * time 0, so frames of different channels at the same k are at the same world time; the module's
 * clock (desc.start_time) starts at the whole minute at or before the first frame and is brought
 * to it in fixed steps, so channels started within the same minute have clocks equal to the bit.
 * --trigger entries and the scene's timeline start at their world times, identified (the #ID, or
 * their order), and one that started before the first frame is drawn at its age. Outside world
 * mode only --trigger entries with #ID are identified, at the module's clock. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "player/player.h"

#define WORLD_BASE_GRID 60.0  /* s: the module's clock starts on a whole minute of world time */
#define NS_PER_S 1e9

/* identities the player makes (1..2^63-1; CIGI's start at 2^62, DIS's at 2^61) */
#define IDENTITY_CLI (UINT64_C(1) << 60)      /* + the --trigger's order, 1.. */
#define IDENTITY_TIMELINE (UINT64_C(1) << 59) /* + the timeline entry's order, 1.. */

double world_system_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec / NS_PER_S;
}

bool world_mode(const struct player_options *opt)
{
    return opt->world_time_set || opt->world_clock != PLAYER_CLOCK_FRAMES;
}

/* The first frame's index on the grid k / fps. */
int world_setup(struct player *p, char *err, size_t n)
{
    const struct player_options *opt = p->opt;
    struct world *w = &p->world;
    memset(w, 0, sizeof(*w));
    w->on = world_mode(opt);
    if (!w->on) return 0;
    double first = opt->world_time;
    /* the system clock; DIS's timestamps, seconds past the system clock's hour, lie within half an
     * hour of it: the module starts half an hour before and follows them (module.c, advance) */
    if (!opt->world_time_set && opt->world_clock == PLAYER_CLOCK_SYSTEM) first = world_system_seconds();
    if (!opt->world_time_set && opt->world_clock == PLAYER_CLOCK_DIS) first = world_system_seconds() - 1800.0;
    double k = opt->world_time_set ? round(first * opt->fps) : ceil(first * opt->fps);
    if (opt->world_time_set && fabs(first * opt->fps - k) > 1e-6) {
        snprintf(err, n, "--world-time %.9g is not on the frame grid k / fps (fps %g): the nearest are %.9g and "
                 "%.9g", first, opt->fps, floor(first * opt->fps) / opt->fps, ceil(first * opt->fps) / opt->fps);
        return -EINVAL;
    }
    w->first_k = (int64_t)k;
    w->base = floor((double)w->first_k / opt->fps / WORLD_BASE_GRID) * WORLD_BASE_GRID;
    return 0;
}

double world_frame_time(const struct player *p, int64_t index)
{
    return (double)(p->world.first_k + index) / p->opt->fps;
}

/* ---- triggers at world times -------------------------------------------------------------- */

static uint64_t cli_identity(const struct player_trigger *t, int order)
{
    return t->id ? t->id : IDENTITY_CLI + (uint64_t)order + 1;
}

/* The --trigger entries that are identified: all in world mode, those with #ID otherwise. */
bool world_trigger_identified(const struct player *p, const struct player_trigger *t)
{
    return p->world.on || t->id != 0;
}

static int start(struct player *p, enum trigger_kind kind, const char *effect, const float position[3],
                 uint64_t identity, double at, const char *what, char *err, size_t n)
{
    sbfx_trigger_desc d = {.version = SBFX_TRIGGER_DESC_VERSION, .effect = effect, .identity = identity,
                           .start_time = at};
    memcpy(d.position, position, sizeof(d.position));
    p->triggers.queue.firing = kind; /* the trigger log's source */
    sbfx_result r = sbfx_trigger_identified(p->fx, &d);
    if (r == SBFX_OK || r == SBFX_ERR_POOL_FULL) return 0; /* a full pool is counted, as for any trigger */
    snprintf(err, n, "%s %s at %.6f s (identity %llu): %s: %s", what, effect, at, (unsigned long long)identity,
             sbfx_result_string(r), sbfx_last_error(p->fx));
    return -EINVAL;
}

/* The clock (sbfx_time) a --trigger's SECONDS stands for. */
static double trigger_clock(const struct player *p, double seconds)
{
    return p->world.on ? seconds : p->opt->start_time + seconds;
}

/* Starts the identified --trigger entries and (world mode) timeline entries whose start is at or
 * before the frame's clock `now`; each once. */
int world_fire_due(struct player *p, double now, char *err, size_t n)
{
    const struct player_options *opt = p->opt;
    struct world *w = &p->world;
    for (int i = 0; i < opt->trigger_count; i++) {
        const struct player_trigger *t = &opt->triggers[i];
        double at = trigger_clock(p, t->seconds);
        if (!world_trigger_identified(p, t) || (w->cli_fired[i / 64] >> (i % 64) & 1) || at > now + 1e-9) continue;
        w->cli_fired[i / 64] |= UINT64_C(1) << (i % 64);
        int rc = start(p, TRIGGER_CLI, t->effect, t->position, cli_identity(t, i), at, "--trigger", err, n);
        if (rc) return rc;
    }
    if (!w->on || opt->no_timeline) return 0;
    for (int i = 0; i < w->timeline_count; i++) {
        const struct world_timeline_entry *t = &w->timeline[i];
        if ((w->timeline_fired[i / 64] >> (i % 64) & 1) || t->time > now + 1e-9) continue;
        w->timeline_fired[i / 64] |= UINT64_C(1) << (i % 64);
        int rc = start(p, TRIGGER_TIMELINE, t->effect, t->position, IDENTITY_TIMELINE + (uint64_t)i + 1, t->time,
                       "the timeline's", err, n);
        if (rc) return rc;
    }
    return 0;
}

void world_take_timeline(struct player *p, const sbfx_scene *scene)
{
    struct world *w = &p->world;
    sbfx_timeline_trigger t;
    w->timeline_count = 0;
    memset(w->timeline_fired, 0, sizeof(w->timeline_fired));
    for (int i = 0; i < WORLD_TIMELINE_MAX && sbfx_scene_timeline_get(scene, i, &t); i++) {
        struct world_timeline_entry *e = &w->timeline[w->timeline_count++];
        snprintf(e->effect, sizeof(e->effect), "%s", t.effect);
        e->time = t.time;
        memcpy(e->position, t.position, sizeof(e->position));
    }
}

/* ---- the channel's view ------------------------------------------------------------------- */

static void multiply(const float a[16], const float b[16], float out[16])
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++) s += (double)a[k * 4 + r] * (double)b[c * 4 + k];
            out[c * 4 + r] = (float)s;
        }
}

/* The eyepoint's camera turned by the offset, as a view matrix: view' = R^-1 view, R = yaw about
 * +y (right positive), then pitch about +x (up positive), then roll about -z (right positive). */
static void offset_view(const float offset[3], float view[16])
{
    double y = -offset[0] * M_PI / 180.0, x = offset[1] * M_PI / 180.0, z = -offset[2] * M_PI / 180.0;
    double cy = cos(y), sy = sin(y), cx = cos(x), sx = sin(x), cz = cos(z), sz = sin(z);
    /* R = Ry Rx Rz (column-major rows r, columns c); R^-1 = R^T */
    double r[3][3] = {{cy * cz + sy * sx * sz, -cy * sz + sy * sx * cz, sy * cx},
                      {cx * sz, cx * cz, -sx},
                      {-sy * cz + cy * sx * sz, sy * sz + cy * sx * cz, cy * cx}};
    float inverse[16] = {0};
    for (int row = 0; row < 3; row++)
        for (int col = 0; col < 3; col++) inverse[col * 4 + row] = (float)r[col][row];
    inverse[15] = 1.0f;
    float turned[16];
    multiply(inverse, view, turned);
    memcpy(view, turned, sizeof(turned));
}

void world_eyepoint_view(const float position[3], const float angles[3], float view[16])
{
    float translate[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    for (int k = 0; k < 3; k++) translate[12 + k] = -position[k];
    memcpy(view, translate, sizeof(translate));
    /* the camera looks down -z, north in the scene (x east, y up, z south): heading = yaw */
    offset_view(angles, view);
}

bool world_eyepoint(const struct player *p, float view[16])
{
    if (p->cigi.have_ownship) { /* CIGI's entity 0 */
        const struct cigi_pose *o = &p->cigi.ownship;
        const float angles[3] = {o->yaw, o->pitch, o->roll};
        world_eyepoint_view(o->position, angles, view);
        return true;
    }
    if (p->dis.have_pose) { /* --follow: a DIS entity */
        world_eyepoint_view(p->dis.pose_position, p->dis.pose_angles, view);
        return true;
    }
    return false; /* the scene's camera */
}

struct player_channel world_channel(const struct player *p)
{
    struct player_channel c = p->channel;
    const struct player_channel *host = &p->cigi.view;
    if (host->have_frustum) memcpy(c.frustum, host->frustum, sizeof(c.frustum)), c.have_frustum = true;
    if (host->have_offset) memcpy(c.offset, host->offset, sizeof(c.offset)), c.have_offset = true;
    return c;
}

void world_channel_view(const struct player_channel *c, float near_z, float far_z, float view[16],
                        float projection[16])
{
    if (c->have_offset) offset_view(c->offset, view);
    if (!c->have_frustum) return;
    float t[4];
    for (int i = 0; i < 4; i++) t[i] = (float)tan(c->frustum[i] * M_PI / 180.0) * near_z;
    sbfx_frustum(projection, t[0], t[1], t[2], t[3], near_z, far_z);
}
