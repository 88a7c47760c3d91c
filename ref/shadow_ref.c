/* The host's shadow map, computed per point in double precision (ref/shadow_ref.h). */
#include "shadow_ref.h"

#include <math.h>
#include <stdbool.h>

double sbfx_ref_chord_depth(double tau, double r, double d)
{
    if (!(d < r)) return 0.0;
    double w = sqrt((r - d) * (r + d));
    double h_asinh = d > 0.0 ? d * d * asinh(w / d) : 0.0; /* -> 0 with d */
    return tau * fmax(w - h_asinh / r, 0.0);
}

/* Where particle q sits on the light's ray through p: its distance d from the ray, and how far
 * along the light's travel its centre is beyond p. */
static void on_ray(const sbfx_ref_particle *q, const double direction[3], const double p[3], double *d,
                   double *beyond)
{
    double v[3], along = 0.0, d2 = 0.0;
    for (int k = 0; k < 3; k++) v[k] = q->center[k] - p[k];
    for (int k = 0; k < 3; k++) along += v[k] * direction[k];
    for (int k = 0; k < 3; k++) {
        double off = v[k] - along * direction[k];
        d2 += off * off;
    }
    *d = sqrt(d2);
    *beyond = along;
}

static double dot4(const double row[4], const double x[3]) { return row[0] * x[0] + row[1] * x[1] + row[2] * x[2] + row[3]; }

static double chord_depth_to(double tau, double r, double d, double s);

/* The transmittance on the light's ray through p: of each particle's whole chord, or of its
 * chord only as far as p. */
static double transmittance(const sbfx_ref_particle *particles, size_t count, const double direction[3],
                            const double p[3], bool whole)
{
    double depth = 0.0;
    for (size_t i = 0; i < count; i++) {
        double d, beyond;
        on_ray(&particles[i], direction, p, &d, &beyond);
        /* p is -beyond past the point of the chord nearest the centre */
        depth += whole ? sbfx_ref_chord_depth(particles[i].tau, particles[i].radius, d)
                       : chord_depth_to(particles[i].tau, particles[i].radius, d, -beyond);
    }
    return exp(-depth);
}

double sbfx_ref_shadow_transmittance(const sbfx_ref_particle *particles, size_t count,
                                     const double direction[3], const double p[3])
{
    return transmittance(particles, count, direction, p, true);
}

/* The variance along the chord at distance d of the density 1 - |x - c| / r (shadow.frag). */
static double chord_variance(double r, double d)
{
    double w = sqrt((r - d) * (r + d)), h = d * d, asinh_wd = d > 0.0 ? asinh(w / d) : 0.0;
    double m0 = w - (d > 0.0 ? h * asinh_wd : 0.0) / r;
    double m2 = 2.0 * w * w * w / 3.0 - (w * (2.0 * w * w + h) * r - (d > 0.0 ? h * h * asinh_wd : 0.0)) / (4.0 * r);
    return m0 > 0.0 ? fmax(m2, 0.0) / m0 : 0.0;
}

void sbfx_ref_shadow_texel(const sbfx_ref_particle *particles, size_t count, const double direction[3],
                           const double p[3], const double depth_row[4], double out[4])
{
    double depth = 0.0, weighted = 0.0, squares = 0.0, front = 1.0;
    for (size_t i = 0; i < count; i++) {
        const sbfx_ref_particle *q = &particles[i];
        double d, beyond;
        on_ray(q, direction, p, &d, &beyond);
        if (!(d < q->radius)) continue;
        double chord = sbfx_ref_chord_depth(q->tau, q->radius, d), centre = dot4(depth_row, q->center);
        double scale = sqrt(depth_row[0] * depth_row[0] + depth_row[1] * depth_row[1] + depth_row[2] * depth_row[2]);
        double variance = chord_variance(q->radius, d) * scale * scale;
        depth += chord, weighted += chord * centre, squares += chord * (centre * centre + variance);
        front = fmin(front, centre - scale * sqrt((q->radius - d) * (q->radius + d)));
    }
    out[0] = exp(-depth);
    out[1] = exp(-weighted);
    out[2] = exp(-squares);
    out[3] = front;
}

double sbfx_ref_shadow_visibility(const double texel[4], double depth)
{
    double t = texel[0], front = texel[3];
    if (!(depth > front) || t >= 1.0) return 1.0;
    if (!(t > 1e-4)) return t; /* the mean and spread are not known: all of it in front */
    double mean = log(texel[1]) / log(t), half = sqrt(3.0 * fmax(log(texel[2]) / log(t) - mean * mean, 0.0));
    double begin = fmax(front, mean - half), end = mean + half;
    double share = end > begin ? (depth - begin) / (end - begin) : (depth > begin ? 1.0 : 0.0);
    return pow(t, share < 0.0 ? 0.0 : share > 1.0 ? 1.0 : share);
}

/* int tau (1 - sqrt(d^2 + s^2) / r) ds from the chord's start to s (s = 0 where the ray passes
 * nearest the centre, |s| <= w): F(s) - F(-w), F(s) = s - (s sqrt(d^2 + s^2) + d^2 asinh(s / d)) / 2r. */
static double chord_depth_to(double tau, double r, double d, double s)
{
    if (!(d < r)) return 0.0;
    double w = sqrt((r - d) * (r + d));
    if (s <= -w) return 0.0;
    if (s > w) s = w;
    double f_s = s - (s * sqrt(d * d + s * s) + (d > 0.0 ? d * d * asinh(s / d) : 0.0)) / (2.0 * r);
    double f_w = -w - (-w * r + (d > 0.0 ? d * d * asinh(-w / d) : 0.0)) / (2.0 * r);
    return tau * fmax(f_s - f_w, 0.0);
}

double sbfx_ref_shadow_transmittance_to(const sbfx_ref_particle *particles, size_t count,
                                        const double direction[3], const double p[3])
{
    return transmittance(particles, count, direction, p, false);
}
