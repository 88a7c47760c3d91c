/* GPIO lines as a trigger source (gpio_source.h): their specs from the scene, the board profile
 * and --gpio, then the lines themselves behind the trigger-source contract (inputs.h). */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "player/inputs/gpio_source.h"

static int add_spec(struct gpio_source *g, const struct gpio_trigger_spec *s, char *err, size_t n)
{
    for (int i = 0; i < g->spec_count; i++) {
        struct gpio_trigger_spec *o = &g->specs[i];
        if (o->line != s->line || strcmp(o->chip, s->chip) != 0 || strcmp(o->origin, s->origin) == 0)
            continue;
        *o = *s; /* the command line wins over the board, the board over the scene */
        return 0;
    }
    if (g->spec_count == GPIO_TRIGGERS_MAX) {
        snprintf(err, n, "%s: more than %d GPIO trigger lines", s->origin, GPIO_TRIGGERS_MAX);
        return -EINVAL;
    }
    g->specs[g->spec_count++] = *s;
    return 0;
}

int gpio_source_add_scene(struct gpio_source *g, const sbfx_scene *scene, const struct board_profile *b, char *err,
                          size_t n)
{
    const sbfx_gpio_trigger *t = NULL;
    int count = scene ? sbfx_scene_gpio_triggers(scene, &t) : 0;
    for (int i = 0; i < count; i++) {
        struct gpio_trigger_spec s = {
            .line = t[i].line, .edge = t[i].edge, .debounce_ms = t[i].debounce_ms,
            .min_interval_ms = b->gpio_min_interval_ms, .origin = "scene",
        };
        snprintf(s.chip, sizeof(s.chip), "%s", t[i].chip);
        snprintf(s.effect, sizeof(s.effect), "%s", t[i].effect);
        memcpy(s.position, t[i].position, sizeof(s.position));
        int rc = add_spec(g, &s, err, n);
        if (rc) return rc;
    }
    return 0;
}

int gpio_source_add_options(struct gpio_source *g, const struct board_profile *b, const struct player_options *opt,
                            char *err, size_t n)
{
    int rc = 0;
    for (int i = 0; i < b->gpio_count && !rc; i++) rc = add_spec(g, &b->gpio[i], err, n);
    for (int i = 0; i < opt->gpio_count && !rc; i++) {
        const struct player_gpio *pg = &opt->gpio[i];
        struct gpio_trigger_spec s = {
            .line = pg->line, .edge = SBFX_EDGE_RISING, .debounce_ms = b->gpio_debounce_ms,
            .min_interval_ms = b->gpio_min_interval_ms, .origin = "--gpio",
        };
        snprintf(s.chip, sizeof(s.chip), "%s", pg->chip);
        snprintf(s.effect, sizeof(s.effect), "%s", pg->effect);
        memcpy(s.position, pg->position, sizeof(s.position));
        rc = add_spec(g, &s, err, n);
    }
    return rc;
}

/* ---- the trigger-source contract ---- */

static int gpio_pollfds(const struct trigger_source *s, struct pollfd *fds, int max)
{
    const struct gpio_source *g = (const struct gpio_source *)s;
    return gpio_triggers_pollfds(&g->lines, fds, max);
}

/* A passing edge, into the queue (the lines' fire hook): false when the queue refuses it. */
static bool queue_edge(const char *effect, const float position[3], int64_t at_ns, void *user)
{
    return trigger_queue_push(user, TRIGGER_GPIO, effect, position, at_ns);
}

static void gpio_service(struct trigger_source *s, struct trigger_queue *q, const sbfx *fx, int64_t now_ns)
{
    (void)fx; /* the lines' effects were checked at open */
    struct gpio_source *g = (struct gpio_source *)s;
    g->lines.fire = queue_edge;
    g->lines.fire_user = q;
    gpio_triggers_service(&g->lines, NULL, now_ns, g->log, g->log_user);
}

static void gpio_close(struct trigger_source *s)
{
    struct gpio_source *g = (struct gpio_source *)s;
    if (g->on) gpio_triggers_close(&g->lines);
    g->on = false;
}

static const struct trigger_source_ops gpio_ops = {
    .pollfds = gpio_pollfds, .service = gpio_service, .reload = NULL, .close = gpio_close,
};

int gpio_source_open(struct gpio_source *g, struct trigger_sources *all, const sbfx *fx, int64_t now_ns,
                     input_log_fn log, void *user, char *err, size_t n)
{
    g->source = (struct trigger_source){.ops = &gpio_ops, .name = "gpio"};
    g->log = log;
    g->log_user = user;
    if (g->spec_count == 0) return 0;
    int rc = gpio_triggers_open(&g->lines, g->specs, g->spec_count, fx, now_ns, log, user, err, n);
    if (rc) return rc;
    g->on = true;
    rc = trigger_sources_add(all, &g->source, err, n);
    if (rc) gpio_close(&g->source);
    return rc;
}
