/* The scene's cigi group and dis.origin (cigi_config.h). */
#include "net/cigi/cigi_config.h"

#include <errno.h>
#include <libconfig.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

struct reader {
    const char *path;
    cigi_effect_check_fn check;
    void *user;
    char *err;
    size_t n;
};

static int fail_at(struct reader *r, const config_setting_t *s, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static int fail_at(struct reader *r, const config_setting_t *s, const char *fmt, ...)
{
    char what[448];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof(what), fmt, ap);
    va_end(ap);
    const char *file = s && config_setting_source_file(s) ? config_setting_source_file(s) : r->path;
    snprintf(r->err, r->n, "%s:%u: %s", file, s ? config_setting_source_line(s) : 0u, what);
    return -EINVAL;
}

static int check_keys(struct reader *r, const config_setting_t *g, const char *where, const char *const *keys)
{
    if (!config_setting_is_group(g)) return fail_at(r, g, "%s must be a group { ... }", where);
    for (int i = 0; i < config_setting_length(g); i++) {
        const config_setting_t *m = config_setting_get_elem(g, (unsigned)i);
        bool known = false;
        for (const char *const *k = keys; *k && !known; k++) known = strcmp(*k, config_setting_name(m)) == 0;
        if (!known) return fail_at(r, m, "unknown key '%s' in %s", config_setting_name(m), where);
    }
    return 0;
}

/* dis.origin, as the dis group has it (net/dis/dis_config.c reads the rest of that group). */
static int read_origin(struct reader *r, const config_setting_t *root, struct cigi_settings *s)
{
    static const double limit[3] = {90.0, 180.0, 1e6};
    const config_setting_t *dis = config_setting_get_member(root, "dis");
    const config_setting_t *o = dis && config_setting_is_group(dis) ? config_setting_get_member(dis, "origin") : NULL;
    if (!o) return 0;
    if (!config_setting_is_array(o) || config_setting_length(o) != 3)
        return fail_at(r, o, "dis.origin must be [latitude, longitude, height] (degrees, degrees, metres)");
    for (int k = 0; k < 3; k++) {
        const config_setting_t *e = config_setting_get_elem(o, (unsigned)k);
        int type = config_setting_type(e);
        double v = type == CONFIG_TYPE_FLOAT ? config_setting_get_float(e)
                   : type == CONFIG_TYPE_INT || type == CONFIG_TYPE_INT64 ? (double)config_setting_get_int64(e)
                                                                         : NAN;
        if (!isfinite(v) || v < -limit[k] || v > limit[k])
            return fail_at(r, o, "dis.origin[%d] must be a number in -%g..%g", k, limit[k], limit[k]);
        s->origin[k] = v;
    }
    s->have_origin = true;
    return 0;
}

static int read_rule(struct reader *r, const config_setting_t *g, const struct cigi_effect_map *so_far,
                     struct cigi_effect_rule *rule)
{
    static const char *const keys[] = {"entity_type", "effect", NULL};
    int rc = check_keys(r, g, "a cigi.effects entry", keys);
    if (rc) return rc;
    const config_setting_t *type = config_setting_get_member(g, "entity_type");
    if (!type || config_setting_type(type) != CONFIG_TYPE_INT || config_setting_get_int(type) < 0 ||
        config_setting_get_int(type) > 65535)
        return fail_at(r, type ? type : g, "a cigi.effects entry needs entity_type = N, the host's entity type "
                       "(0..65535)");
    rule->entity_type = (uint16_t)config_setting_get_int(type);
    for (int i = 0; i < so_far->count; i++)
        if (so_far->rules[i].entity_type == rule->entity_type)
            return fail_at(r, type, "cigi.effects names entity_type %u twice", rule->entity_type);
    const char *effect = NULL;
    if (!config_setting_lookup_string(g, "effect", &effect) || !effect[0] || strlen(effect) >= sizeof(rule->effect))
        return fail_at(r, g, "a cigi.effects entry needs effect = \"NAME\" (an effect of the scene)");
    char why[320] = "";
    if (r->check && r->check(effect, why, sizeof(why), r->user) != 0)
        return fail_at(r, config_setting_get_member(g, "effect"), "cigi.effects: entity_type %u sets off '%s': %s",
                       rule->entity_type, effect, why);
    snprintf(rule->effect, sizeof(rule->effect), "%s", effect);
    return 0;
}

static int read_group(struct reader *r, const config_setting_t *g, struct cigi_settings *s)
{
    static const char *const keys[] = {"effects", NULL};
    int rc = check_keys(r, g, "cigi", keys);
    const config_setting_t *list = rc ? NULL : config_setting_get_member(g, "effects");
    if (rc || !list) return rc;
    if (!config_setting_is_list(list)) return fail_at(r, list, "cigi.effects must be a list ( { ... }, ... )");
    int count = config_setting_length(list);
    if (count > CIGI_EFFECTS_MAX)
        return fail_at(r, list, "cigi.effects has %d entries, at most %d", count, CIGI_EFFECTS_MAX);
    s->effects.count = 0;
    for (int i = 0; i < count; i++) {
        rc = read_rule(r, config_setting_get_elem(list, (unsigned)i), &s->effects, &s->effects.rules[i]);
        if (rc) return rc;
        s->effects.count = i + 1;
    }
    return 0;
}

int cigi_config_read(const char *scene_path, struct cigi_settings *s, bool *found, cigi_effect_check_fn check,
                     void *user, char *err, size_t n)
{
    *found = false;
    config_t cfg;
    config_init(&cfg);
    int rc = 0;
    if (config_read_file(&cfg, scene_path) != CONFIG_TRUE) {
        rc = config_error_type(&cfg) == CONFIG_ERR_FILE_IO ? -ENOENT : -EINVAL;
        snprintf(err, n, "%s:%d: %s", config_error_file(&cfg) ? config_error_file(&cfg) : scene_path,
                 config_error_line(&cfg), config_error_text(&cfg));
    } else {
        const config_setting_t *root = config_root_setting(&cfg);
        const config_setting_t *g = config_setting_get_member(root, "cigi");
        struct reader r = {scene_path, check, user, err, n};
        struct cigi_settings read = *s; /* s changes only when all of it is good */
        *found = g != NULL;
        rc = read_origin(&r, root, &read);
        if (!rc && g) rc = read_group(&r, g, &read);
        if (!rc) *s = read;
    }
    config_destroy(&cfg);
    return rc;
}
