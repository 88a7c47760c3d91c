/* The scene's dis group (dis_config.h). */
#include "net/dis/dis_config.h"

#include <errno.h>
#include <libconfig.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

struct reader {
    const char *path;
    char *err;
    size_t n;
};

static int fail_at(struct reader *r, const config_setting_t *s, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static int fail_at(struct reader *r, const config_setting_t *s, const char *fmt, ...)
{
    char what[320];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof(what), fmt, ap);
    va_end(ap);
    const char *file = s && config_setting_source_file(s) ? config_setting_source_file(s) : r->path;
    snprintf(r->err, r->n, "%s:%u: %s", file, s ? config_setting_source_line(s) : 0u, what);
    return -EINVAL;
}

static bool number_of(const config_setting_t *s, double *v)
{
    int type = config_setting_type(s);
    if (type == CONFIG_TYPE_FLOAT) *v = config_setting_get_float(s);
    else if (type == CONFIG_TYPE_INT || type == CONFIG_TYPE_INT64) *v = (double)config_setting_get_int64(s);
    else return false;
    return isfinite(*v);
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

static int read_origin(struct reader *r, const config_setting_t *g, struct dis_settings *s)
{
    static const double limit[3] = {90.0, 180.0, 1e6};
    const config_setting_t *o = config_setting_get_member(g, "origin");
    if (!o) return 0;
    if (!config_setting_is_array(o) || config_setting_length(o) != 3)
        return fail_at(r, o, "dis.origin must be [latitude, longitude, height] (degrees, degrees, metres)");
    for (int k = 0; k < 3; k++) {
        double v = 0;
        if (!number_of(config_setting_get_elem(o, (unsigned)k), &v) || v < -limit[k] || v > limit[k])
            return fail_at(r, o, "dis.origin[%d] must be a number in -%g..%g", k, limit[k], limit[k]);
        s->origin[k] = v;
    }
    s->have_origin = true;
    return 0;
}

static int read_scalars(struct reader *r, const config_setting_t *g, struct dis_settings *s)
{
    const config_setting_t *v;
    double range = 0;
    if ((v = config_setting_get_member(g, "range")) && (!number_of(v, &range) || range <= 0 || range > 1e7))
        return fail_at(r, v, "dis.range must be a distance in metres, 0 < range <= 1e7");
    if (v) s->range_m = range;
    if ((v = config_setting_get_member(g, "exercise"))) {
        if (config_setting_type(v) != CONFIG_TYPE_INT || config_setting_get_int(v) < 1 || config_setting_get_int(v) > 255)
            return fail_at(r, v, "dis.exercise must be an exercise ID, 1..255");
        s->exercise = config_setting_get_int(v);
    }
    if ((v = config_setting_get_member(g, "default"))) {
        const char *name = config_setting_get_string(v);
        if (!name || !name[0] || strlen(name) >= sizeof(s->effects.fallback))
            return fail_at(r, v, "dis.default must be an effect's name");
        snprintf(s->effects.fallback, sizeof(s->effects.fallback), "%s", name);
    }
    return 0;
}

static int read_rule(struct reader *r, const config_setting_t *g, struct dis_effect_rule *rule)
{
    static const char *const keys[] = {"munition", "result", "effect", NULL};
    int rc = check_keys(r, g, "a dis.effects rule", keys);
    if (rc) return rc;
    const char *munition = NULL, *effect = NULL, *why = "";
    if (!config_setting_lookup_string(g, "munition", &munition) || dis_munition_parse(munition, rule->munition, &why))
        return fail_at(r, g, "a dis.effects rule needs munition = \"K.D.C.C.S.S.E\" (fields a number or *, or "
                       "\"*\" for any)%s%s", munition ? ": " : "", munition ? why : "");
    if (!config_setting_lookup_string(g, "effect", &effect) || !effect[0] || strlen(effect) >= sizeof(rule->effect))
        return fail_at(r, g, "a dis.effects rule needs effect = \"NAME\"");
    snprintf(rule->effect, sizeof(rule->effect), "%s", effect);
    rule->result = DIS_ANY;
    const config_setting_t *result = config_setting_get_member(g, "result");
    if (result && (config_setting_type(result) != CONFIG_TYPE_INT || config_setting_get_int(result) < 0 ||
                   config_setting_get_int(result) > 255))
        return fail_at(r, result, "result must be a detonation result, 0..255");
    if (result) rule->result = config_setting_get_int(result);
    return 0;
}

static int read_effects(struct reader *r, const config_setting_t *g, struct dis_settings *s)
{
    const config_setting_t *list = config_setting_get_member(g, "effects");
    if (!list) return 0;
    if (!config_setting_is_list(list)) return fail_at(r, list, "dis.effects must be a list ( { ... }, ... )");
    int count = config_setting_length(list);
    if (count > DIS_EFFECTS_MAX) return fail_at(r, list, "dis.effects has %d rules, at most %d", count, DIS_EFFECTS_MAX);
    for (int i = 0; i < count; i++) {
        int rc = read_rule(r, config_setting_get_elem(list, (unsigned)i), &s->effects.rules[i]);
        if (rc) return rc;
    }
    s->effects.count = count;
    return 0;
}

static int read_group(struct reader *r, const config_setting_t *g, struct dis_settings *s)
{
    static const char *const keys[] = {"origin", "range", "exercise", "effects", "default", NULL};
    int rc = check_keys(r, g, "dis", keys);
    if (!rc) rc = read_origin(r, g, s);
    if (!rc) rc = read_scalars(r, g, s);
    if (!rc) rc = read_effects(r, g, s);
    return rc;
}

int dis_config_read(const char *scene_path, struct dis_settings *s, bool *found, char *err, size_t n)
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
        const config_setting_t *g = config_setting_get_member(config_root_setting(&cfg), "dis");
        struct dis_settings read = *s;
        struct reader r = {scene_path, err, n};
        *found = g != NULL;
        if (g) rc = read_group(&r, g, &read);
        if (!rc) *s = read;
    }
    config_destroy(&cfg);
    return rc;
}
