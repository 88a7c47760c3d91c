/* Scene files: libconfig syntax, validated key by key. Every error names the file and line;
 * nothing is kept from a file that fails. The format is documented in docs/scene-format.md. */
#include <libconfig.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "scene/scene.h"
#include "tables/tables.h"

typedef struct parser {
    const char *name;
    char *err;
    size_t err_size;
    sbfx_scene *scene;
} parser;

static int fail_at(parser *p, const config_setting_t *s, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static int fail_at(parser *p, const config_setting_t *s, const char *fmt, ...)
{
    char message[384];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof(message), fmt, ap);
    va_end(ap);
    int line = s ? (int)config_setting_source_line(s) : 0;
    /* a setting read from an @included file is named by that file */
    const char *file = s && config_setting_source_file(s) ? config_setting_source_file(s) : p->name;
    if (line > 0) snprintf(p->err, p->err_size, "%s:%d: %s", file, line, message);
    else snprintf(p->err, p->err_size, "%s: %s", p->name, message); /* the file as a whole */
    return -1;
}

/* ---- unknown keys, with the nearest valid one suggested ---- */
static int edit_distance(const char *a, const char *b)
{
    int la = (int)strlen(a), lb = (int)strlen(b);
    if (la > 63 || lb > 63) return 99;
    int row[64];
    for (int j = 0; j <= lb; j++) row[j] = j;
    for (int i = 1; i <= la; i++) {
        int diagonal = row[0];
        row[0] = i;
        for (int j = 1; j <= lb; j++) {
            int up = row[j];
            int cost = a[i - 1] == b[j - 1] ? 0 : 1;
            int best = diagonal + cost;
            if (row[j] + 1 < best) best = row[j] + 1;
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            row[j] = best;
            diagonal = up;
        }
    }
    return row[lb];
}

static int check_keys(parser *p, const config_setting_t *group, const char *what,
                      const char *const *valid)
{
    if (!config_setting_is_group(group)) return fail_at(p, group, "%s must be a group { ... }", what);
    for (int i = 0; i < config_setting_length(group); i++) {
        const config_setting_t *m = config_setting_get_elem(group, (unsigned)i);
        const char *key = config_setting_name(m);
        const char *nearest = NULL;
        int best = 1 << 20;
        bool known = false;
        for (const char *const *v = valid; *v; v++) {
            if (strcmp(*v, key) == 0) known = true;
            int d = edit_distance(key, *v);
            if (d < best) best = d, nearest = *v;
        }
        if (known) continue;
        if (nearest && best <= 3)
            return fail_at(p, m, "unknown key '%s' in %s (did you mean '%s'?)", key, what, nearest);
        return fail_at(p, m, "unknown key '%s' in %s", key, what);
    }
    return 0;
}

/* ---- typed getters: absent keys keep the default ---- */
static bool is_number(const config_setting_t *s)
{
    int t = config_setting_type(s);
    return t == CONFIG_TYPE_INT || t == CONFIG_TYPE_INT64 || t == CONFIG_TYPE_FLOAT;
}

static int get_float(parser *p, const config_setting_t *g, const char *key, double lo, double hi, float *out)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) return 0;
    if (!is_number(s)) return fail_at(p, s, "'%s' must be a number", key);
    double v = config_setting_get_float(s);
    if (config_setting_type(s) != CONFIG_TYPE_FLOAT) v = (double)config_setting_get_int64(s);
    if (!(v >= lo && v <= hi)) return fail_at(p, s, "'%s' = %g is out of range [%g, %g]", key, v, lo, hi);
    *out = (float)v;
    return 0;
}

static int get_int(parser *p, const config_setting_t *g, const char *key, long lo, long hi, int *out)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) return 0;
    int t = config_setting_type(s);
    if (t != CONFIG_TYPE_INT && t != CONFIG_TYPE_INT64) return fail_at(p, s, "'%s' must be an integer", key);
    long long v = config_setting_get_int64(s);
    if (v < lo || v > hi) return fail_at(p, s, "'%s' = %lld is out of range [%ld, %ld]", key, v, lo, hi);
    *out = (int)v;
    return 0;
}

static int get_bool(parser *p, const config_setting_t *g, const char *key, bool *out)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) return 0;
    if (config_setting_type(s) != CONFIG_TYPE_BOOL) return fail_at(p, s, "'%s' must be true or false", key);
    *out = config_setting_get_bool(s) != 0;
    return 0;
}

/* A fixed-length array of numbers, each in [lo, hi]. */
static int get_vector(parser *p, const config_setting_t *g, const char *key, int n, double lo, double hi,
                      float *out)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) return 0;
    if (!config_setting_is_array(s) || config_setting_length(s) != n)
        return fail_at(p, s, "'%s' must be an array of %d numbers [ ... ]", key, n);
    for (int i = 0; i < n; i++) {
        const config_setting_t *e = config_setting_get_elem(s, (unsigned)i);
        if (!is_number(e)) return fail_at(p, s, "'%s' must be an array of %d numbers", key, n);
        double v = config_setting_type(e) == CONFIG_TYPE_FLOAT ? config_setting_get_float(e)
                                                                : (double)config_setting_get_int64(e);
        if (!(v >= lo && v <= hi))
            return fail_at(p, s, "'%s'[%d] = %g is out of range [%g, %g]", key, i, v, lo, hi);
        out[i] = (float)v;
    }
    return 0;
}

/* [min, max] with min <= max */
static int get_range(parser *p, const config_setting_t *g, const char *key, double lo, double hi,
                     float *min, float *max)
{
    float v[2] = {*min, *max};
    if (get_vector(p, g, key, 2, lo, hi, v)) return -1;
    if (v[0] > v[1])
        return fail_at(p, config_setting_get_member(g, key), "'%s' = [%g, %g]: the first must not exceed the second",
                       key, (double)v[0], (double)v[1]);
    *min = v[0], *max = v[1];
    return 0;
}

/* [a, b] of integers in [lo, hi] with a <= b */
static int get_int_range(parser *p, const config_setting_t *g, const char *key, long lo, long hi, int *a,
                         int *b)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) return 0;
    if (!config_setting_is_array(s) || config_setting_length(s) != 2)
        return fail_at(p, s, "'%s' must be an array of 2 integers [ ... ]", key);
    long long v[2];
    for (int i = 0; i < 2; i++) {
        const config_setting_t *e = config_setting_get_elem(s, (unsigned)i);
        int t = config_setting_type(e);
        if (t != CONFIG_TYPE_INT && t != CONFIG_TYPE_INT64) return fail_at(p, s, "'%s' must be an array of 2 integers", key);
        v[i] = config_setting_get_int64(e);
        if (v[i] < lo || v[i] > hi)
            return fail_at(p, s, "'%s'[%d] = %lld is out of range [%ld, %ld]", key, i, v[i], lo, hi);
    }
    if (v[0] > v[1])
        return fail_at(p, s, "'%s' = [%lld, %lld]: the first must not exceed the second", key, v[0], v[1]);
    *a = (int)v[0], *b = (int)v[1];
    return 0;
}

/* A string that must be one of `names`; *out becomes its index + base. */
static int get_choice(parser *p, const config_setting_t *g, const char *key, const char *const *names,
                      int base, int *out)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) return 0;
    const char *v = config_setting_get_string(s);
    if (!v) return fail_at(p, s, "'%s' must be a string", key);
    char list[256] = "";
    for (int i = 0; names[i]; i++) {
        if (strcmp(v, names[i]) == 0) {
            *out = base + i;
            return 0;
        }
        snprintf(list + strlen(list), sizeof(list) - strlen(list), "%s%s", i ? ", " : "", names[i]);
    }
    return fail_at(p, s, "'%s' = \"%s\" is not one of: %s", key, v, list);
}

static int get_name(parser *p, const config_setting_t *g, const char *key, char *out, size_t size, bool required)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) return required ? fail_at(p, g, "missing '%s'", key) : 0;
    const char *v = config_setting_get_string(s);
    if (!v) return fail_at(p, s, "'%s' must be a string", key);
    if (!*v || strlen(v) >= size) return fail_at(p, s, "'%s' must be 1 to %zu characters", key, size - 1);
    snprintf(out, size, "%s", v);
    return 0;
}

static const char *const medium_names[] = {"dust", "smoke", "fire", "heat", NULL};

/* ---- render ---- */
/* budget_ms: a positive time (get_float would let 0 mean "none" silently) */
static int parse_budget(parser *p, const config_setting_t *g)
{
    const config_setting_t *s = config_setting_get_member(g, "budget_ms");
    float ms = 0;
    if (get_float(p, g, "budget_ms", -INFINITY, INFINITY, &ms)) return -1;
    if (s && !(ms > 0 && ms <= 1e4f))
        return fail_at(p, s, "'budget_ms' = %g: use a frame time in milliseconds above 0 and at most 10000", (double)ms);
    p->scene->render.frame_budget_ms = ms;
    return 0;
}

/* ladder = ["exact/4/nd", ...]: quality level names (sbfx_quality_parse), most accurate first */
static int parse_ladder(parser *p, const config_setting_t *g)
{
    const config_setting_t *s = config_setting_get_member(g, "ladder");
    if (!s) return 0;
    int n = config_setting_length(s);
    if (!config_setting_is_array(s) || n < 1 || n > SBFX_LADDER_MAX)
        return fail_at(p, s, "'ladder' must be an array of 1 to %d quality names [ \"exact/4/nd\", ... ]", SBFX_LADDER_MAX);
    sbfx_scene *scene = p->scene;
    for (int i = 0; i < n; i++) {
        const char *name = config_setting_get_string_elem(s, (unsigned)i);
        char why[256];
        sbfx_quality q;
        if (!name) return fail_at(p, s, "'ladder'[%d] must be a string", i);
        if (sbfx_quality_parse(name, &q, why, sizeof(why)) != SBFX_OK) return fail_at(p, s, "'ladder'[%d]: %s", i, why);
        snprintf(scene->ladder_names[i], sizeof(scene->ladder_names[i]), "%s", name);
        scene->ladder_ptrs[i] = scene->ladder_names[i];
    }
    scene->render.ladder = scene->ladder_ptrs;
    scene->render.ladder_count = n;
    return 0;
}

/* What the scene asks of its host (sbfx_scene_host): fire-lit ground, smoke shadows. */
static int parse_render_host(parser *p, const config_setting_t *g)
{
    sbfx_scene *scene = p->scene;
    bool terminate = false;
    if (get_bool(p, g, "host_lights", &scene->host_lights) || get_bool(p, g, "host_shadows", &scene->host_shadows) ||
        get_int(p, g, "shadow_map_size", 16, 16384, &scene->render.shadow_map_size) ||
        get_bool(p, g, "early_termination", &terminate))
        return -1;
    scene->early_termination = terminate;
    if (scene->host_shadows && !scene->render.shadow_map_size) scene->render.shadow_map_size = 256;
    return 0;
}

static int parse_render(parser *p, const config_setting_t *g)
{
    static const char *const keys[] = {"target_scale", "target_format", "upsample", "opacity",
                                       "seed", "max_particles", "sim_rate", "blackbody_max_kelvin",
                                       "light_rate", "blackbody", "phase", "detail_format", "tone_map",
                                       "exposure", "budget_ms", "ladder", "white_luminance", "host_lights",
                                       "host_shadows", "shadow_map_size", "early_termination", NULL};
    static const char *const tone_maps[] = {"none", "hue-preserving", "per-channel", "filmic", NULL};
    static const char *const rates[] = {"per-pixel", "per-particle", NULL};
    static const char *const evaluations[] = {"table", "analytic", NULL};
    static const char *const detail_formats[] = {"r16f", "r32f", NULL};
    static const char *const formats[] = {"auto", "rgba8", "rgba16f", "rgba32f", NULL};
    static const char *const upsamples[] = {"bilinear", "nearest-depth", "mixed", NULL};
    static const char *const opacities[] = {"planar", "soft", "spherical", "exact", NULL};
    sbfx_desc *d = &p->scene->render;
    int format = 0, upsample = 0, opacity = 0, seed = 0, rate_choice = 0, blackbody = 0, phase = 0;
    int detail_format = 0, tone_map = 0;
    float rate = 0, kelvin = 0;
    if (check_keys(p, g, "render", keys) || get_int(p, g, "target_scale", 1, 8, &d->target_divisor) ||
        get_choice(p, g, "target_format", formats, 0, &format) ||
        get_choice(p, g, "upsample", upsamples, SBFX_UPSAMPLE_BILINEAR, &upsample) ||
        get_choice(p, g, "opacity", opacities, SBFX_OPACITY_PLANAR, &opacity) ||
        get_int(p, g, "seed", 1, 2147483647L, &seed) ||
        get_int(p, g, "max_particles", 1, 1 << 20, &d->max_particles) ||
        get_float(p, g, "sim_rate", 10, 1000, &rate) ||
        get_float(p, g, "blackbody_max_kelvin", 1000, 100000, &kelvin) ||
        get_choice(p, g, "light_rate", rates, 0, &rate_choice) ||
        get_choice(p, g, "blackbody", evaluations, 0, &blackbody) || get_choice(p, g, "phase", evaluations, 1, &phase) ||
        get_choice(p, g, "detail_format", detail_formats, SBFX_DETAIL_R16F, &detail_format) ||
        get_choice(p, g, "tone_map", tone_maps, SBFX_TONE_MAP_NONE, &tone_map) ||
        get_float(p, g, "exposure", 0.01, 100, &d->exposure) ||
        get_float(p, g, "white_luminance", 1, 1e9, &d->white_luminance) || parse_budget(p, g) || parse_ladder(p, g) ||
        parse_render_host(p, g))
        return -1;
    d->tone_map = (sbfx_tone_map)tone_map;
    d->light_per_particle = rate_choice == 1;
    d->analytic_blackbody = blackbody == 1;
    d->table_phase = phase == 1;      /* analytic, the default, where the key names it or is left out */
    d->analytic_phase = phase == 2;
    d->detail_format = (sbfx_detail_format)detail_format;
    int scale = d->target_divisor;
    if (scale && scale != 1 && scale != 2 && scale != 4 && scale != 8)
        return fail_at(p, config_setting_get_member(g, "target_scale"), "'target_scale' = %d: use 1, 2, 4 or 8", scale);
    d->target_format = (sbfx_target_format)format;
    d->upsample = (sbfx_upsample)upsample;
    d->opacity = (sbfx_opacity_mode)opacity;
    d->seed = (uint32_t)seed;
    d->sim_step = rate > 0 ? 1.0f / rate : 0.0f;
    d->blackbody_max_kelvin = kelvin;
    return 0;
}

/* ---- lights ---- */
static int parse_orbit(parser *p, const config_setting_t *g, sbfx_orbit *o)
{
    static const char *const keys[] = {"center", "radius", "period", "phase", NULL};
    float phase_degrees = 0;
    *o = (sbfx_orbit){.on = true, .radius = 1.0f, .period = 8.0f};
    if (check_keys(p, g, "an orbit", keys) || get_vector(p, g, "center", 3, -1e6, 1e6, o->center) ||
        get_float(p, g, "radius", 0, 1e6, &o->radius) || get_float(p, g, "period", -1e6, 1e6, &o->period) ||
        get_float(p, g, "phase", -360, 360, &phase_degrees))
        return -1;
    if (fabsf(o->period) < 0.01f)
        return fail_at(p, config_setting_get_member(g, "period"),
                       "'period' = %g: use at least 0.01 s (negative: clockwise)", (double)o->period);
    o->phase = phase_degrees * (float)(M_PI / 180.0);
    return 0;
}

static int parse_lights(parser *p, const config_setting_t *list)
{
    static const char *const keys[] = {"type", "direction", "position", "color", "orbit", NULL};
    static const char *const types[] = {"directional", "point", NULL};
    if (!config_setting_is_list(list)) return fail_at(p, list, "'lights' must be a list ( {...}, ... )");
    int n = config_setting_length(list);
    if (n > SBFX_MAX_LIGHTS) return fail_at(p, list, "%d lights: at most %d", n, SBFX_MAX_LIGHTS);
    for (int i = 0; i < n; i++) {
        const config_setting_t *g = config_setting_get_elem(list, (unsigned)i);
        sbfx_light *l = &p->scene->lights[i];
        int type = 0;
        *l = (sbfx_light){.type = SBFX_LIGHT_DIRECTIONAL, .vector = {0, -1, 0}, .color = {1, 1, 1}};
        if (check_keys(p, g, "a light", keys) || get_choice(p, g, "type", types, 0, &type)) return -1;
        l->type = (sbfx_light_type)type;
        const char *vector_key = type == SBFX_LIGHT_POINT ? "position" : "direction";
        const config_setting_t *orbit = config_setting_get_member(g, "orbit");
        if (orbit && type != SBFX_LIGHT_POINT) return fail_at(p, orbit, "'orbit' needs a point light");
        if (orbit && parse_orbit(p, orbit, &l->orbit)) return -1;
        if (!orbit && !config_setting_get_member(g, vector_key))
            return fail_at(p, g, "a %s light needs '%s'", types[type], vector_key);
        if (get_vector(p, g, vector_key, 3, -1e6, 1e6, l->vector) ||
            get_vector(p, g, "color", 3, 0, 1e4, l->color))
            return -1;
        if (type == SBFX_LIGHT_DIRECTIONAL && !(fabsf(l->vector[0]) + fabsf(l->vector[1]) + fabsf(l->vector[2]) > 0))
            return fail_at(p, g, "'direction' must not be [0, 0, 0]");
    }
    p->scene->light_count = n;
    return 0;
}

/* ---- media ---- */
/* A clip path as written, or resolved against the folder of the scene's name when relative
 * (docs/detail-clips.md): "clips/smoke.mp4" in "scenes/a.cfg" is "scenes/clips/smoke.mp4". */
static int resolve_clip(parser *p, const config_setting_t *s, const char *clip, char *out, size_t size)
{
    const char *slash = strrchr(p->name, '/');
    int folder = clip[0] != '/' && slash ? (int)(slash - p->name) + 1 : 0;
    int len = snprintf(out, size, "%.*s%s", folder, p->name, clip);
    if (len < 0 || (size_t)len >= size) return fail_at(p, s, "detail clip path \"%s\" is too long", clip);
    return 0;
}

/* Every medium shares the one detail volume: at most one clip feeds it, and not beside a camera. */
static int check_one_feed(parser *p, const config_setting_t *s, const sbfx_medium_params *m)
{
    for (int i = 0; i < SBFX_MEDIUM_COUNT; i++) {
        const sbfx_medium_params *o = &p->scene->media[i];
        if (o == m || !p->scene->has_medium[i] || (!o->live_detail && !o->detail_clip[0])) continue;
        if ((m->live_detail && o->detail_clip[0]) || (m->detail_clip[0] && o->live_detail) ||
            (m->detail_clip[0] && o->detail_clip[0] && strcmp(m->detail_clip, o->detail_clip) != 0))
            return fail_at(p, s, "media name different detail sources (\"%s\" and \"%s\"); the module has one "
                           "detail volume: name the same clip or camera in every medium",
                           m->live_detail ? "v4l2" : m->detail_clip, o->live_detail ? "v4l2" : o->detail_clip);
    }
    return 0;
}

/* source: "procedural", "v4l2", or any other string: a video clip's path (docs/detail-clips.md). */
static int parse_detail_source(parser *p, const config_setting_t *g, sbfx_medium_params *m)
{
    const config_setting_t *s = config_setting_get_member(g, "source");
    if (!s) return 0;
    const char *v = config_setting_get_string(s);
    if (!v || !v[0]) return fail_at(p, s, "'source' must be \"procedural\", \"v4l2\" or a video file's path");
    m->live_detail = strcmp(v, "v4l2") == 0;
    m->detail_clip[0] = '\0';
    if (strcmp(v, "procedural") != 0 && !m->live_detail &&
        resolve_clip(p, s, v, m->detail_clip, sizeof(m->detail_clip)))
        return -1;
    return check_one_feed(p, s, m);
}

static int parse_detail(parser *p, const config_setting_t *g, sbfx_medium_params *m)
{
    static const char *const keys[] = {"source", "strength", "window", NULL};
    if (check_keys(p, g, "detail", keys) || parse_detail_source(p, g, m) ||
        get_float(p, g, "strength", 0, 1, &m->detail_strength) || get_float(p, g, "window", 0.01, 1, &m->detail_window))
        return -1;
    return 0;
}

static int parse_texture(parser *p, const config_setting_t *g, sbfx_medium_params *m)
{
    static const char *const keys[] = {"size", "variants", NULL};
    if (check_keys(p, g, "texture", keys) ||
        get_int(p, g, "size", SBFX_SMOKE_MIN_SIZE, SBFX_SMOKE_MAX_SIZE, &m->texture_size) ||
        get_int(p, g, "variants", 1, SBFX_SMOKE_MAX_VARIANTS, &m->texture_variants))
        return -1;
    if (m->texture_size & (m->texture_size - 1)) /* its mip chain halves down to 1 x 1 */
        return fail_at(p, config_setting_get_member(g, "size"), "'size' = %d: use a power of two", m->texture_size);
    return 0;
}

/* The lit-smoke keys; they are kept (and harmless) on a medium that stays "phase". */
static int parse_lighting(parser *p, const config_setting_t *g, sbfx_medium_params *m, const char *what)
{
    static const char *const models[] = {"phase", "lit", NULL};
    int model = m->lit ? 1 : 0;
    const config_setting_t *texture = config_setting_get_member(g, "texture");
    if (get_choice(p, g, "lighting", models, 0, &model) || get_float(p, g, "wrap", 0, 1, &m->wrap) ||
        get_float(p, g, "translucency", 0, 100, &m->translucency) ||
        get_float(p, g, "dampening", 0, 1, &m->dampening) ||
        get_int_range(p, g, "steps", 0, SBFX_LIT_MAX_STEPS, &m->steps_min, &m->steps_max) ||
        (texture && parse_texture(p, texture, m)))
        return -1;
    m->lit = model == 1;
    if (m->lit && !(m->albedo > 0))
        return fail_at(p, config_setting_get_member(g, "lighting"),
                       "%s: lighting = \"lit\" lights scattered light, and its albedo is 0", what);
    return 0;
}

/* Fire's light: `emissivity` (0..1, photometric: docs/look-fire.md) or the older `emission`, a
 * bare multiplier of the black body normalised to luminance 1 at blackbody_max_kelvin. */
static int parse_emission(parser *p, const config_setting_t *g, sbfx_medium_params *m, const char *what)
{
    const config_setting_t *emission = config_setting_get_member(g, "emission");
    if (emission && config_setting_get_member(g, "emissivity"))
        return fail_at(p, emission, "%s: give 'emissivity' (photometric, 0..1) or 'emission' (a bare scale), "
                       "not both", what);
    if (emission) m->emissivity = 0.0f;
    return get_float(p, g, "emissivity", 0, 1, &m->emissivity);
}

static int parse_medium(parser *p, const config_setting_t *g, sbfx_medium which)
{
    static const char *const keys[] = {"albedo", "density", "phase_g", "color", "temperature",
                                       "cooling", "soot", "emission", "emissivity", "detail", "lighting", "wrap",
                                       "translucency", "dampening", "steps", "texture", "strength", NULL};
    sbfx_medium_params *m = &p->scene->media[which];
    float temperature[2] = {m->t0, m->t1};
    char what[32];
    snprintf(what, sizeof(what), "media.%s", medium_names[which]);
    if (check_keys(p, g, what, keys) || get_float(p, g, "albedo", 0, 1, &m->albedo) ||
        get_float(p, g, "density", 0, 1e6, &m->tau) || get_float(p, g, "phase_g", -0.99, 0.99, &m->phase_g) ||
        get_vector(p, g, "color", 3, 0, 100, m->color) ||
        get_vector(p, g, "temperature", 2, 0, 1e5, temperature) ||
        get_float(p, g, "cooling", 0, 1, &m->cooling) || get_float(p, g, "soot", 0, 64, &m->soot) ||
        get_float(p, g, "emission", 0, 1e4, &m->emission_scale) ||
        get_float(p, g, "strength", 0, 0.2, &m->heat_strength) || parse_emission(p, g, m, what))
        return -1;
    m->t0 = temperature[0], m->t1 = temperature[1];
    if (parse_lighting(p, g, m, what)) return -1;
    const config_setting_t *detail = config_setting_get_member(g, "detail");
    if (detail && parse_detail(p, detail, m)) return -1;
    p->scene->has_medium[which] = true;
    return 0;
}

static int parse_media(parser *p, const config_setting_t *g)
{
    if (check_keys(p, g, "media", medium_names)) return -1;
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) {
        const config_setting_t *s = config_setting_get_member(g, medium_names[m]);
        if (s && parse_medium(p, s, (sbfx_medium)m)) return -1;
    }
    return 0;
}

/* ---- effects ---- */
static int parse_emitter(parser *p, const config_setting_t *g, const char *effect, sbfx_emitter *e)
{
    static const char *const keys[] = {"type", "medium", "count", "delay", "spawn_shape", "spawn_radius",
                                       "speed", "upward", "lifetime", "radius", "radius_jitter", "drag",
                                       "buoyancy", "intensity", "fade_in", NULL};
    static const char *const shapes[] = {"sphere", NULL};
    int medium = -1, shape = 0;
    *e = (sbfx_emitter){.count = 1, .speed_min = 1, .speed_max = 1, .life_min = 1, .life_max = 1,
                        .radius_start = 0.5f, .radius_end = 0.5f, .intensity_start = 1, .intensity_end = 1};
    if (check_keys(p, g, "an emitter step", keys)) return -1;
    if (!config_setting_get_member(g, "medium")) return fail_at(p, g, "emitter step of effect '%s' needs 'medium'", effect);
    if (get_choice(p, g, "medium", medium_names, 0, &medium) || get_int(p, g, "count", 1, SBFX_MAX_EMITTER_COUNT, &e->count) ||
        get_float(p, g, "delay", 0, 3600, &e->delay) || get_choice(p, g, "spawn_shape", shapes, 0, &shape) ||
        get_float(p, g, "spawn_radius", 0, 1e4, &e->spawn_radius) ||
        get_range(p, g, "speed", 0, 1e4, &e->speed_min, &e->speed_max) ||
        get_float(p, g, "upward", 0, 1, &e->upward) ||
        get_range(p, g, "lifetime", 0.001, 3600, &e->life_min, &e->life_max) ||
        get_vector(p, g, "radius", 2, 1e-6, 1e4, &e->radius_start) ||
        get_float(p, g, "radius_jitter", 0, 0.99, &e->radius_jitter) || get_float(p, g, "drag", 0, 1e3, &e->drag) ||
        get_float(p, g, "buoyancy", -1e3, 1e3, &e->buoyancy) ||
        get_vector(p, g, "intensity", 2, 0, 100, &e->intensity_start) ||
        get_float(p, g, "fade_in", 0, 1, &e->fade_in))
        return -1;
    if (!p->scene->has_medium[medium])
        return fail_at(p, config_setting_get_member(g, "medium"),
                       "effect '%s' uses medium '%s', which is not defined in media", effect, medium_names[medium]);
    e->medium = (sbfx_medium)medium;
    return 0;
}

static int parse_flash(parser *p, const config_setting_t *g, sbfx_flash *f)
{
    static const char *const keys[] = {"type", "delay", "duration", "color", "offset", NULL};
    *f = (sbfx_flash){.duration = 0.3f, .color = {4, 3, 2}};
    return check_keys(p, g, "a light_flash step", keys) || get_float(p, g, "delay", 0, 3600, &f->delay) ||
                   get_float(p, g, "duration", 0.001, 3600, &f->duration) ||
                   get_vector(p, g, "color", 3, 0, 1e4, f->color) || get_vector(p, g, "offset", 3, -1e4, 1e4, f->offset)
               ? -1 : 0;
}

static int parse_step(parser *p, const config_setting_t *g, sbfx_effect *e)
{
    static const char *const types[] = {"emitter", "light_flash", NULL};
    int type = 0;
    if (!config_setting_is_group(g)) return fail_at(p, g, "a step must be a group { type = ...; ... }");
    if (!config_setting_get_member(g, "type")) return fail_at(p, g, "a step of effect '%s' needs 'type'", e->name);
    if (get_choice(p, g, "type", types, 0, &type)) return -1;
    if (type == 0) {
        if (e->emitter_count == SBFX_MAX_EMITTERS) return fail_at(p, g, "more than %d emitter steps", SBFX_MAX_EMITTERS);
        return parse_emitter(p, g, e->name, &e->emitters[e->emitter_count++]);
    }
    if (e->flash_count == SBFX_MAX_FLASHES) return fail_at(p, g, "more than %d light_flash steps", SBFX_MAX_FLASHES);
    return parse_flash(p, g, &e->flashes[e->flash_count++]);
}

static int parse_effects(parser *p, const config_setting_t *g)
{
    static const char *const keys[] = {"steps", NULL};
    if (!config_setting_is_group(g)) return fail_at(p, g, "'effects' must be a group { name = { steps = (...); }; }");
    int n = config_setting_length(g);
    if (n > SBFX_MAX_EFFECTS) return fail_at(p, g, "%d effects: at most %d", n, SBFX_MAX_EFFECTS);
    for (int i = 0; i < n; i++) {
        const config_setting_t *eg = config_setting_get_elem(g, (unsigned)i);
        sbfx_effect *e = &p->scene->effects[i];
        memset(e, 0, sizeof(*e));
        if (strlen(config_setting_name(eg)) >= sizeof(e->name)) return fail_at(p, eg, "effect name too long");
        snprintf(e->name, sizeof(e->name), "%s", config_setting_name(eg));
        if (check_keys(p, eg, "an effect", keys)) return -1;
        const config_setting_t *steps = config_setting_get_member(eg, "steps");
        if (!steps || !config_setting_is_list(steps) || config_setting_length(steps) == 0)
            return fail_at(p, eg, "effect '%s' needs 'steps', a non-empty list ( {...}, ... )", e->name);
        for (int s = 0; s < config_setting_length(steps); s++)
            if (parse_step(p, config_setting_get_elem(steps, (unsigned)s), e)) return -1;
        if (e->emitter_count == 0 && e->flash_count == 0) return fail_at(p, eg, "effect '%s' has no step", e->name);
    }
    p->scene->effect_count = n;
    return 0;
}

/* ---- triggers ---- */
static int effect_index(parser *p, const config_setting_t *g, const char *name)
{
    for (int i = 0; i < p->scene->effect_count; i++)
        if (strcmp(p->scene->effects[i].name, name) == 0) return i;
    return fail_at(p, g, "trigger names effect '%s', which is not defined in effects", name), -1;
}

static int parse_timeline(parser *p, const config_setting_t *list)
{
    static const char *const keys[] = {"effect", "time", "position", NULL};
    if (!config_setting_is_list(list)) return fail_at(p, list, "'timeline' must be a list ( {...}, ... )");
    int n = config_setting_length(list);
    if (n > SBFX_MAX_TIMELINE) return fail_at(p, list, "%d timeline entries: at most %d", n, SBFX_MAX_TIMELINE);
    for (int i = 0; i < n; i++) {
        const config_setting_t *g = config_setting_get_elem(list, (unsigned)i);
        sbfx_timeline_entry *t = &p->scene->timeline[i];
        char effect[SBFX_NAME_MAX];
        float time = 0;
        memset(t, 0, sizeof(*t));
        if (check_keys(p, g, "a timeline entry", keys) || get_name(p, g, "effect", effect, sizeof(effect), true) ||
            get_float(p, g, "time", 0, 1e6, &time) || get_vector(p, g, "position", 3, -1e6, 1e6, t->position))
            return -1;
        if ((t->effect = effect_index(p, g, effect)) < 0) return -1;
        t->time = time;
    }
    p->scene->timeline_count = n;
    return 0;
}

static int parse_gpio(parser *p, const config_setting_t *list)
{
    static const char *const keys[] = {"chip", "line", "edge", "debounce_ms", "effect", "position", NULL};
    static const char *const edges[] = {"rising", "falling", "both", NULL};
    if (!config_setting_is_list(list)) return fail_at(p, list, "'gpio' must be a list ( {...}, ... )");
    int n = config_setting_length(list);
    if (n > SBFX_MAX_GPIO) return fail_at(p, list, "%d gpio triggers: at most %d", n, SBFX_MAX_GPIO);
    for (int i = 0; i < n; i++) {
        const config_setting_t *g = config_setting_get_elem(list, (unsigned)i);
        sbfx_gpio_trigger *t = &p->scene->gpio[i];
        int edge = SBFX_EDGE_RISING;
        *t = (sbfx_gpio_trigger){.edge = SBFX_EDGE_RISING, .debounce_ms = 30};
        if (check_keys(p, g, "a gpio trigger", keys) || get_name(p, g, "chip", t->chip, sizeof(t->chip), true) ||
            get_int(p, g, "line", 0, 65535, &t->line) || get_choice(p, g, "edge", edges, 1, &edge) ||
            get_int(p, g, "debounce_ms", 0, 10000, &t->debounce_ms) ||
            get_name(p, g, "effect", t->effect, sizeof(t->effect), true) ||
            get_vector(p, g, "position", 3, -1e6, 1e6, t->position))
            return -1;
        if (!config_setting_get_member(g, "line")) return fail_at(p, g, "a gpio trigger needs 'line'");
        if (effect_index(p, g, t->effect) < 0) return -1;
        t->edge = (sbfx_edge)edge;
    }
    p->scene->gpio_count = n;
    return 0;
}

static int parse_triggers(parser *p, const config_setting_t *g)
{
    static const char *const keys[] = {"timeline", "gpio", NULL};
    const config_setting_t *timeline = config_setting_get_member(g, "timeline");
    const config_setting_t *gpio = config_setting_get_member(g, "gpio");
    if (check_keys(p, g, "triggers", keys) || (timeline && parse_timeline(p, timeline)) ||
        (gpio && parse_gpio(p, gpio)))
        return -1;
    return 0;
}

/* ---- post effects ---- */
static int parse_motion_blur(parser *p, const config_setting_t *g, sbfx_post_params *post)
{
    static const char *const keys[] = {"mode", "persistence", "tile", "samples", "shutter", NULL};
    static const char *const modes[] = {"history", "velocity", NULL};
    int mode = SBFX_BLUR_HISTORY;
    if (check_keys(p, g, "post.motion_blur", keys) || get_choice(p, g, "mode", modes, SBFX_BLUR_HISTORY, &mode) ||
        get_float(p, g, "persistence", 0.001, 60, &post->persistence) || get_int(p, g, "tile", 2, 32, &post->tile) ||
        get_int(p, g, "samples", 3, 63, &post->samples) || get_float(p, g, "shutter", 0, 1, &post->shutter))
        return -1;
    post->blur = (sbfx_blur_mode)mode;
    return 0;
}

static int parse_dof(parser *p, const config_setting_t *g, sbfx_post_params *post)
{
    static const char *const keys[] = {"near", "far", "max_radius", "scale", NULL};
    if (check_keys(p, g, "post.depth_of_field", keys) ||
        get_range(p, g, "near", 0, 1e6, &post->dof_near[0], &post->dof_near[1]) ||
        get_range(p, g, "far", 0, 1e6, &post->dof_far[0], &post->dof_far[1]) ||
        get_float(p, g, "max_radius", 0.5, 32, &post->dof_max_radius) || get_int(p, g, "scale", 1, 4, &post->dof_scale))
        return -1;
    if (post->dof_near[1] > post->dof_far[0])
        return fail_at(p, g, "depth_of_field: the focus range near[1] .. far[0] is empty (%g > %g)",
                       (double)post->dof_near[1], (double)post->dof_far[0]);
    post->dof = true;
    return 0;
}

static int parse_post(parser *p, const config_setting_t *g)
{
    static const char *const keys[] = {"motion_blur", "depth_of_field", NULL};
    const config_setting_t *blur = config_setting_get_member(g, "motion_blur");
    const config_setting_t *dof = config_setting_get_member(g, "depth_of_field");
    if (check_keys(p, g, "post", keys) || (blur && parse_motion_blur(p, blur, &p->scene->post)) ||
        (dof && parse_dof(p, dof, &p->scene->post)))
        return -1;
    return 0;
}

/* ---- camera (a viewer's; the module does not use it) ---- */

/* The default orbit: 8.5 m out, 2.6 m up, around (0, 1.5, 0), starting 0.35 rad toward +x and
 * moving 0.06 rad per second (in degrees below), 50 degrees of vertical field of view. */
static const sbfx_scene_camera default_camera = {
    .target = {0.0f, 1.5f, 0.0f}, .distance = 8.5f, .height = 2.6f, .azimuth = 20.0535228f, .orbit = 3.43774677f,
    .fov = 50.0f};

static int parse_camera(parser *p, const config_setting_t *g)
{
    static const char *const keys[] = {"target", "distance", "height", "azimuth", "orbit", "fov", NULL};
    sbfx_scene_camera *c = &p->scene->camera;
    if (check_keys(p, g, "camera", keys) || get_vector(p, g, "target", 3, -1e6, 1e6, c->target) ||
        get_float(p, g, "distance", 0.01, 1e5, &c->distance) || get_float(p, g, "height", -1e5, 1e5, &c->height) ||
        get_float(p, g, "azimuth", -360, 360, &c->azimuth) || get_float(p, g, "orbit", -360, 360, &c->orbit) ||
        get_float(p, g, "fov", 1, 170, &c->fov))
        return -1;
    p->scene->has_camera = true;
    return 0;
}

bool sbfx_scene_camera_get(const sbfx_scene *scene, sbfx_scene_camera *out)
{
    if (!out) return false;
    *out = scene && scene->has_camera ? scene->camera : default_camera;
    return scene && scene->has_camera;
}

static int parse_root(parser *p, const config_setting_t *root)
{
    /* dis, cigi: the player's network inputs (docs/triggers.md, docs/simulators.md), read by the
     * player, not the module */
    static const char *const keys[] = {"render", "lights", "ambient", "media", "effects", "triggers", "post",
                                       "camera", "sky", "dis", "cigi", NULL};
    if (check_keys(p, root, "the scene", keys)) return -1;
    const config_setting_t *s;
    if ((s = config_setting_get_member(root, "render")) && parse_render(p, s)) return -1;
    if ((s = config_setting_get_member(root, "lights")) && parse_lights(p, s)) return -1;
    if (get_vector(p, root, "ambient", 3, 0, 1e4, p->scene->ambient)) return -1;
    if (get_vector(p, root, "sky", 3, 0, 1e4, p->scene->sky)) return -1;
    p->scene->has_sky = config_setting_get_member(root, "sky") != NULL;
    if (!(s = config_setting_get_member(root, "media"))) return fail_at(p, root, "the scene has no 'media'");
    if (parse_media(p, s)) return -1;
    if (!(s = config_setting_get_member(root, "effects"))) return fail_at(p, root, "the scene has no 'effects'");
    if (parse_effects(p, s)) return -1;
    if ((s = config_setting_get_member(root, "triggers")) && parse_triggers(p, s)) return -1;
    if ((s = config_setting_get_member(root, "post")) && parse_post(p, s)) return -1;
    if ((s = config_setting_get_member(root, "camera")) && parse_camera(p, s)) return -1;
    return 0;
}

/* Defaults for what a file leaves out: the seed's media, the default sun. */
static void scene_defaults(sbfx_scene *scene, const char *name)
{
    memset(scene, 0, sizeof(*scene));
    snprintf(scene->name, sizeof(scene->name), "%s", name);
    sbfx_default_media(scene->media);
    sbfx_default_post(&scene->post);
    scene->camera = default_camera;
    scene->light_count = 1;
    scene->lights[0] = (sbfx_light){.type = SBFX_LIGHT_DIRECTIONAL, .vector = {-0.45f, -0.8f, -0.4f},
                                    .color = {1.6f, 1.5f, 1.35f}};
    scene->ambient[0] = 0.28f, scene->ambient[1] = 0.32f, scene->ambient[2] = 0.4f;
}

void sbfx_scene_builtin(sbfx_scene *scene)
{
    scene_defaults(scene, "built-in explosion");
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) scene->has_medium[m] = true;
    /* the seed's explosion carries its soot as smoke particles: its fire has none of its own */
    scene->media[SBFX_FIRE].soot = 0.0f;
    sbfx_builtin_explosion(&scene->effects[0]);
    scene->effect_count = 1;
    scene->timeline_count = 1; /* explosion at t = 0 at the origin */
}

static sbfx_result parse_config(config_t *cfg, int read_ok, const char *name, sbfx_scene **out, char *err,
                                size_t err_size)
{
    if (!read_ok) {
        if (config_error_type(cfg) == CONFIG_ERR_FILE_IO)
            snprintf(err, err_size, "%s: cannot read the file", name);
        else
            snprintf(err, err_size, "%s:%d: syntax error: %s", config_error_file(cfg) ? config_error_file(cfg) : name,
                     config_error_line(cfg), config_error_text(cfg));
        return SBFX_ERR_INVALID_ARGUMENT;
    }
    sbfx_scene *scene = calloc(1, sizeof(*scene));
    if (!scene) {
        snprintf(err, err_size, "%s: out of memory", name);
        return SBFX_ERR_OUT_OF_MEMORY;
    }
    scene_defaults(scene, name);
    parser p = {name, err, err_size, scene};
    if (parse_root(&p, config_root_setting(cfg)) != 0) {
        free(scene);
        return SBFX_ERR_INVALID_ARGUMENT;
    }
    *out = scene;
    return SBFX_OK;
}

static void note_file(sbfx_scene *scene, const char *file)
{
    if (!file) return;
    for (int i = 0; i < scene->file_count; i++)
        if (strcmp(scene->files[i], file) == 0) return;
    if (scene->file_count < SBFX_SCENE_FILES && strlen(file) < sizeof(scene->files[0]))
        strcpy(scene->files[scene->file_count++], file);
}

/* libconfig 1.5 has no include hook, but every setting knows the file it was read from: the
 * files a scene @includes are those its settings come from. */
static void note_files(sbfx_scene *scene, const config_setting_t *s)
{
    note_file(scene, config_setting_source_file(s));
    if (config_setting_is_aggregate(s))
        for (int i = 0; i < config_setting_length(s); i++)
            note_files(scene, config_setting_get_elem(s, (unsigned)i));
}

sbfx_result sbfx_scene_load(const char *path, sbfx_scene **out, char *err, size_t err_size)
{
    if (!out || !path || !err || !err_size) return SBFX_ERR_INVALID_ARGUMENT;
    *out = NULL;
    config_t cfg;
    config_init(&cfg);
    sbfx_result r = parse_config(&cfg, config_read_file(&cfg, path), path, out, err, err_size);
    if (r == SBFX_OK) {
        note_file(*out, path);
        note_files(*out, config_root_setting(&cfg));
    }
    config_destroy(&cfg);
    return r;
}

const char *sbfx_scene_file(const sbfx_scene *scene, int index)
{
    return scene && index >= 0 && index < scene->file_count ? scene->files[index] : NULL;
}

sbfx_result sbfx_scene_parse(const char *text, const char *name, sbfx_scene **out, char *err, size_t err_size)
{
    if (!out || !text || !err || !err_size) return SBFX_ERR_INVALID_ARGUMENT;
    *out = NULL;
    config_t cfg;
    config_init(&cfg);
    /* @include would read other files: not from text given in memory (fuzzing, tests). */
    config_set_include_dir(&cfg, "/nonexistent");
    sbfx_result r = parse_config(&cfg, config_read_string(&cfg, text), name ? name : "<scene>", out, err, err_size);
    config_destroy(&cfg);
    return r;
}

void sbfx_scene_free(sbfx_scene *scene) { free(scene); }

bool sbfx_scene_timeline_get(const sbfx_scene *scene, int index, sbfx_timeline_trigger *out)
{
    if (!out || index < 0) return false;
    if (!scene) { /* sbfx_scene_builtin's: one explosion at 0 at the origin */
        if (index > 0) return false;
        *out = (sbfx_timeline_trigger){.effect = "explosion"};
        return true;
    }
    if (index >= scene->timeline_count) return false;
    const sbfx_timeline_entry *t = &scene->timeline[index];
    *out = (sbfx_timeline_trigger){.effect = scene->effects[t->effect].name, .time = t->time};
    for (int k = 0; k < 3; k++) out->position[k] = t->position[k];
    return true;
}

int sbfx_scene_gpio_triggers(const sbfx_scene *scene, const sbfx_gpio_trigger **out)
{
    if (!scene || !out) return 0;
    *out = scene->gpio;
    return scene->gpio_count;
}
