/* Fire as a light source: particle intensities from the black body, gathered into a few point
 * lights (fire_light.h). Pure C in double: the module and the CPU reference share it. */
#include <math.h>
#include <stdint.h>
#include <string.h>
#include "base/float16.h"
#include "sim/fire_light.h"
#include "tables/tables.h"

/* particle.frag's constants (EROSION_*) */
#define EROSION_THRESHOLD 0.30
#define EROSION_AGE 0.25
#define EROSION_SHARPNESS 1.8
#define EROSION_GAIN 2.2
#define RINGS 8 /* midpoint rule over rho: 0.5 % of the exact integral for the defaults */
#define BINS SBFX_FIRE_DETAIL_BINS
#define SHADE_REACH 4.0 /* m */

static double clamp01(double x) { return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x; }
static double mix(double a, double b, double t) { return a + (b - a) * t; }

/* Optical depth of the exact model's chord at rho (units of the radius): the integral of
 * 1 - |x - c| / r along it is r (w - rho^2 asinh(w / rho)), w = sqrt(1 - rho^2). */
static double chord_depth(double rho)
{
    double w = sqrt((1.0 - rho) * (1.0 + rho));
    return rho > 0.0 ? w - rho * rho * asinh(w / rho) : w;
}

static double texel(const float *v, int size, int frames, int x, int y, int t)
{
    x &= size - 1, y &= size - 1, t &= frames - 1; /* powers of two, REPEAT */
    return v[((size_t)t * size + y) * size + x];
}

static double trilinear(const float *v, int size, int frames, const double p[3])
{
    int x = (int)p[0], y = (int)p[1], t = (int)p[2];
    double fx = p[0] - x, fy = p[1] - y, ft = p[2] - t, sum = 0.0;
    for (int c = 0; c < 8; c++) {
        double w = (c & 1 ? fx : 1.0 - fx) * (c & 2 ? fy : 1.0 - fy) * (c & 4 ? ft : 1.0 - ft);
        sum += w * texel(v, size, frames, x + (c & 1), y + (c >> 1 & 1), t + (c >> 2 & 1));
    }
    return sum;
}

static double next_uniform(uint64_t *state)
{
    *state = *state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*state >> 11) * 0x1p-53;
}

static void count_value(double value, unsigned *histogram, unsigned *n)
{
    if (!(value >= 0.0 && value <= 1.0)) return;
    int b = (int)(value * BINS);
    histogram[b < BINS ? b : BINS - 1]++;
    ++*n;
}

/* The quantiles (j + 1/2) / LEVELS of a histogram of n values, linear within a bin. */
static void quantiles(const unsigned histogram[BINS], unsigned n, double out[SBFX_FIRE_DETAIL_LEVELS])
{
    unsigned seen = 0;
    int b = 0;
    for (int j = 0; j < SBFX_FIRE_DETAIL_LEVELS; j++) {
        double want = (j + 0.5) / SBFX_FIRE_DETAIL_LEVELS * n;
        while (b < BINS - 1 && seen + histogram[b] < want) seen += histogram[b++];
        double within = histogram[b] ? (want - seen) / histogram[b] : 0.5;
        out[j] = n ? (b + within) / BINS : 0.5;
    }
}

void sbfx_fire_detail_levels(const float *volume, int size, int frames, double out[SBFX_FIRE_DETAIL_LEVELS])
{
    unsigned histogram[BINS] = {0};
    unsigned n = 0;
    uint64_t state = 0x9e3779b97f4a7c15ull;
    for (int i = 0; i < 65536 && volume && size > 0 && frames > 0; i++) {
        double p[3];
        for (int k = 0; k < 3; k++) p[k] = next_uniform(&state) * (k < 2 ? size : frames);
        count_value(trilinear(volume, size, frames, p), histogram, &n);
    }
    quantiles(histogram, n, out);
}

static double half_texel(const uint16_t *slice, int size, int x, int y)
{
    sbfx_float16 h;
    memcpy(&h, &slice[(size_t)(y & (size - 1)) * size + (x & (size - 1))], sizeof(h));
    return (double)h;
}

void sbfx_fire_slice_histogram(const uint16_t *half_texels, int size, uint16_t histogram[SBFX_FIRE_DETAIL_BINS])
{
    unsigned counts[BINS] = {0}, n = 0;
    uint64_t state = 0x9e3779b97f4a7c15ull;
    for (int i = 0; i < SBFX_FIRE_SLICE_SAMPLES && half_texels && size > 0; i++) {
        double px = next_uniform(&state) * size, py = next_uniform(&state) * size;
        int x = (int)px, y = (int)py;
        double fx = px - x, fy = py - y;
        double value = (1.0 - fy) * ((1.0 - fx) * half_texel(half_texels, size, x, y) +
                                     fx * half_texel(half_texels, size, x + 1, y)) +
                       fy * ((1.0 - fx) * half_texel(half_texels, size, x, y + 1) +
                             fx * half_texel(half_texels, size, x + 1, y + 1));
        count_value(value, counts, &n);
    }
    for (int b = 0; b < BINS; b++) histogram[b] = (uint16_t)counts[b];
}

void sbfx_fire_detail_levels_of_slices(const uint16_t *histograms, int slices, double out[SBFX_FIRE_DETAIL_LEVELS])
{
    unsigned total[BINS] = {0}, n = 0;
    for (int s = 0; s < slices; s++)
        for (int b = 0; b < BINS; b++) {
            unsigned count = histograms[(size_t)s * BINS + b];
            total[b] += count, n += count;
        }
    quantiles(total, n, out);
}

double sbfx_fire_coordinate(double detail, double rho, double intensity, double strength)
{
    double fresh = clamp01(intensity);
    double spread = SBFX_FIRE_DETAIL * (1.0 + SBFX_FIRE_DETAIL_AGE * (1.0 - fresh));
    return mix(0.5, clamp01(0.5 + spread * (detail - 0.5) + SBFX_FIRE_CORE * fresh * (0.5 - rho)), strength);
}

double sbfx_fire_soot(double coordinate, double cooled, double intensity)
{
    double age = 1.0 - clamp01(intensity);
    double cool = (1.0 - coordinate * cooled) * age * age;
    return SBFX_FIRE_SOOT * cool * cool;
}

double sbfx_fire_glow_share(double coordinate, double intensity, double strength)
{
    double threshold = SBFX_FIRE_GLOW_THRESHOLD + SBFX_FIRE_GLOW_AGE * (1.0 - clamp01(intensity));
    return mix(1.0, clamp01((coordinate - threshold) / SBFX_FIRE_GLOW_WIDTH), strength);
}

double sbfx_fire_cool_soot(double depth, double glow, double soot)
{
    return depth * soot * (1.0 - glow);
}

/* One pixel's disc of light at one detail value: sum over rings of L_e alpha dA; returns the
 * area it covers (with its soot). */
static double disc_at_detail(const sbfx_fire_model *m, double radius, double intensity, double detail, double rgb[3])
{
    double s = m->detail_strength;
    double threshold = EROSION_THRESHOLD + EROSION_AGE * (1.0 - clamp01(intensity));
    double density = mix(1.0, clamp01((detail - threshold) * EROSION_SHARPNESS) * EROSION_GAIN, s);
    double tau = m->tau * density * intensity;
    double cooled = 1.0 - m->cooling * (1.0 - intensity);
    double area = 0.0;
    for (int i = 0; i < RINGS; i++) {
        double rho = (i + 0.5) / RINGS;
        double depth = tau * radius * chord_depth(rho), alpha = -expm1(-depth);
        double ring = 2.0 * M_PI * rho * radius * radius / RINGS;
        double coordinate = sbfx_fire_coordinate(detail, rho, intensity, s);
        double soot_path = 2.0 * radius * (1.0 - rho) * (1.0 + rho); /* chord^2 / 2r */
        double glow = sbfx_fire_glow_share(coordinate, intensity, s);
        area += ring * -expm1(-(depth + sbfx_fire_cool_soot(depth, glow, m->soot) +
                                s * tau * soot_path * sbfx_fire_soot(coordinate, cooled, intensity)));
        ring *= alpha * glow;
        if (ring == 0.0) continue; /* soot too cool to glow: it only covers */
        double bb[3];
        m->blackbody(m->blackbody_ctx, (m->t0 + m->t1 * coordinate) * cooled, bb);
        for (int k = 0; k < 3; k++) {
            double radiance = bb[k] * m->emission_scale;
            rgb[k] += ring * (m->ceiling > 0.0 && radiance > m->ceiling ? m->ceiling : radiance);
        }
    }
    return area;
}

void sbfx_fire_particle_intensity(const sbfx_fire_model *m, double radius, double intensity, double rgb[3],
                                  double *area)
{
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    *area = 0.0;
    if (!(radius > 0.0) || !isfinite(radius) || !(intensity > 0.0) || !isfinite(intensity)) return;
    /* without detail every level gives the same: one is enough */
    int levels = m->detail_strength > 0.0 ? SBFX_FIRE_DETAIL_LEVELS : 1;
    for (int j = 0; j < levels; j++)
        *area += disc_at_detail(m, radius, intensity, levels > 1 ? m->detail[j] : 0.5, rgb);
    for (int k = 0; k < 3; k++) rgb[k] /= levels;
    *area /= levels;
}

static double luminance(const double rgb[3]) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

static double distance2(const double a[3], const double b[3])
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
}

/* The brightest particle no cluster has taken, or -1. */
static int brightest_free(const sbfx_fire_work *work, int count)
{
    int best = -1;
    for (int i = 0; i < count; i++)
        if (work[i].cluster < 0 && work[i].luminance > 0.0 && (best < 0 || work[i].luminance > work[best].luminance))
            best = i;
    return best;
}

static int seed_clusters(const sbfx_fire_particle *p, int count, sbfx_fire_work *work, int seeds[], int max)
{
    int n = 0;
    const double reach2 = SBFX_FIRE_CLUSTER_M * SBFX_FIRE_CLUSTER_M;
    for (int seed; n < max && (seed = brightest_free(work, count)) >= 0; n++) {
        seeds[n] = seed;
        for (int i = 0; i < count; i++)
            if (work[i].cluster < 0 && work[i].luminance > 0.0 && distance2(p[i].position, p[seed].position) <= reach2)
                work[i].cluster = n;
    }
    for (int i = 0; i < count && n > 0; i++) { /* left over once max lights are seeded */
        if (work[i].cluster >= 0 || !(work[i].luminance > 0.0)) continue;
        int nearest = 0;
        for (int c = 1; c < n; c++)
            if (distance2(p[i].position, p[seeds[c]].position) < distance2(p[i].position, p[seeds[nearest]].position))
                nearest = c;
        work[i].cluster = nearest;
    }
    return n;
}

/* The share of particle i's light that leaves the fire, averaged over directions: each other
 * fire particle j (nearer than SHADE_REACH: farther ones subtend little) lies in front of it over the solid angle its sphere subtends from
 * i (half of all directions when i is inside it; the fraction is (1 - cos) / 2 of the cone) and
 * there passes 1 - a_j of it, a_j = its emitting area / its disc (the mean opacity of its disc). */
static double leaving_share(const sbfx_fire_particle *p, int count, const sbfx_fire_work *work, int i)
{
    double share = 1.0;
    for (int j = 0; j < count; j++) {
        double r2 = p[j].radius * p[j].radius, d2 = distance2(p[i].position, p[j].position);
        if (j == i || !(work[j].area > 0.0) || d2 > SHADE_REACH * SHADE_REACH) continue;
        double front = d2 > r2 ? 0.5 * (1.0 - sqrt(1.0 - r2 / d2)) : 0.5;
        double opacity = work[j].area / (M_PI * r2);
        share *= 1.0 - front * (opacity < 1.0 ? opacity : 1.0);
    }
    return share;
}

static void finish_cluster(const sbfx_fire_particle *p, int count, const sbfx_fire_work *work, int c,
                           sbfx_fire_gathered *out)
{
    double y = 0.0, spread = 0.0, radius = 0.0;
    memset(out, 0, sizeof(*out));
    for (int i = 0; i < count; i++) {
        if (work[i].cluster != c) continue;
        double share = leaving_share(p, count, work, i);
        y += work[i].luminance;
        for (int k = 0; k < 3; k++) {
            out->intensity[k] += share * work[i].rgb[k];
            out->position[k] += work[i].luminance * p[i].position[k];
        }
    }
    for (int k = 0; k < 3; k++) out->position[k] /= y;
    for (int i = 0; i < count; i++) {
        if (work[i].cluster != c) continue;
        spread += work[i].luminance * distance2(p[i].position, out->position);
        radius += work[i].luminance * p[i].radius;
    }
    out->extent = sqrt(spread / y) + radius / y;
}

int sbfx_fire_gather(const sbfx_fire_model *m, const sbfx_fire_particle *particles, int count,
                     sbfx_fire_work *work, sbfx_fire_gathered *out, int max)
{
    if (max > SBFX_FIRE_GATHER_MAX) max = SBFX_FIRE_GATHER_MAX;
    if (max < 1 || count < 1) return 0;
    for (int i = 0; i < count; i++) {
        const sbfx_fire_particle *p = &particles[i];
        sbfx_fire_particle_intensity(m, p->radius, p->intensity, work[i].rgb, &work[i].area);
        bool finite = isfinite(p->position[0]) && isfinite(p->position[1]) && isfinite(p->position[2]);
        work[i].luminance = finite ? luminance(work[i].rgb) : 0.0;
        work[i].cluster = -1;
    }
    int seeds[SBFX_FIRE_GATHER_MAX];
    int n = seed_clusters(particles, count, work, seeds, max);
    for (int c = 0; c < n; c++) finish_cluster(particles, count, work, c, &out[c]);
    /* brightest first (a few entries: insertion sort) */
    for (int i = 1; i < n; i++) {
        sbfx_fire_gathered g = out[i];
        int j = i;
        for (; j > 0 && luminance(out[j - 1].intensity) < luminance(g.intensity); j--) out[j] = out[j - 1];
        out[j] = g;
    }
    return n;
}

double sbfx_light_falloff(double d2, double radius)
{
    double x2 = d2 / (radius * radius), window = 1.0 - x2 * x2;
    window = window > 0.0 ? window * window : 0.0;
    return window / (d2 > SBFX_LIGHT_MIN_D2 ? d2 : SBFX_LIGHT_MIN_D2);
}

double sbfx_fire_light_radius(double colour_max, double exposure, double extent)
{
    double reach = sqrt(colour_max * exposure / SBFX_LIGHT_NEGLIGIBLE);
    double least = extent + 0.5;
    return reach > least ? reach : least;
}

double sbfx_fire_gathered_radius(const sbfx_fire_gathered *g, double exposure)
{
    double top = fmax(g->intensity[0], fmax(g->intensity[1], g->intensity[2])) / M_PI;
    return sbfx_fire_light_radius(top, exposure, g->extent);
}

void sbfx_fire_scatter_at(const sbfx_fire_gathered *lights, int count, double exposure, const double c[3], double g,
                          sbfx_fire_scatter *out)
{
    memset(out, 0, sizeof(*out));
    double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), weight = 0.0;
    double to_eye[3] = {len > 0.0 ? -c[0] / len : 0.0, len > 0.0 ? -c[1] / len : 0.0, len > 0.0 ? -c[2] / len : 1.0};
    for (int i = 0; i < count; i++) {
        const sbfx_fire_gathered *l = &lights[i];
        double d[3] = {c[0] - l->position[0], c[1] - l->position[1], c[2] - l->position[2]};
        double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        double falloff = sbfx_light_falloff(d2, sbfx_fire_gathered_radius(l, exposure));
        if (!(falloff > 0.0)) continue;
        double inverse = 1.0 / sqrt(d2 > SBFX_LIGHT_MIN_D2 ? d2 : SBFX_LIGHT_MIN_D2);
        double cos_theta = (d[0] * to_eye[0] + d[1] * to_eye[1] + d[2] * to_eye[2]) * inverse;
        double scattered = falloff * sbfx_phase(cos_theta, g), rgb[3];
        for (int k = 0; k < 3; k++) out->rgb[k] += rgb[k] = l->intensity[k] * scattered;
        double w = luminance(rgb);
        for (int k = 0; k < 3; k++) out->position[k] += w * l->position[k];
        weight += w;
    }
    for (int k = 0; k < 3; k++) out->position[k] = weight > 0.0 ? out->position[k] / weight : c[k];
    double d2 = distance2(c, out->position);
    out->d2 = d2 > SBFX_LIGHT_MIN_D2 ? d2 : SBFX_LIGHT_MIN_D2;
}

void sbfx_fire_scatter_instance(const sbfx_fire_scatter *s, const double c[3], double radius, double out[8])
{
    memset(out, 0, 8 * sizeof(double));
    for (int k = 0; k < 3; k++) out[k] = s->rgb[k];
    if (!(s->d2 > 0.0)) return;   /* no fire light */
    double g[2] = {2.0 * (s->position[0] - c[0]) / s->d2, 2.0 * (s->position[1] - c[1]) / s->d2};
    double length = sqrt(g[0] * g[0] + g[1] * g[1]), most = radius > 0.0 ? 1.0 / radius : 0.0;
    double scale = length > most ? most / length : 1.0;
    out[4] = g[0] * scale;
    out[5] = g[1] * scale;
}
