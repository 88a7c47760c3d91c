/* What the protocols' scene groups read alike (scene_group.h). */
#include "net/common/scene_group.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int scene_group_load(config_t *cfg, const char *path, char *err, size_t n)
{
    config_init(cfg);
    if (config_read_file(cfg, path) == CONFIG_TRUE) return 0;
    snprintf(err, n, "%s:%d: %s", config_error_file(cfg) ? config_error_file(cfg) : path, config_error_line(cfg),
             config_error_text(cfg));
    return config_error_type(cfg) == CONFIG_ERR_FILE_IO ? -ENOENT : -EINVAL;
}

int scene_group_fail(struct scene_reader *r, const config_setting_t *s, const char *fmt, ...)
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

int scene_group_check_keys(struct scene_reader *r, const config_setting_t *g, const char *where,
                           const char *const *keys)
{
    if (!config_setting_is_group(g)) return scene_group_fail(r, g, "%s must be a group { ... }", where);
    for (int i = 0; i < config_setting_length(g); i++) {
        const config_setting_t *m = config_setting_get_elem(g, (unsigned)i);
        bool known = false;
        for (const char *const *k = keys; *k && !known; k++) known = strcmp(*k, config_setting_name(m)) == 0;
        if (!known) return scene_group_fail(r, m, "unknown key '%s' in %s", config_setting_name(m), where);
    }
    return 0;
}

bool scene_group_number(const config_setting_t *s, double *v)
{
    int type = config_setting_type(s);
    if (type == CONFIG_TYPE_FLOAT) *v = config_setting_get_float(s);
    else if (type == CONFIG_TYPE_INT || type == CONFIG_TYPE_INT64) *v = (double)config_setting_get_int64(s);
    else return false;
    return isfinite(*v);
}

int scene_group_read_origin(struct scene_reader *r, const config_setting_t *dis, double origin[3],
                            bool *have_origin)
{
    static const double limit[3] = {90.0, 180.0, 1e6};
    const config_setting_t *o = dis && config_setting_is_group(dis) ? config_setting_get_member(dis, "origin") : NULL;
    if (!o) return 0;
    if (!config_setting_is_array(o) || config_setting_length(o) != 3)
        return scene_group_fail(r, o, "dis.origin must be [latitude, longitude, height] (degrees, degrees, metres)");
    for (int k = 0; k < 3; k++) {
        double v = 0;
        if (!scene_group_number(config_setting_get_elem(o, (unsigned)k), &v) || v < -limit[k] || v > limit[k])
            return scene_group_fail(r, o, "dis.origin[%d] must be a number in -%g..%g", k, limit[k], limit[k]);
        origin[k] = v;
    }
    *have_origin = true;
    return 0;
}
