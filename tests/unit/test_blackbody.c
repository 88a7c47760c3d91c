/* Unit tests of the black-body reference (src/tables/blackbody.c): the compiled-in CMFs, Planck's law, XYZ ->
 * linear sRGB, the normalised table and its lookup (docs/design.md §2.3, hard cases of §2.2). No GL. */
#include "check.h"
#include "reference.h"

#define TABLE_MAX_K 6000.0 /* the module's default black-body unit (luminance 1 here) */

/* The CIE 1931 2° table compiled into the library (tools/gen_cmf.c made it from colord-data's
 * file at build time; tests/gen_cmf.sh tests the generator's errors). */
static void load_cmf(sbfx_cmf *cmf)
{
    *cmf = sbfx_cie1931_2deg;
}

static double luminance(const double rgb[3])
{
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; /* Y of linear sRGB */
}

static double rel_err(double a, double b)
{
    return fabs(a - b) / (fabs(b) > 0 ? fabs(b) : 1.0);
}

/* ---- the compiled-in table ---------------------------------------------------------------- */

CHECK_TEST(cmf_compiled_in_table)
{
    static sbfx_cmf cmf;
    load_cmf(&cmf);
    CHECK(cmf.bands == 95, "bands %d", cmf.bands);
    CHECK_NEAR(cmf.start_nm, 360.0, 1e-12);
    CHECK_NEAR(cmf.step_nm, 5.0, 1e-12);
    /* Spot values of the CIE 1931 table (as CIE 15 prints them; colord's copy). */
    CHECK_NEAR(cmf.xyz[0][0], 0.0001299, 1e-12);
    CHECK_NEAR(cmf.xyz[1][(555 - 360) / 5], 1.0, 1e-12); /* ȳ peaks at 555 nm */
    CHECK_NEAR(cmf.xyz[2][(445 - 360) / 5], 1.7826, 1e-12);
    CHECK_NEAR(cmf.xyz[0][94], 0.000001251141, 1e-15);
    /* ∫ȳ dλ ≈ 106.86 nm for the 1931 observer: a check that all 95 bands were read. */
    double sum = 0;
    for (int i = 0; i < cmf.bands; i++) sum += cmf.xyz[1][i] * cmf.step_nm * (i == 0 || i == 94 ? 0.5 : 1);
    CHECK_NEAR(sum, 106.86, 0.05);
}

/* ---- Planck ------------------------------------------------------------------------------ */

CHECK_TEST(planck_wien_peak)
{
    /* Wien's displacement law: λ_max T = 2.897771955e-3 m K (CODATA 2018). */
    double temps[] = {800, 1500, 5000, 1e5};
    for (size_t k = 0; k < 4; k++) {
        double t = temps[k], lo = 1e-9, hi = 1e-4, g = (sqrt(5) - 1) / 2;
        for (int i = 0; i < 200; i++) { /* golden-section search in log λ */
            double a = exp(log(hi) - g * (log(hi) - log(lo))), b = exp(log(lo) + g * (log(hi) - log(lo)));
            if (sbfx_planck(a, t) > sbfx_planck(b, t)) hi = b;
            else lo = a;
        }
        CHECK(rel_err(lo * t, 2.897771955e-3) < 1e-6, "T %g: λmax T = %.10g", t, lo * t);
    }
}

CHECK_TEST(planck_stefan_boltzmann)
{
    /* ∫ L dλ = σ T^4 / π, σ = 5.670374419e-8 W m^-2 K^-4. Simpson in log λ. */
    double temps[] = {300, 1500, 6500, 1e5};
    for (size_t k = 0; k < 4; k++) {
        double t = temps[k], a = log(1e-10), b = log(1.0), sum = 0;
        int n = 200000;
        for (int i = 0; i <= n; i++) {
            double y = a + (b - a) * i / n, l = exp(y);
            sum += sbfx_planck(l, t) * l * (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2));
        }
        sum *= (b - a) / n / 3;
        double want = 5.670374419e-8 * pow(t, 4) / 3.14159265358979323846;
        CHECK(rel_err(sum, want) < 1e-6, "T %g: %.10g vs %.10g", t, sum, want);
    }
}

CHECK_TEST(planck_t_to_zero)
{
    CHECK(sbfx_planck(550e-9, 0.0) == 0.0);
    CHECK(sbfx_planck(550e-9, -0.0) == 0.0);
    CHECK(sbfx_planck(550e-9, -100.0) == 0.0);
    CHECK(sbfx_planck(550e-9, NAN) == 0.0);
    CHECK(sbfx_planck(550e-9, -INFINITY) == 0.0);
    CHECK(sbfx_planck(550e-9, INFINITY) == 0.0);
    CHECK(sbfx_planck(0.0, 1000.0) == 0.0);
    CHECK(sbfx_planck(-1e-6, 1000.0) == 0.0);
    CHECK(sbfx_planck(NAN, 1000.0) == 0.0);
    /* Approaching 0 K: the exponent overflows, the value underflows to 0 without inf/NaN. */
    double prev = INFINITY;
    for (double t = 3000; t > 1e-300; t *= 0.5) {
        double v = sbfx_planck(360e-9, t);
        CHECK(isfinite(v) && v >= 0 && v <= prev, "T %g: %g", t, v);
        prev = v;
    }
    CHECK(prev == 0.0);
    CHECK(sbfx_planck(360e-9, 4.9406564584124654e-324) == 0.0);
}

CHECK_TEST(planck_hot_1e5_and_1e6)
{
    for (double t = 1e4; t <= 1e6; t *= 1.5) {
        for (double l = 360e-9; l <= 830e-9; l += 5e-9) {
            double v = sbfx_planck(l, t);
            CHECK(isfinite(v) && v > 0, "T %g λ %g: %g", t, l, v);
        }
    }
    /* Rayleigh–Jeans limit: L -> 2 c k T / λ^4 when hc/λkT -> 0 (x = 0.0173 here). */
    double l = 830e-9, t = 1e6, x = 6.62607015e-34 * 299792458.0 / (l * 1.380649e-23 * t);
    double rj = 2 * 299792458.0 * 1.380649e-23 * t / pow(l, 4);
    CHECK(rel_err(sbfx_planck(l, t), rj * x / expm1(x)) < 1e-13);
    CHECK(rel_err(sbfx_planck(l, t), rj) < x);
}

/* ---- colour ------------------------------------------------------------------------------ */

CHECK_TEST(srgb_matrix_maps_d65_to_white)
{
    double d65[3] = {0.95047, 1.0, 1.08883}, rgb[3];
    sbfx_xyz_to_linear_srgb(d65, rgb);
    for (int k = 0; k < 3; k++) CHECK_NEAR(rgb[k], 1.0, 1e-3);
    double red[3] = {0.4124, 0.2126, 0.0193};
    sbfx_xyz_to_linear_srgb(red, rgb);
    CHECK_NEAR(rgb[0], 1.0, 1e-3);
    CHECK_NEAR(rgb[1], 0.0, 1e-3);
    CHECK_NEAR(rgb[2], 0.0, 1e-3);
}

CHECK_TEST(blackbody_t_zero_is_exactly_zero)
{
    static sbfx_cmf cmf;
    load_cmf(&cmf);
    double xyz[3], rgb[3];
    double temps[] = {0.0, -5.0, NAN, 1e-300, 1.0, 10.0};
    for (size_t i = 0; i < sizeof temps / sizeof temps[0]; i++) {
        sbfx_blackbody_xyz(&cmf, temps[i], xyz);
        sbfx_blackbody_rgb(&cmf, temps[i], 1.0, rgb);
        for (int k = 0; k < 3; k++) {
            CHECK(xyz[k] == 0.0, "T %g xyz[%d] = %g", temps[i], k, xyz[k]);
            CHECK(rgb[k] == 0.0, "T %g rgb[%d] = %g", temps[i], k, rgb[k]);
        }
    }
    /* Small but visible: positive and finite. */
    sbfx_blackbody_xyz(&cmf, 300.0, xyz);
    CHECK(isfinite(xyz[1]) && xyz[1] >= 0);
    sbfx_blackbody_xyz(&cmf, 800.0, xyz);
    CHECK(isfinite(xyz[1]) && xyz[1] > 0);
}

CHECK_TEST(blackbody_1e5_kelvin_finite)
{
    static sbfx_cmf cmf;
    load_cmf(&cmf);
    double norm = sbfx_blackbody_norm(&cmf, 1e5), rgb[3], xyz[3];
    CHECK(isfinite(norm) && norm > 0);
    sbfx_blackbody_rgb(&cmf, 1e5, norm, rgb);
    for (int k = 0; k < 3; k++) CHECK(isfinite(rgb[k]) && rgb[k] >= 0);
    CHECK(rgb[2] > rgb[0], "1e5 K should be blue: %g %g %g", rgb[0], rgb[1], rgb[2]);
    sbfx_blackbody_xyz(&cmf, 1e6, xyz);
    for (int k = 0; k < 3; k++) CHECK(isfinite(xyz[k]) && xyz[k] > 0);
    /* A table from 500 K to 1e6 K stays finite too. */
    static float table[4 * 256];
    sbfx_blackbody_table(&cmf, norm, 500, 1e6, 256, table);
    for (int i = 0; i < 4 * 256; i++) CHECK(isfinite(table[i]), "entry %d: %g", i / 4, table[i]);
}

CHECK_TEST(blackbody_6500_is_roughly_white)
{
    static sbfx_cmf cmf;
    load_cmf(&cmf);
    double xyz[3], rgb[3];
    sbfx_blackbody_xyz(&cmf, 6500, xyz);
    sbfx_blackbody_rgb(&cmf, 6500, 1.0 / xyz[1], rgb);
    double lo = fmin(rgb[0], fmin(rgb[1], rgb[2])), hi = fmax(rgb[0], fmax(rgb[1], rgb[2]));
    printf("# 6500 K, Y = 1: linear sRGB %.4f %.4f %.4f, chromaticity x %.4f y %.4f\n", rgb[0],
           rgb[1], rgb[2], xyz[0] / (xyz[0] + xyz[1] + xyz[2]), xyz[1] / (xyz[0] + xyz[1] + xyz[2]));
    CHECK(hi <= 1.15 * lo, "not white: %g %g %g", rgb[0], rgb[1], rgb[2]);
    CHECK_NEAR(luminance(rgb), 1.0, 1e-3);
    /* Planckian locus at 6500 K: x = 0.3135, y = 0.3237 (CIE 1931). */
    CHECK_NEAR(xyz[0] / (xyz[0] + xyz[1] + xyz[2]), 0.3135, 2e-3);
    CHECK_NEAR(xyz[1] / (xyz[0] + xyz[1] + xyz[2]), 0.3237, 2e-3);
}

CHECK_TEST(blackbody_low_temperatures_are_red)
{
    static sbfx_cmf cmf;
    load_cmf(&cmf);
    double norm = sbfx_blackbody_norm(&cmf, TABLE_MAX_K);
    printf("# table normalisation 1/Y(%g K) = %.6g (Y in W sr^-1 m^-2, trapezoid over 5 nm bands)\n",
           TABLE_MAX_K, norm);
    double temps[] = {1000, 1500, 2000, 3000, 4000, 6500};
    for (size_t i = 0; i < sizeof temps / sizeof temps[0]; i++) {
        double rgb[3], xyz[3], by_y[3];
        sbfx_blackbody_rgb(&cmf, temps[i], norm, rgb);
        sbfx_blackbody_xyz(&cmf, temps[i], xyz);
        sbfx_blackbody_rgb(&cmf, temps[i], 1.0 / xyz[1], by_y);
        printf("# %6.0f K: table rgb %.6g %.6g %.6g | at Y = 1: %.4f %.4f %.4f\n", temps[i], rgb[0],
               rgb[1], rgb[2], by_y[0], by_y[1], by_y[2]);
        if (temps[i] <= 3000) CHECK(rgb[0] > rgb[1] && rgb[1] > rgb[2], "T %g: %g %g %g", temps[i], rgb[0], rgb[1], rgb[2]);
    }
    /* 1500 K lies outside the sRGB gamut: blue clipped to 0, not negative. */
    double rgb[3];
    sbfx_blackbody_rgb(&cmf, 1500, norm, rgb);
    CHECK(rgb[2] == 0.0, "blue %g", rgb[2]);
}

CHECK_TEST(blackbody_norm_is_inverse_y_of_max)
{
    static sbfx_cmf cmf;
    load_cmf(&cmf);
    double xyz[3];
    sbfx_blackbody_xyz(&cmf, TABLE_MAX_K, xyz);
    double norm = sbfx_blackbody_norm(&cmf, TABLE_MAX_K);
    CHECK(rel_err(norm * xyz[1], 1.0) < 1e-15);
    CHECK(sbfx_blackbody_norm(&cmf, 0.0) == 0.0);
    CHECK(sbfx_blackbody_norm(&cmf, -1.0) == 0.0);
    CHECK(sbfx_blackbody_norm(&cmf, NAN) == 0.0);
    CHECK(sbfx_blackbody_norm(&cmf, 10.0) == 0.0); /* Y underflows: a black table, not inf */
    CHECK(sbfx_blackbody_norm(NULL, 6000.0) == 0.0);
}

/* ---- photometry (docs/look-fire.md) ------------------------------------------------------ */

/* The test's own integration, independent of src/tables/blackbody.c: Planck's law written out in long
 * double, ybar interpolated linearly between the file's 5 nm bands, Simpson's rule at 0.05 nm. */
static double independent_luminance(const sbfx_cmf *cmf, double kelvin)
{
    const long double h = 6.62607015e-34L, c = 299792458.0L, k = 1.380649e-23L;
    double end_nm = cmf->start_nm + cmf->step_nm * (cmf->bands - 1), step = 0.05, sum = 0;
    int n = (int)lround((end_nm - cmf->start_nm) / step);
    for (int i = 0; i <= n; i++) {
        double nm = cmf->start_nm + step * i, pos = (nm - cmf->start_nm) / cmf->step_nm;
        int j = (int)pos < cmf->bands - 1 ? (int)pos : cmf->bands - 2;
        double ybar = cmf->xyz[1][j] + (cmf->xyz[1][j + 1] - cmf->xyz[1][j]) * (pos - j);
        long double lambda = nm * 1e-9L;
        long double planck = 2 * h * c * c / powl(lambda, 5) / expm1l(h * c / (lambda * k * kelvin));
        double weight = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
        sum += weight * ybar * (double)planck;
    }
    return 683.002 * sum * step * 1e-9 / 3.0;
}

/* docs/design.md §8: an optically thick black body at 1500 K has about 7.8e3 cd/m^2 (a clear daylight
 * sky is about 1e4), 2000 K about 4.7e5, 2500 K about 5.7e6. */
CHECK_TEST(blackbody_luminance_in_candela)
{
    static sbfx_cmf cmf;
    load_cmf(&cmf);
    const double kelvin[] = {1000, 1500, 2000, 2500, 3000, 6000}, expected[] = {0, 7.8e3, 4.7e5, 5.7e6, 0, 0};
    for (int i = 0; i < 6; i++) {
        double got = sbfx_blackbody_luminance(&cmf, kelvin[i]), want = independent_luminance(&cmf, kelvin[i]);
        printf("# %5.0f K: %.4g cd/m^2 (Simpson at 0.05 nm: %.4g)\n", kelvin[i], got, want);
        /* 5 nm trapezoid against a fine integration of the same data */
        CHECK(rel_err(got, want) < 2e-3, "%g K: %g vs %g", kelvin[i], got, want);
        if (expected[i] > 0) CHECK(rel_err(got, expected[i]) < 0.03, "%g K: %g cd/m^2", kelvin[i], got);
    }
    CHECK(sbfx_blackbody_luminance(&cmf, 1500) < sbfx_blackbody_luminance(&cmf, 2000));
    CHECK(sbfx_blackbody_luminance(&cmf, 0) == 0.0 && sbfx_blackbody_luminance(&cmf, NAN) == 0.0);
    double hot = sbfx_blackbody_luminance(&cmf, 1e5);
    CHECK(isfinite(hot) && hot > 1e11, "1e5 K: %g", hot);
}

/* Entries: chromaticity (rgb / Y, unclipped) and ln(Y / T) at T uniform in 1/T. */
CHECK_TEST(table_entries)
{
    static sbfx_cmf cmf;
    load_cmf(&cmf);
    enum { N = 64 };
    static float table[4 * N];
    double norm = sbfx_blackbody_norm(&cmf, TABLE_MAX_K), lo = 800, hi = 9000;
    sbfx_blackbody_table(&cmf, norm, lo, hi, N, table);
    for (int i = 0; i < N; i++) {
        double t = 1.0 / (1.0 / hi + (1.0 / lo - 1.0 / hi) * i / (N - 1)), xyz[3], rgb[3];
        sbfx_blackbody_xyz(&cmf, t, xyz);
        sbfx_xyz_to_linear_srgb(xyz, rgb);
        for (int k = 0; k < 3; k++) CHECK_NEAR(table[4 * i + k], rgb[k] / xyz[1], 1e-6 * fabs(rgb[k] / xyz[1]) + 1e-7);
        CHECK_NEAR(table[4 * i + 3], log(xyz[1] * norm / t), 1e-6 * fabs(log(xyz[1] * norm / t)));
    }
    /* entry 0 is the hot end; blue is out of gamut (negative, kept until after interpolation)
     * at 800 K only */
    CHECK(table[2] > 0.0f && table[4 * (N - 1) + 2] < 0.0f, "blue %g at 9000 K, %g at 800 K", table[2],
          table[4 * (N - 1) + 2]);
}

/* Both ends exact (up to float), and the interpolation within 1e-4 of the largest channel over
 * 500..20000 K with the module's 512 entries; a table linear in T (the old one) is far off. */
CHECK_TEST(table_lookup_matches_function)
{
    static sbfx_cmf cmf;
    load_cmf(&cmf);
    enum { N = 512 };
    static float table[4 * N];
    double norm = sbfx_blackbody_norm(&cmf, TABLE_MAX_K), lo = 500, hi = 20000;
    sbfx_blackbody_table(&cmf, norm, lo, hi, N, table);
    const double ends[] = {lo, hi};
    for (int i = 0; i < 2; i++) {
        double rgb[3], want[3];
        sbfx_blackbody_table_lookup(table, N, lo, hi, ends[i], rgb);
        sbfx_blackbody_rgb(&cmf, ends[i], norm, want);
        /* float entries: ln(Y/T) ~ -50 at 500 K is held to 2^-24 of that */
        for (int k = 0; k < 3; k++) CHECK_NEAR(rgb[k], want[k], 5e-6 * fmax(want[0], want[1]));
    }
    double err = sbfx_blackbody_table_error(&cmf, norm, table, N, lo, hi);
    printf("# table %d entries, %g..%g K: largest error %.3g of the largest channel\n", N, lo, hi, err);
    CHECK(err < 1.5e-4, "%g", err);
    CHECK(sbfx_blackbody_table_error(&cmf, norm, table, 64, lo, hi) > 1e-3, "a coarse table must show its error");
}

CHECK_TEST(table_lookup_edges)
{
    static sbfx_cmf cmf;
    load_cmf(&cmf);
    enum { N = 128 };
    static float table[4 * N];
    double norm = sbfx_blackbody_norm(&cmf, TABLE_MAX_K), lo = 1000, hi = 4000, rgb[3], want[3];
    sbfx_blackbody_table(&cmf, norm, lo, hi, N, table);
    const double dark[] = {0.0, -50.0, NAN, -INFINITY, 1e-30};
    for (size_t i = 0; i < sizeof dark / sizeof dark[0]; i++) {
        sbfx_blackbody_table_lookup(table, N, lo, hi, dark[i], rgb);
        CHECK(rgb[0] == 0 && rgb[1] == 0 && rgb[2] == 0, "T = %g: %g %g %g", dark[i], rgb[0], rgb[1], rgb[2]);
    }
    /* Below the table: Wien's law carries the luminance on (not the end entry's value). */
    sbfx_blackbody_table_lookup(table, N, lo, hi, 900, rgb);
    sbfx_blackbody_rgb(&cmf, 900, norm, want);
    CHECK(rel_err(rgb[0], want[0]) < 1e-2, "900 K: %g vs %g", rgb[0], want[0]);
    /* Far above: finite, not clamped to the top entry's colour. */
    sbfx_blackbody_table_lookup(table, N, lo, hi, INFINITY, rgb);
    for (int k = 0; k < 3; k++) CHECK(isfinite(rgb[k]) && rgb[k] >= 0.0);
    double top[3];
    sbfx_blackbody_table_lookup(table, N, lo, hi, hi, top);
    sbfx_blackbody_table_lookup(table, N, lo, hi, 1.3 * hi, rgb);
    CHECK(rgb[1] > top[1], "not clamped at the top");
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
