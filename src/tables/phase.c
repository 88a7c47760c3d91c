/* Phase function of dust and smoke (docs/design.md §2.3): the Cornette–Shanks shaped function that the
 * seed prints (and calls Henyey–Greenstein), its table and the bilinear lookup the GPU does.
 *
 * Convention, chosen on purpose: cos_theta is the cosine between the direction the light
 * travels in and the direction the scattered light leaves in, so cos_theta = 1 means "straight
 * on" and g > 0 peaks forward:
 *     P(c, g) = 3 (1 - g^2) (1 + c^2) / (8 pi (2 + g^2) (1 + g^2 - 2 g c)^{3/2}).
 *
 * Why the seed's "+2g(w'.w)" is the same function: in the seed, C_j = ∫ I(j, w') P(w', w) dw'
 * with I(j, w') the radiance coming *from* direction w', so w' points from the particle toward
 * the light and the light travels along -w'. The scattering cosine is then c = (-w').w, and
 * 1 + g^2 - 2 g c = 1 + g^2 + 2 g (w'.w): the seed's denominator. Read with w' pointing toward
 * the light, the seed's formula peaks forward for g > 0; read with w' as the light's direction of
 * travel it would peak backward, which is the trap docs/design.md §2.3 warns about. Callers pass
 * c = dot(direction the light travels in, direction from the particle toward the camera), so a
 * particle back-lit by a light shining toward the camera gets c = 1 and, for g > 0, the peak.
 *
 * Normalisation: ∫ over the sphere of P = 2 pi ∫_{-1}^{1} P dc = 1 for every |g| < 1. */
#include <math.h>
#include <stdbool.h>
#include "tables/tables.h"

#define PI 3.14159265358979323846 /* M_PI is not C11 */

static double clamp(double x, double lo, double hi)
{
    return x > lo ? (x < hi ? x : hi) : lo; /* NaN -> lo */
}

double sbfx_phase(double cos_theta, double g)
{
    if (isnan(cos_theta) || isnan(g)) return 0.0; /* a bad input scatters nothing */
    double c = clamp(cos_theta, -1.0, 1.0);
    g = clamp(g, -SBFX_PHASE_G_MAX, SBFX_PHASE_G_MAX);
    double g2 = g * g;
    /* 1 + g^2 - 2gc >= (1 - |g|)^2 >= 1e-4: no division by zero at the clamp. */
    double base = 1.0 + g2 - 2.0 * g * c;
    return 3.0 * (1.0 - g2) * (1.0 + c * c) / (8.0 * PI * (2.0 + g2) * base * sqrt(base));
}

/* ---- the table of one medium (reference.h says why this coordinate) ----------------------- */

static bool warped(double g) { return fabs(g) >= SBFX_PHASE_WARP_MIN_G; }

double sbfx_phase_coordinate(double cos_theta, double g)
{
    if (isnan(cos_theta) || isnan(g)) return 0.0;
    double s = clamp(g < 0.0 ? -cos_theta : cos_theta, -1.0, 1.0);
    if (!warped(g)) return 0.5 * s + 0.5;
    double a = clamp(fabs(g), 0.0, SBFX_PHASE_G_MAX);
    double back = (1.0 + a) * (1.0 + a), peak = (1.0 - a) * (1.0 - a);
    return log((peak + 2.0 * a * (1.0 - s)) / back) / log(peak / back);
}

/* The s of coordinate t: b(t) = back^(1-t) peak^t, s = 1 - (b - peak) / 2|g|. */
static double table_s(double t, double g)
{
    if (!warped(g)) return 2.0 * t - 1.0;
    double a = clamp(fabs(g), 0.0, SBFX_PHASE_G_MAX);
    double back = (1.0 + a) * (1.0 + a), peak = (1.0 - a) * (1.0 - a);
    double b = back * exp(t * log(peak / back));
    return clamp(1.0 - (b - peak) / (2.0 * a), -1.0, 1.0);
}

void sbfx_phase_table(double g, int size, float *out)
{
    if (!out || size < 2) return;
    double sign = g < 0.0 ? -1.0 : 1.0;
    for (int i = 0; i < size; i++) out[i] = (float)sbfx_phase(sign * table_s((double)i / (size - 1), g), g);
}

double sbfx_phase_table_lookup(const float *table, int size, double g, double cos_theta)
{
    if (!table || size < 2 || isnan(cos_theta) || isnan(g)) return 0.0;
    double pos = sbfx_phase_coordinate(cos_theta, g) * (size - 1);
    int i = (int)pos;
    if (i > size - 2) i = size - 2;
    return table[i] + (table[i + 1] - table[i]) * (pos - i);
}

double sbfx_phase_table_error(const float *table, int size, double g)
{
    double worst = 0.0;
    int n = 16 * size;
    for (int i = 0; i <= n; i++) { /* a uniform cos θ grid (the back, for a warped table) */
        double c = -1.0 + 2.0 * i / n;
        double want = sbfx_phase(c, g), got = sbfx_phase_table_lookup(table, size, g, c);
        worst = fmax(worst, fabs(got - want) / want);
    }
    double sign = g < 0.0 ? -1.0 : 1.0;
    for (int i = 0; i < 8 * (size - 1); i++) { /* 8 points in every cell of t (the peak) */
        double c = sign * table_s((i + 0.5) / (8.0 * (size - 1)), g);
        double want = sbfx_phase(c, g), got = sbfx_phase_table_lookup(table, size, g, c);
        worst = fmax(worst, fabs(got - want) / want);
    }
    return worst;
}
