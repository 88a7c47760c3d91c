/* The scene's cigi group and dis.origin (cigi_config.h). */
#include "net/cigi/cigi_config.h"

#include <stdio.h>
#include <string.h>

#include "net/common/scene_group.h"

struct reader {
    struct scene_reader at;
    cigi_effect_check_fn check;
    void *user;
};

static int read_rule(struct reader *r, const config_setting_t *g, const struct cigi_effect_map *so_far,
                     struct cigi_effect_rule *rule)
{
    static const char *const keys[] = {"entity_type", "effect", NULL};
    int rc = scene_group_check_keys(&r->at, g, "a cigi.effects entry", keys);
    if (rc) return rc;
    const config_setting_t *type = config_setting_get_member(g, "entity_type");
    if (!type || config_setting_type(type) != CONFIG_TYPE_INT || config_setting_get_int(type) < 0 ||
        config_setting_get_int(type) > 65535)
        return scene_group_fail(&r->at, type ? type : g, "a cigi.effects entry needs entity_type = N, the host's "
                                "entity type (0..65535)");
    rule->entity_type = (uint16_t)config_setting_get_int(type);
    for (int i = 0; i < so_far->count; i++)
        if (so_far->rules[i].entity_type == rule->entity_type)
            return scene_group_fail(&r->at, type, "cigi.effects names entity_type %u twice", rule->entity_type);
    const char *effect = NULL;
    if (!config_setting_lookup_string(g, "effect", &effect) || !effect[0] || strlen(effect) >= sizeof(rule->effect))
        return scene_group_fail(&r->at, g, "a cigi.effects entry needs effect = \"NAME\" (an effect of the scene)");
    char why[320] = "";
    if (r->check && r->check(effect, why, sizeof(why), r->user) != 0)
        return scene_group_fail(&r->at, config_setting_get_member(g, "effect"),
                                "cigi.effects: entity_type %u sets off '%s': %s", rule->entity_type, effect, why);
    snprintf(rule->effect, sizeof(rule->effect), "%s", effect);
    return 0;
}

static int read_group(struct reader *r, const config_setting_t *g, struct cigi_settings *s)
{
    static const char *const keys[] = {"effects", NULL};
    int rc = scene_group_check_keys(&r->at, g, "cigi", keys);
    const config_setting_t *list = rc ? NULL : config_setting_get_member(g, "effects");
    if (rc || !list) return rc;
    if (!config_setting_is_list(list))
        return scene_group_fail(&r->at, list, "cigi.effects must be a list ( { ... }, ... )");
    int count = config_setting_length(list);
    if (count > CIGI_EFFECTS_MAX)
        return scene_group_fail(&r->at, list, "cigi.effects has %d entries, at most %d", count, CIGI_EFFECTS_MAX);
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
    int rc = scene_group_load(&cfg, scene_path, err, n);
    if (!rc) {
        const config_setting_t *root = config_root_setting(&cfg);
        const config_setting_t *g = config_setting_get_member(root, "cigi");
        struct reader r = {{scene_path, err, n}, check, user};
        struct cigi_settings read = *s; /* s changes only when all of it is good */
        *found = g != NULL;
        rc = scene_group_read_origin(&r.at, config_setting_get_member(root, "dis"), read.origin, &read.have_origin);
        if (!rc && g) rc = read_group(&r, g, &read);
        if (!rc) *s = read;
    }
    config_destroy(&cfg);
    return rc;
}
