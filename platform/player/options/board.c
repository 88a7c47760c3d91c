/* Board profiles from libconfig files (board.h). */
#include "player/options/board.h"

#include <errno.h>
#include <libconfig.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))

struct reader {
    const char *path;
    struct board_profile *b;
    char *err;
    size_t n;
};

static int fail_at(struct reader *r, const config_setting_t *s, const char *fmt, ...)
{
    char what[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof(what), fmt, ap);
    va_end(ap);
    snprintf(r->err, r->n, "%s:%u: %s", r->path, s ? config_setting_source_line(s) : 0u, what);
    return -EINVAL;
}

/* Every member of group must be one of keys (NULL-terminated). */
static int check_keys(struct reader *r, const config_setting_t *group, const char *where,
                      const char *const *keys)
{
    if (!config_setting_is_group(group)) return fail_at(r, group, "'%s' must be a group { ... }", where);
    for (int i = 0; i < config_setting_length(group); i++) {
        const config_setting_t *m = config_setting_get_elem(group, (unsigned)i);
        const char *name = config_setting_name(m);
        bool known = false;
        for (const char *const *k = keys; *k && !known; k++) known = strcmp(*k, name) == 0;
        if (known) continue;
        char list[192] = "";
        for (const char *const *k = keys; *k; k++)
            snprintf(list + strlen(list), sizeof(list) - strlen(list), "%s%s", k == keys ? "" : ", ", *k);
        return fail_at(r, m, "unknown key '%s' in %s (known: %s)", name, where, list);
    }
    return 0;
}

static int get_string(struct reader *r, const config_setting_t *g, const char *key, char *dst,
                      size_t cap)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) return 0;
    const char *v = config_setting_get_string(s);
    if (!v) return fail_at(r, s, "'%s' must be a string", key);
    if (strlen(v) >= cap) return fail_at(r, s, "'%s' is longer than %zu characters", key, cap - 1);
    snprintf(dst, cap, "%s", v);
    return 0;
}

static int get_int(struct reader *r, const config_setting_t *g, const char *key, int min, int max,
                   int *dst)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) return 0;
    if (config_setting_type(s) != CONFIG_TYPE_INT && config_setting_type(s) != CONFIG_TYPE_INT64)
        return fail_at(r, s, "'%s' must be a whole number", key);
    long long v = config_setting_get_int64(s);
    if (v < min || v > max) return fail_at(r, s, "'%s' = %lld is out of range %d..%d", key, v, min, max);
    *dst = (int)v;
    return 0;
}

static int get_choice(struct reader *r, const config_setting_t *g, const char *key,
                      const char *const *names, int *dst)
{
    char v[32] = "";
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) return 0;
    int rc = get_string(r, g, key, v, sizeof(v));
    if (rc) return rc;
    for (int i = 0; names[i]; i++)
        if (strcmp(names[i], v) == 0) {
            *dst = i;
            return 0;
        }
    return fail_at(r, s, "'%s' = \"%s\" is not one of the choices (%s|%s...)", key, v, names[0], names[1]);
}

static int get_vector(struct reader *r, const config_setting_t *g, const char *key, int count,
                      double limit, float *dst)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) return 0;
    if (!config_setting_is_array(s) || config_setting_length(s) != count)
        return fail_at(r, s, "'%s' must be an array of %d numbers", key, count);
    for (int i = 0; i < count; i++) {
        const config_setting_t *e = config_setting_get_elem(s, (unsigned)i);
        int type = config_setting_type(e);
        double v = type == CONFIG_TYPE_FLOAT ? config_setting_get_float(e)
                                             : (double)config_setting_get_int64(e);
        if (type != CONFIG_TYPE_FLOAT && type != CONFIG_TYPE_INT && type != CONFIG_TYPE_INT64)
            return fail_at(r, s, "'%s' must hold numbers", key);
        if (!(v >= -limit && v <= limit)) return fail_at(r, s, "'%s'[%d] is out of range", key, i);
        dst[i] = (float)v;
    }
    return 0;
}

static int read_display(struct reader *r, const config_setting_t *g)
{
    static const char *const keys[] = {"device", "connector", "mode", "modeset", "backend", NULL};
    static const char *const modesets[] = {"auto", "atomic", "legacy", NULL};
    static const char *const backends[] = {"drm", "wayland", "auto", NULL};
    struct board_profile *b = r->b;
    int modeset = (int)b->modeset, backend = -1, w, h, hz;
    int rc = check_keys(r, g, "display", keys);
    if (!rc) rc = get_string(r, g, "device", b->drm_device, sizeof(b->drm_device));
    if (!rc) rc = get_string(r, g, "connector", b->connector, sizeof(b->connector));
    if (!rc) rc = get_string(r, g, "mode", b->mode, sizeof(b->mode));
    if (!rc && b->mode[0] && mode_spec_parse(b->mode, &w, &h, &hz) != 0)
        rc = fail_at(r, config_setting_get_member(g, "mode"),
                     "'mode' = \"%s\" is not WxH or WxH@HZ (e.g. 1920x1080@60)", b->mode);
    if (!rc) rc = get_choice(r, g, "modeset", modesets, &modeset);
    b->modeset = (enum modeset_kind)modeset;
    if (!rc) rc = get_choice(r, g, "backend", backends, &backend);
    if (backend >= 0) snprintf(b->backend, sizeof(b->backend), "%s", backends[backend]);
    return rc;
}

static int read_video(struct reader *r, const config_setting_t *g)
{
    static const char *const keys[] = {"device", "size", NULL};
    float size[2] = {0, 0};
    int rc = check_keys(r, g, "video", keys);
    if (!rc) rc = get_string(r, g, "device", r->b->video_device, sizeof(r->b->video_device));
    if (!rc) rc = get_vector(r, g, "size", 2, 16384, size);
    if (!rc && (size[0] < 0 || size[1] < 0 || size[0] != (int)size[0] || size[1] != (int)size[1]))
        rc = fail_at(r, config_setting_get_member(g, "size"), "'size' must be two whole numbers >= 0");
    r->b->video_width = (int)size[0];
    r->b->video_height = (int)size[1];
    return rc;
}

static int read_line(struct reader *r, const config_setting_t *g, struct gpio_trigger_spec *t)
{
    static const char *const keys[] = {"chip", "line", "edge", "debounce_ms", "min_interval_ms",
                                       "effect", "position", NULL};
    static const char *const edges[] = {"none", "rising", "falling", "both", NULL};
    int edge = SBFX_EDGE_RISING;
    memset(t, 0, sizeof(*t));
    t->line = -1;
    t->debounce_ms = r->b->gpio_debounce_ms;
    t->min_interval_ms = r->b->gpio_min_interval_ms;
    snprintf(t->effect, sizeof(t->effect), "explosion");
    t->origin = "--board";
    int rc = check_keys(r, g, "a gpio line", keys);
    if (!rc) rc = get_string(r, g, "chip", t->chip, sizeof(t->chip));
    if (!rc) rc = get_int(r, g, "line", 0, 65535, &t->line);
    if (!rc) rc = get_choice(r, g, "edge", edges, &edge);
    if (!rc) rc = get_int(r, g, "debounce_ms", 0, 60000, &t->debounce_ms);
    if (!rc) rc = get_int(r, g, "min_interval_ms", 0, 3600000, &t->min_interval_ms);
    if (!rc) rc = get_string(r, g, "effect", t->effect, sizeof(t->effect));
    if (!rc) rc = get_vector(r, g, "position", 3, 1e6, t->position);
    if (!rc && (!t->chip[0] || t->line < 0)) rc = fail_at(r, g, "a gpio line needs 'chip' and 'line'");
    if (!rc && edge == 0) rc = fail_at(r, g, "'edge' of a trigger line cannot be \"none\"");
    t->edge = (sbfx_edge)edge;
    return rc;
}

static int read_gpio(struct reader *r, const config_setting_t *g)
{
    static const char *const keys[] = {"debounce_ms", "min_interval_ms", "lines", NULL};
    struct board_profile *b = r->b;
    int rc = check_keys(r, g, "gpio", keys);
    if (!rc) rc = get_int(r, g, "debounce_ms", 0, 60000, &b->gpio_debounce_ms);
    if (!rc) rc = get_int(r, g, "min_interval_ms", 0, 3600000, &b->gpio_min_interval_ms);
    const config_setting_t *lines = config_setting_get_member(g, "lines");
    if (rc || !lines) return rc;
    if (!config_setting_is_list(lines)) return fail_at(r, lines, "'lines' must be a list ( {...}, ... )");
    int count = config_setting_length(lines);
    if (count > GPIO_TRIGGERS_MAX) return fail_at(r, lines, "at most %d gpio lines", GPIO_TRIGGERS_MAX);
    for (int i = 0; i < count && !rc; i++)
        rc = read_line(r, config_setting_get_elem(lines, (unsigned)i), &b->gpio[i]);
    b->gpio_count = rc ? 0 : count;
    return rc;
}

static int read_render(struct reader *r, const config_setting_t *g)
{
    static const char *const keys[] = {"target_scale", "max_particles", NULL};
    struct board_profile *b = r->b;
    int rc = check_keys(r, g, "render", keys);
    if (!rc) rc = get_int(r, g, "target_scale", 1, 8, &b->target_scale);
    if (!rc && b->target_scale && (b->target_scale & (b->target_scale - 1)))
        rc = fail_at(r, config_setting_get_member(g, "target_scale"), "'target_scale' must be 1, 2, 4 or 8");
    if (!rc) rc = get_int(r, g, "max_particles", 1, 1 << 20, &b->max_particles);
    return rc;
}

static int read_mqtt(struct reader *r, const config_setting_t *g)
{
    static const char *const keys[] = {"host", "port", "topic", "status_topic", "username", "password_file",
                                       "ca_file", "min_interval_ms", NULL};
    struct mqtt_settings *m = &r->b->mqtt;
    int rc = check_keys(r, g, "mqtt", keys);
    if (!rc) rc = get_string(r, g, "host", m->host, sizeof(m->host));
    if (!rc && (!m->host[0] || strpbrk(m->host, " \t/")))
        rc = fail_at(r, g, "mqtt needs 'host', the broker's name or address (no port: that is 'port')");
    if (!rc) rc = get_int(r, g, "port", 1, 65535, &m->port);
    if (!rc) rc = get_string(r, g, "topic", m->topic, sizeof(m->topic));
    if (!rc) rc = get_string(r, g, "status_topic", m->status_topic, sizeof(m->status_topic));
    if (!rc) rc = get_string(r, g, "username", m->username, sizeof(m->username));
    if (!rc) rc = get_string(r, g, "password_file", m->password_file, sizeof(m->password_file));
    if (!rc && m->password_file[0] && !m->username[0])
        rc = fail_at(r, config_setting_get_member(g, "password_file"), "'password_file' needs 'username'");
    if (!rc) rc = get_string(r, g, "ca_file", m->ca_file, sizeof(m->ca_file));
    if (!rc) rc = get_int(r, g, "min_interval_ms", 0, 3600000, &r->b->mqtt_min_interval_ms);
    return rc;
}

static int read_dis(struct reader *r, const config_setting_t *g)
{
    static const char *const keys[] = {"listen", "interface", NULL};
    struct board_profile *b = r->b;
    struct udp_endpoint e;
    char why[256];
    int rc = check_keys(r, g, "dis", keys);
    if (!rc) rc = get_string(r, g, "listen", b->dis_listen, sizeof(b->dis_listen));
    if (!rc && b->dis_listen[0] && udp_endpoint_parse(b->dis_listen, &e, why, sizeof(why)) != 0)
        rc = fail_at(r, config_setting_get_member(g, "listen"), "'listen': %s", why);
    if (!rc) rc = get_string(r, g, "interface", b->dis_interface, sizeof(b->dis_interface));
    return rc;
}

static int read_channel(struct reader *r, const config_setting_t *g)
{
    static const char *const keys[] = {"frustum", "view_offset", NULL};
    struct player_channel *c = &r->b->channel;
    int rc = check_keys(r, g, "channel", keys);
    const config_setting_t *s;
    if (!rc && (s = config_setting_get_member(g, "frustum"))) {
        rc = get_vector(r, g, "frustum", 4, 89.0, c->frustum);
        const char *why = rc ? NULL : player_channel_check_frustum(c->frustum);
        if (why) rc = fail_at(r, s, "'frustum' [left, right, bottom, top]: %s", why);
        c->have_frustum = rc == 0;
    }
    if (!rc && config_setting_get_member(g, "view_offset")) {
        rc = get_vector(r, g, "view_offset", 3, 360.0, c->offset);
        c->have_offset = rc == 0;
    }
    return rc;
}

static int read_root(struct reader *r, const config_setting_t *root)
{
    static const char *const keys[] = {"board", "description", "display", "video", "gpio", "render", "mqtt", "dis",
                                       "channel", NULL};
    int rc = check_keys(r, root, "the profile", keys);
    if (!rc) rc = get_string(r, root, "board", r->b->name, sizeof(r->b->name));
    if (!rc) rc = get_string(r, root, "description", r->b->description, sizeof(r->b->description));
    const config_setting_t *s;
    if (!rc && (s = config_setting_get_member(root, "display"))) rc = read_display(r, s);
    if (!rc && (s = config_setting_get_member(root, "video"))) rc = read_video(r, s);
    if (!rc && (s = config_setting_get_member(root, "gpio"))) rc = read_gpio(r, s);
    if (!rc && (s = config_setting_get_member(root, "render"))) rc = read_render(r, s);
    if (!rc && (s = config_setting_get_member(root, "mqtt"))) rc = read_mqtt(r, s);
    if (!rc && (s = config_setting_get_member(root, "dis"))) rc = read_dis(r, s);
    if (!rc && (s = config_setting_get_member(root, "channel"))) rc = read_channel(r, s);
    return rc;
}

void board_profile_defaults(struct board_profile *b)
{
    memset(b, 0, sizeof(*b));
    b->gpio_debounce_ms = GPIO_DEFAULT_DEBOUNCE_MS;
    b->gpio_min_interval_ms = GPIO_DEFAULT_MIN_INTERVAL_MS;
    b->mqtt_min_interval_ms = GPIO_DEFAULT_MIN_INTERVAL_MS;
}

int board_load(const char *path, struct board_profile *b, char *err, size_t n)
{
    board_profile_defaults(b);
    FILE *f = fopen(path, "r");
    if (!f) {
        int rc = -errno;
        snprintf(err, n, "%s: cannot open the board profile: %s", path, strerror(errno));
        return rc;
    }
    config_t cfg;
    config_init(&cfg);
    int rc = 0;
    if (config_read(&cfg, f) != CONFIG_TRUE) {
        snprintf(err, n, "%s:%d: %s", path, config_error_line(&cfg), config_error_text(&cfg));
        rc = -EINVAL;
    } else {
        struct reader r = {.path = path, .b = b, .err = err, .n = n};
        rc = read_root(&r, config_root_setting(&cfg));
    }
    config_destroy(&cfg);
    fclose(f);
    if (rc) board_profile_defaults(b);
    return rc;
}
