/* CPU reference (double) of the lit-smoke shading: texture fetches as the GPU filters them,
 * wrap-around Lambert, back-lighting, the view-dependent step count and the height-field ray
 * march toward the key light (the first; the others are lit from the particle's centre,
 * unshadowed). particle.frag's lit_scattered (LIGHTING_LIT; its part
 * shaders_es/particle.frag.parts/5-lighting.glsl) mirrors it line by line. */
#include <math.h>
#include <stdbool.h>
#include "lit_ref.h"

static int clamp_int(int v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : v; }

/* One level of the texture: its side and first texel. */
typedef struct level_view {
    int side;
    const uint8_t *texels;
} level_view;

static level_view level_of(const sbfx_smoke_texture *tex, int level)
{
    level_view v = {tex->size >> level > 0 ? tex->size >> level : 1,
                    tex->texels + sbfx_smoke_level_offset(tex->size, tex->layers, level)};
    return v;
}

static double texel(const level_view *v, int layer, int x, int y, int c)
{
    x = clamp_int(x, 0, v->side - 1);
    y = clamp_int(y, 0, v->side - 1);
    size_t i = (((size_t)layer * v->side + y) * v->side + x) * 4 + c;
    return v->texels[i] / 255.0;
}

static void bilinear(const level_view *v, int layer, double s, double t, double rgba[4])
{
    double x = s * v->side - 0.5, y = t * v->side - 0.5;
    if (!isfinite(x)) x = 0.0;
    if (!isfinite(y)) y = 0.0;
    x = fmax(-1.0, fmin(x, v->side)); /* beyond the edge every tap is clamped anyway */
    y = fmax(-1.0, fmin(y, v->side));
    double fx = floor(x), fy = floor(y), ax = x - fx, ay = y - fy;
    int x0 = (int)fx, y0 = (int)fy;
    for (int c = 0; c < 4; c++) {
        double bottom = texel(v, layer, x0, y0, c) * (1 - ax) + texel(v, layer, x0 + 1, y0, c) * ax;
        double top = texel(v, layer, x0, y0 + 1, c) * (1 - ax) + texel(v, layer, x0 + 1, y0 + 1, c) * ax;
        rgba[c] = bottom * (1 - ay) + top * ay;
    }
}

void sbfx_smoke_sample(const sbfx_smoke_texture *tex, int layer, double s, double t, double lod, double rgba[4])
{
    layer = clamp_int(layer, 0, tex->layers - 1);
    lod = isnan(lod) ? 0.0 : fmin(fmax(lod, 0.0), tex->levels - 1);
    int l0 = (int)floor(lod);
    double f = lod - l0;
    level_view v0 = level_of(tex, l0);
    bilinear(&v0, layer, s, t, rgba);
    if (f <= 0.0) return;
    double upper[4];
    level_view v1 = level_of(tex, l0 + 1);
    bilinear(&v1, layer, s, t, upper);
    for (int c = 0; c < 4; c++) rgba[c] = rgba[c] * (1 - f) + upper[c] * f;
}

double sbfx_lit_lod(int size, double radius, double depth, double pixel_slope)
{
    double texels = size * pixel_slope * depth / (2.0 * radius);
    return texels > 1.0 ? fmin(log2(texels), 30.0) : 0.0; /* NaN -> 0, inf -> the coarsest */
}

void sbfx_lit_maps_at(const sbfx_smoke_texture *tex, int variant, double s, double t, double lod,
                      sbfx_lit_maps *out)
{
    double a[4], b[4];
    sbfx_smoke_sample(tex, SBFX_SMOKE_LAYERS_PER_VARIANT * variant, s, t, lod, a);
    sbfx_smoke_sample(tex, SBFX_SMOKE_LAYERS_PER_VARIANT * variant + 1, s, t, lod, b);
    for (int k = 0; k < 3; k++) out->normal[k] = a[k] * 2 - 1; /* as filtered, not renormalised */
    out->height = a[3];
    out->brightness = b[0];
    out->translucency = b[1];
}

int sbfx_lit_variant(double detail_u, int variants)
{
    if (!(detail_u > 0.0)) return 0; /* NaN too */
    double v = floor(fmin(detail_u, 1.0) * variants);
    return v > variants - 1 ? variants - 1 : (int)v;
}

double sbfx_lit_wrap(double n_dot_l, double wrap)
{
    return fmax(n_dot_l * (1.0 / (1.0 + wrap)) + wrap / (1.0 + wrap), 0.0);
}

double sbfx_lit_backlight(double v_dot_l, double translucency_map, double translucency)
{
    return translucency * translucency_map * fmax(-v_dot_l, 0.0);
}

int sbfx_lit_steps(double n_dot_v, int n_min, int n_max)
{
    double x = fmin(fmax(n_dot_v, 0.0), 1.0); /* NaN -> 0 */
    return (int)floor(n_min + x * (n_max - n_min) + 0.5);
}

double sbfx_lit_shadow(const sbfx_smoke_texture *tex, int variant, double lod, const double st[2],
                       double height, const double to_light[3], double radius, double tau, int steps)
{
    if (steps <= 0) return 1.0;
    const double start[3] = {st[0], st[1], 0.5 * height};
    double dt = 1.0 / steps, sum = 0.0; /* one diameter: the longest chord of the sphere */
    for (int k = 0; k < steps; k++) {
        double t = (k + 0.5) * dt, rgba[4];
        double p[3] = {start[0] + t * to_light[0], start[1] + t * to_light[1], start[2] + t * to_light[2]};
        sbfx_smoke_sample(tex, SBFX_SMOKE_LAYERS_PER_VARIANT * variant, p[0], p[1], lod, rgba);
        sum += fmax(rgba[3] - 2.0 * fabs(p[2]), 0.0);
        if (tau * 2.0 * radius * sum * dt > 20.0) break; /* transmittance < 2e-9: the shader stops too */
    }
    return exp(-tau * 2.0 * radius * sum * dt);
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The key light at the front surface p: unit direction toward it (0 for a point light at p
 * itself) and its falloff 1/max(d^2, 1/4). */
static double key_light(const sbfx_lit_light *l, const double p[3], double dir[3])
{
    bool point = l->vector[3] > 0.5;
    double d[3];
    for (int k = 0; k < 3; k++) d[k] = point ? l->vector[k] - p[k] : -l->vector[k];
    double s = 1.0 / sqrt(fmax(dot3(d, d), 1e-24));
    for (int k = 0; k < 3; k++) dir[k] = d[k] * s;
    return point ? fmin(s * s, 4.0) : 1.0;
}

/* A light after the key light, seen from the particle's centre c: unit direction ((0,0,1), toward
 * the eye's side, for a point light at c) and falloff. */
static double fill_light(const sbfx_lit_light *l, const double c[3], double dir[3])
{
    bool point = l->vector[3] > 0.5;
    double d[3];
    for (int k = 0; k < 3; k++) d[k] = point ? l->vector[k] - c[k] : -l->vector[k];
    double d2 = dot3(d, d);
    for (int k = 0; k < 3; k++) dir[k] = d2 > 1e-12 ? d[k] / sqrt(d2) : (k == 2);
    return point ? 1.0 / fmax(d2, 0.25) : 1.0;
}

void sbfx_lit_radiance(const sbfx_lit_medium *m, const sbfx_smoke_texture *tex, int variant, double lod,
                       const double center[3], double radius, const double ray[3],
                       const sbfx_lit_light *lights, int light_count, const double ambient[3],
                       double rgb[3])
{
    double zc = -center[2], q[2] = {ray[0] * zc, ray[1] * zc};
    double st[2] = {(q[0] - center[0]) / (2 * radius) + 0.5, (q[1] - center[1]) / (2 * radius) + 0.5};
    sbfx_lit_maps maps;
    sbfx_lit_maps_at(tex, variant, st[0], st[1], lod, &maps);
    const double p[3] = {q[0], q[1], center[2] + radius * maps.height}; /* the front surface */
    double len = sqrt(dot3(center, center)), v[3]; /* V: the centre toward the eye */
    for (int k = 0; k < 3; k++) v[k] = -center[k] / len;
    int steps = sbfx_lit_steps(dot3(maps.normal, v), m->steps_min, m->steps_max);
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < light_count && i < SBFX_LIT_MAX_LIGHTS; i++) {
        double l[3];
        double falloff = i == 0 ? key_light(&lights[i], p, l) : fill_light(&lights[i], center, l);
        double diffuse = sbfx_lit_wrap(dot3(maps.normal, l), m->wrap);
        double back = sbfx_lit_backlight(dot3(v, l), maps.translucency, m->translucency);
        /* the key light (the first) is self-shadowed, the others light the relief unshadowed */
        double shadow = i == 0 ? sbfx_lit_shadow(tex, variant, lod, st, maps.height, l, radius, m->tau, steps) : 1.0;
        for (int k = 0; k < 3; k++) sum[k] += lights[i].color[k] * falloff * shadow * (diffuse + back);
    }
    for (int k = 0; k < 3; k++)
        rgb[k] = m->albedo_color[k] * maps.brightness * (ambient[k] + (1.0 - m->dampening) * sum[k]);
}

void sbfx_lit_fire_radiance(const sbfx_lit_medium *m, const sbfx_smoke_texture *tex, int variant, double lod,
                            const double center[3], double radius, const double ray[3], const double fire[3],
                            double rgb[3])
{
    double zc = -center[2];
    double st[2] = {(ray[0] * zc - center[0]) / (2 * radius) + 0.5, (ray[1] * zc - center[1]) / (2 * radius) + 0.5};
    sbfx_lit_maps maps;
    sbfx_lit_maps_at(tex, variant, st[0], st[1], lod, &maps);
    for (int k = 0; k < 3; k++) rgb[k] = m->albedo_color[k] * maps.brightness * (1.0 - m->dampening) * fire[k];
}
