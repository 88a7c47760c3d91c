/* Phase function of dust and smoke (DESIGN §2.3): the Cornette–Shanks shaped function that the
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
 * travel it would peak backward, which is the trap DESIGN §2.3 warns about. Callers pass
 * c = dot(direction the light travels in, direction from the particle toward the camera), so a
 * particle back-lit by a light shining toward the camera gets c = 1 and, for g > 0, the peak.
 *
 * Normalisation: ∫ over the sphere of P = 2 pi ∫_{-1}^{1} P dc = 1 for every |g| < 1. */
#include <math.h>
#include "tables.h"

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

static double table_cos(int i, int n_cos)
{
    return n_cos > 1 ? -1.0 + 2.0 * i / (n_cos - 1) : 1.0;
}

static double table_g(int j, int n_g)
{
    return n_g > 1 ? -SBFX_PHASE_G_MAX + 2.0 * SBFX_PHASE_G_MAX * j / (n_g - 1) : 0.0;
}

/* Layout: out[j * n_cos + i] = P(cos_i, g_j) — one row per g, cos varying fastest, i.e. a GL
 * texture of width n_cos (s = cos) and height n_g (t = g). A single-column or single-row table
 * (n == 1) holds cos = 1 or g = 0 respectively. */
void sbfx_phase_table(int n_cos, int n_g, double *out)
{
    if (!out || n_cos < 1 || n_g < 1) return;
    for (int j = 0; j < n_g; j++)
        for (int i = 0; i < n_cos; i++)
            out[(size_t)j * (size_t)n_cos + (size_t)i] = sbfx_phase(table_cos(i, n_cos), table_g(j, n_g));
}

/* Position of x in a grid of n points over [lo, hi]: integer cell and fraction. */
static void grid_position(double x, double lo, double hi, int n, int *cell, double *frac)
{
    if (n < 2) {
        *cell = 0;
        *frac = 0.0;
        return;
    }
    double pos = (clamp(x, lo, hi) - lo) / (hi - lo) * (n - 1);
    int k = (int)pos;
    if (k > n - 2) k = n - 2;
    *cell = k;
    *frac = pos - k;
}

double sbfx_phase_table_lookup(const double *table, int n_cos, int n_g, double cos_theta, double g)
{
    if (!table || n_cos < 1 || n_g < 1 || isnan(cos_theta) || isnan(g)) return 0.0;
    int i, j;
    double fi, fj;
    grid_position(cos_theta, -1.0, 1.0, n_cos, &i, &fi);
    grid_position(g, -SBFX_PHASE_G_MAX, SBFX_PHASE_G_MAX, n_g, &j, &fj);
    int i1 = n_cos > 1 ? i + 1 : i, j1 = n_g > 1 ? j + 1 : j;
    const double *row0 = table + (size_t)j * (size_t)n_cos;
    const double *row1 = table + (size_t)j1 * (size_t)n_cos;
    double v0 = row0[i] + (row0[i1] - row0[i]) * fi;
    double v1 = row1[i] + (row1[i1] - row1[i]) * fi;
    return v0 + (v1 - v0) * fj;
}
