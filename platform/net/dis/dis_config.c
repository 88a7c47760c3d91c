/* The scene's dis group (dis_config.h). */
#include "net/dis/dis_config.h"

#include <stdio.h>
#include <string.h>

#include "net/common/scene_group.h"

static int read_scalars(struct scene_reader *r, const config_setting_t *g, struct dis_settings *s)
{
    const config_setting_t *v;
    double range = 0;
    if ((v = config_setting_get_member(g, "range")) && (!scene_group_number(v, &range) || range <= 0 || range > 1e7))
        return scene_group_fail(r, v, "dis.range must be a distance in metres, 0 < range <= 1e7");
    if (v) s->range_m = range;
    if ((v = config_setting_get_member(g, "exercise"))) {
        if (config_setting_type(v) != CONFIG_TYPE_INT || config_setting_get_int(v) < 1 || config_setting_get_int(v) > 255)
            return scene_group_fail(r, v, "dis.exercise must be an exercise ID, 1..255");
        s->exercise = config_setting_get_int(v);
    }
    if ((v = config_setting_get_member(g, "default"))) {
        const char *name = config_setting_get_string(v);
        if (!name || !name[0] || strlen(name) >= sizeof(s->effects.fallback))
            return scene_group_fail(r, v, "dis.default must be an effect's name");
        snprintf(s->effects.fallback, sizeof(s->effects.fallback), "%s", name);
    }
    return 0;
}

static int read_rule(struct scene_reader *r, const config_setting_t *g, struct dis_effect_rule *rule)
{
    static const char *const keys[] = {"munition", "result", "effect", NULL};
    int rc = scene_group_check_keys(r, g, "a dis.effects rule", keys);
    if (rc) return rc;
    const char *munition = NULL, *effect = NULL, *why = "";
    if (!config_setting_lookup_string(g, "munition", &munition) || dis_munition_parse(munition, rule->munition, &why))
        return scene_group_fail(r, g, "a dis.effects rule needs munition = \"K.D.C.C.S.S.E\" (fields a number or *, or "
                                "\"*\" for any)%s%s", munition ? ": " : "", munition ? why : "");
    if (!config_setting_lookup_string(g, "effect", &effect) || !effect[0] || strlen(effect) >= sizeof(rule->effect))
        return scene_group_fail(r, g, "a dis.effects rule needs effect = \"NAME\"");
    snprintf(rule->effect, sizeof(rule->effect), "%s", effect);
    rule->result = DIS_ANY;
    const config_setting_t *result = config_setting_get_member(g, "result");
    if (result && (config_setting_type(result) != CONFIG_TYPE_INT || config_setting_get_int(result) < 0 ||
                   config_setting_get_int(result) > 255))
        return scene_group_fail(r, result, "result must be a detonation result, 0..255");
    if (result) rule->result = config_setting_get_int(result);
    return 0;
}

static int read_effects(struct scene_reader *r, const config_setting_t *g, struct dis_settings *s)
{
    const config_setting_t *list = config_setting_get_member(g, "effects");
    if (!list) return 0;
    if (!config_setting_is_list(list)) return scene_group_fail(r, list, "dis.effects must be a list ( { ... }, ... )");
    int count = config_setting_length(list);
    if (count > DIS_EFFECTS_MAX)
        return scene_group_fail(r, list, "dis.effects has %d rules, at most %d", count, DIS_EFFECTS_MAX);
    for (int i = 0; i < count; i++) {
        int rc = read_rule(r, config_setting_get_elem(list, (unsigned)i), &s->effects.rules[i]);
        if (rc) return rc;
    }
    s->effects.count = count;
    return 0;
}

static int read_group(struct scene_reader *r, const config_setting_t *g, struct dis_settings *s)
{
    static const char *const keys[] = {"origin", "range", "exercise", "effects", "default", NULL};
    int rc = scene_group_check_keys(r, g, "dis", keys);
    if (!rc) rc = scene_group_read_origin(r, g, s->origin, &s->have_origin);
    if (!rc) rc = read_scalars(r, g, s);
    if (!rc) rc = read_effects(r, g, s);
    return rc;
}

int dis_config_read(const char *scene_path, struct dis_settings *s, bool *found, char *err, size_t n)
{
    *found = false;
    config_t cfg;
    int rc = scene_group_load(&cfg, scene_path, err, n);
    if (!rc) {
        const config_setting_t *g = config_setting_get_member(config_root_setting(&cfg), "dis");
        struct dis_settings read = *s;
        struct scene_reader r = {scene_path, err, n};
        *found = g != NULL;
        if (g) rc = read_group(&r, g, &read);
        if (!rc) *s = read;
    }
    config_destroy(&cfg);
    return rc;
}
