/* sbfx-play's inputs: the board profile, GPIO trigger lines (scene, board, --gpio; a later
 * source replaces an earlier one's spec for the same chip and line), the scene's detail clip and
 * the V4L2 camera. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "player/player.h"
#include "video/clip_detail.h"

int player_load_board(struct player *p, char *err, size_t n)
{
    board_profile_defaults(&p->board);
    if (!p->opt->board_path) return 0;
    char why[512];
    int rc = board_load(p->opt->board_path, &p->board, why, sizeof(why));
    if (rc) {
        snprintf(err, n, "--board: %s", why);
        return rc;
    }
    p->have_board = true;
    return 0;
}

static int add_spec(struct player *p, const struct gpio_trigger_spec *s, char *err, size_t n)
{
    for (int i = 0; i < p->gpio_spec_count; i++) {
        struct gpio_trigger_spec *o = &p->gpio_specs[i];
        if (o->line != s->line || strcmp(o->chip, s->chip) != 0 || strcmp(o->origin, s->origin) == 0)
            continue;
        *o = *s; /* the command line wins over the board, the board over the scene */
        return 0;
    }
    if (p->gpio_spec_count == GPIO_TRIGGERS_MAX) {
        snprintf(err, n, "%s: more than %d GPIO trigger lines", s->origin, GPIO_TRIGGERS_MAX);
        return -EINVAL;
    }
    p->gpio_specs[p->gpio_spec_count++] = *s;
    return 0;
}

int player_collect_scene_gpio(struct player *p, const sbfx_scene *scene, char *err, size_t n)
{
    const sbfx_gpio_trigger *t = NULL;
    int count = scene ? sbfx_scene_gpio_triggers(scene, &t) : 0;
    for (int i = 0; i < count; i++) {
        struct gpio_trigger_spec s = {
            .line = t[i].line, .edge = t[i].edge, .debounce_ms = t[i].debounce_ms,
            .min_interval_ms = p->board.gpio_min_interval_ms, .origin = "scene",
        };
        snprintf(s.chip, sizeof(s.chip), "%s", t[i].chip);
        snprintf(s.effect, sizeof(s.effect), "%s", t[i].effect);
        memcpy(s.position, t[i].position, sizeof(s.position));
        int rc = add_spec(p, &s, err, n);
        if (rc) return rc;
    }
    return 0;
}

static int collect_gpio(struct player *p, char *err, size_t n)
{
    int rc = 0;
    for (int i = 0; i < p->board.gpio_count && !rc; i++) rc = add_spec(p, &p->board.gpio[i], err, n);
    for (int i = 0; i < p->opt->gpio_count && !rc; i++) {
        const struct player_gpio *g = &p->opt->gpio[i];
        struct gpio_trigger_spec s = {
            .line = g->line, .edge = SBFX_EDGE_RISING, .debounce_ms = p->board.gpio_debounce_ms,
            .min_interval_ms = p->board.gpio_min_interval_ms, .origin = "--gpio",
        };
        snprintf(s.chip, sizeof(s.chip), "%s", g->chip);
        snprintf(s.effect, sizeof(s.effect), "%s", g->effect);
        memcpy(s.position, g->position, sizeof(s.position));
        rc = add_spec(p, &s, err, n);
    }
    return rc;
}

static const char *video_device(const struct player *p)
{
    if (p->opt->video) return p->opt->video;
    if (p->board.video_device[0] && sbfx_wants_live_detail(p->fx)) return p->board.video_device;
    return NULL;
}

int player_open_video(struct player *p, char *err, size_t n)
{
    const char *device = video_device(p);
    if (!device) {
        if (sbfx_wants_live_detail(p->fx))
            player_log("the scene asks for camera detail (source \"v4l2\") but neither --video nor "
                       "the board names a camera: procedural detail", p);
        return 0;
    }
    const struct live_detail_desc desc = {
        .device = device, .width = p->board.video_width, .height = p->board.video_height,
    };
    int rc = live_detail_start(&p->live, p->fx, &desc, player_log, p, err, n);
    p->live_on = rc == 0;
    return rc;
}

int player_open_clip(struct player *p, char *err, size_t n)
{
    const char *clip = sbfx_detail_clip(p->fx);
    if (!clip) return 0;
    struct clip_info info;
    int rc = clip_detail_load(p->fx, clip, &info, err, n);
    if (rc) return rc;
    char msg[512];
    clip_describe(clip, &info, msg, sizeof(msg));
    player_log(msg, p);
    return 0;
}

int player_open_inputs(struct player *p, char *err, size_t n)
{
    int rc = collect_gpio(p, err, n);
    if (rc == 0 && p->gpio_spec_count > 0) {
        rc = gpio_triggers_open(&p->gpio, p->gpio_specs, p->gpio_spec_count, p->fx, player_now_ns(),
                                player_log, p, err, n);
        p->gpio_on = rc == 0;
    }
    if (rc == 0) rc = player_open_clip(p, err, n);
    if (rc == 0) rc = player_open_video(p, err, n);
    return rc;
}

void player_close_inputs(struct player *p)
{
    if (p->gpio_on) gpio_triggers_close(&p->gpio);
    if (p->live_on) live_detail_stop(&p->live);
    p->gpio_on = p->live_on = false;
}

void player_service_gpio(struct player *p)
{
    if (p->gpio_on) gpio_triggers_service(&p->gpio, p->fx, player_now_ns(), player_log, p);
}

void player_service_video(struct player *p)
{
    if (p->live_on) live_detail_service(&p->live, player_now_ns());
}
