/* Black-body colour of fire (docs/design.md §2.3): Planck's law integrated against the CIE 1931 2°
 * colour-matching functions, XYZ -> linear sRGB, normalised, tabulated over temperature.
 *
 * The CMFs are compiled in (sbfx_cie1931_2deg, generated at build time from colord-data's file
 * by tools/gen_cmf.c): nothing here reads a file. */
#include <math.h>
#include "tables/tables.h"

/* ---- Planck's law ------------------------------------------------------------------------ */

/* CODATA 2018 exact SI values. The seed prints L = 2 C1 / (λ^5 (e^{C2/λT} - 1)) with
 * C1 = 3.7418e-16 W m^2, which is the first radiation constant 2πhc² (it gives exitance when
 * used once); spectral *radiance* is 2hc²/(λ^5 (e^{hc/λkT} - 1)), used here. The seed's 2·C1
 * differs from 2hc² by the constant factor 2π and its C2 = 1.4388e-2 m K is hc/k rounded, so
 * nothing but the scale changes, and the table is normalised by 1/Y(T_max): the scale cancels. */
#define PLANCK_H 6.62607015e-34   /* J s */
#define LIGHT_C 299792458.0       /* m / s */
#define BOLTZMANN_K 1.380649e-23  /* J / K */
#define PLANCK_C1L (2.0 * PLANCK_H * LIGHT_C * LIGHT_C)    /* 1.191042972e-16 W m^2 sr^-1 */
#define PLANCK_C2 (PLANCK_H * LIGHT_C / BOLTZMANN_K)        /* 1.438776877e-2 m K */
/* e^-x < 2^-54 beyond it: 1 - e^-x rounds to 1 in double, so 1/(e^x - 1) is e^-x there */
#define PLANCK_WIEN_X 38.0

double sbfx_planck(double lambda_m, double kelvin)
{
    if (!(kelvin > 0.0) || !(lambda_m > 0.0) || !isfinite(kelvin) || !isfinite(lambda_m))
        return 0.0;
    double x = PLANCK_C2 / (lambda_m * kelvin);
    /* 1/(e^x - 1), one exponential: expm1(x) keeps full precision for x -> 0 (very hot bodies);
     * beyond x = PLANCK_WIEN_X, e^x - 1 is e^x in double, and e^-x underflows quietly to 0 for
     * cold bodies instead of e^x overflowing. (It was e^-x / -expm1(-x), two exponentials for
     * every band and temperature: a third of a scene's load on the CPU, its black-body table
     * and that table's check, 4600 temperatures at 95 bands.) */
    double l5 = lambda_m * lambda_m * lambda_m * lambda_m * lambda_m;
    double value = PLANCK_C1L / l5 * (x > PLANCK_WIEN_X ? exp(-x) : 1.0 / expm1(x));
    /* Only absurd inputs (T > ~1e290 K, λ < ~1e-60 m) leave the double range: 0, never inf/NaN. */
    return isfinite(value) ? value : 0.0;
}

/* ---- colour ----------------------------------------------------------------------------- */

void sbfx_blackbody_xyz(const sbfx_cmf *cmf, double kelvin, double xyz[3])
{
    xyz[0] = xyz[1] = xyz[2] = 0.0;
    if (!cmf || cmf->bands < 2) return;
    double step_m = cmf->step_nm * 1e-9;
    /* Trapezoid rule on the file's own band grid (the CMFs are only known there). */
    for (int i = 0; i < cmf->bands; i++) {
        double lambda_m = (cmf->start_nm + cmf->step_nm * i) * 1e-9;
        double weight = (i == 0 || i == cmf->bands - 1) ? 0.5 * step_m : step_m;
        double radiance = sbfx_planck(lambda_m, kelvin) * weight;
        for (int k = 0; k < 3; k++) xyz[k] += cmf->xyz[k][i] * radiance;
    }
}

/* IEC 61966-2-1 (sRGB, D65 white) XYZ -> linear RGB matrix, as the standard prints it. */
void sbfx_xyz_to_linear_srgb(const double xyz[3], double rgb[3])
{
    static const double m[3][3] = {
        {3.2406, -1.5372, -0.4986},
        {-0.9689, 1.8758, 0.0415},
        {0.0557, -0.2040, 1.0570},
    };
    for (int i = 0; i < 3; i++) rgb[i] = m[i][0] * xyz[0] + m[i][1] * xyz[1] + m[i][2] * xyz[2];
}

void sbfx_blackbody_rgb(const sbfx_cmf *cmf, double kelvin, double norm, double rgb[3])
{
    double xyz[3];
    sbfx_blackbody_xyz(cmf, kelvin, xyz);
    for (int k = 0; k < 3; k++) xyz[k] *= norm;
    sbfx_xyz_to_linear_srgb(xyz, rgb);
    /* Low temperatures (below about 2000 K) lie outside the sRGB gamut, beyond its red–green
     * edge: blue comes out negative. A display cannot emit negative light, so the component is
     * clipped to 0 (hue shifts slightly toward the gamut edge, luminance rises slightly). */
    for (int k = 0; k < 3; k++)
        if (!(rgb[k] > 0.0) || !isfinite(rgb[k])) rgb[k] = 0.0;
}

double sbfx_blackbody_luminance(const sbfx_cmf *cmf, double kelvin)
{
    double xyz[3];
    sbfx_blackbody_xyz(cmf, kelvin, xyz);
    /* Y is W sr^-1 m^-2 weighted by ybar (peak 1): lumens per watt at the peak make it cd/m^2 */
    return SBFX_LUMINOUS_EFFICACY * xyz[1];
}

double sbfx_emission_scale_photometric(double norm, double emissivity, double white_luminance)
{
    if (!(norm > 0.0) || !(white_luminance > 0.0) || !(emissivity > 0.0)) return 0.0;
    return emissivity * SBFX_LUMINOUS_EFFICACY / (norm * white_luminance);
}

double sbfx_blackbody_norm(const sbfx_cmf *cmf, double kelvin)
{
    double xyz[3];
    sbfx_blackbody_xyz(cmf, kelvin, xyz);
    double norm = 1.0 / xyz[1];
    /* No light at that temperature (T <= 0, or so cold Y underflows): a black table. */
    return (xyz[1] > 0.0 && isfinite(norm)) ? norm : 0.0;
}

/* ---- the table (reference.h says why these coordinates) ----------------------------------- */

static double table_inverse_kelvin(int i, int size, double lo, double hi)
{
    return size > 1 ? 1.0 / hi + (1.0 / lo - 1.0 / hi) * i / (size - 1) : 1.0 / hi;
}

void sbfx_blackbody_table(const sbfx_cmf *cmf, double norm, double lo, double hi, int size, float *out)
{
    if (!out || size < 1) return;
    for (int i = 0; i < size; i++) {
        double w = table_inverse_kelvin(i, size, lo, hi), xyz[3], rgb[3];
        sbfx_blackbody_xyz(cmf, 1.0 / w, xyz);
        double y = xyz[1] * norm;
        sbfx_xyz_to_linear_srgb(xyz, rgb); /* unclipped: the clip comes after interpolation */
        float *e = out + 4 * (size_t)i;
        for (int k = 0; k < 3; k++) e[k] = xyz[1] > 0.0 ? (float)(rgb[k] / xyz[1]) : 0.0f;
        /* ln(Y/T) = ln(Y w); a table with no light at all holds -inf's stand-in */
        e[3] = y > 0.0 ? (float)log(y * w) : -1e30f;
    }
}

void sbfx_blackbody_table_lookup(const float *table, int size, double lo, double hi, double kelvin,
                                 double rgb[3])
{
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (!table || size < 2 || !(kelvin > 0.0)) return;
    double pos = (1.0 / kelvin - 1.0 / hi) / (1.0 / lo - 1.0 / hi) * (size - 1);
    double cell = floor(pos);
    int i = cell < 0.0 ? 0 : cell > size - 2 ? size - 2 : (int)cell;
    double f = pos - i;
    const float *a = table + 4 * (size_t)i, *b = a + 4;
    double y = exp(a[3] + (b[3] - a[3]) * f) * (kelvin < 1e30 ? kelvin : 1e30);
    for (int k = 0; k < 3; k++) {
        double v = (a[k] + (b[k] - a[k]) * f) * y;
        rgb[k] = v > 0.0 && isfinite(v) ? v : 0.0;
    }
}

double sbfx_blackbody_table_error(const sbfx_cmf *cmf, double norm, const float *table, int size,
                                  double lo, double hi)
{
    double worst = 0.0;
    for (int i = 0; i < 8 * (size - 1) + 1 && size > 1; i++) {
        double w = 1.0 / hi + (1.0 / lo - 1.0 / hi) * i / (8.0 * (size - 1)), want[3], got[3];
        sbfx_blackbody_rgb(cmf, 1.0 / w, norm, want);
        sbfx_blackbody_table_lookup(table, size, lo, hi, 1.0 / w, got);
        double top = fmax(want[0], fmax(want[1], want[2]));
        for (int k = 0; k < 3 && top > 0.0; k++) worst = fmax(worst, fabs(got[k] - want[k]) / top);
    }
    return worst;
}
