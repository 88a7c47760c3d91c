/* Unit tests of the phase function reference (src/phase.c): normalisation, the forward-peak
 * convention, the table and its bilinear lookup (DESIGN §2.3, g = ±0.99 and 0 of §2.2). */
#include "check.h"
#include "reference.h"

#define PI 3.14159265358979323846
#define TABLE_COS 128 /* the module's table size (src/module.h) */
#define TABLE_G 64

/* ∫ over the sphere of P(c, g) · c^k (k = 0: normalisation, k = 1: mean cosine).
 *
 * For g = ±0.99 the peak is about (1-|g|)^2 = 1e-4 wide in cos θ, so the integral is taken in
 * the variable of the peak, t = (1 + g^2 - 2 g c)^{-1/2}: dt = g (1 + g^2 - 2gc)^{-3/2} dc
 * absorbs the singular factor, and what is left, (1 + c(t)^2) c(t)^k with
 * c(t) = (1 + g^2 - 1/t^2) / (2g), is smooth on [1/(1+|g|), 1/(1-|g|)]. Composite Simpson with
 * 200000 panels is then exact to about 1e-15. Near g = 0 the substitution degenerates and plain
 * Simpson in c is used (the function is smooth there). */
static double sphere_moment(double g, int k)
{
    const int n = 200000;
    double sum = 0;
    if (fabs(g) < 0.05) {
        for (int i = 0; i <= n; i++) {
            double c = -1 + 2.0 * i / n;
            sum += sbfx_phase(c, g) * pow(c, k) * (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2));
        }
        return 2 * PI * sum * (2.0 / n) / 3;
    }
    double t_lo = 1 / (1 + fabs(g)), t_hi = 1 / (1 - fabs(g)); /* t at the two ends of c */
    double h = (t_hi - t_lo) / n;
    for (int i = 0; i <= n; i++) {
        double t = t_lo + h * i, c = (1 + g * g - 1 / (t * t)) / (2 * g);
        sum += (1 + c * c) * pow(c, k) * (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2));
    }
    sum *= h / 3;
    /* P dc = 3(1-g^2)(1+c^2) / (8π(2+g^2)) · dt / |g|, and 2π from the azimuth. */
    return 2 * PI * 3 * (1 - g * g) / (8 * PI * (2 + g * g)) * sum / fabs(g);
}

/* A brute-force check of the substitution itself: midpoint rule in c with 2e7 samples. */
static double sphere_integral_brute(double g)
{
    const int n = 20000000;
    double sum = 0;
    for (int i = 0; i < n; i++) sum += sbfx_phase(-1 + (i + 0.5) * 2.0 / n, g);
    return 2 * PI * sum * 2.0 / n;
}

CHECK_TEST(normalised_over_sphere)
{
    double gs[] = {-0.99, -0.9, -0.5, -0.1, 0.0, 0.1, 0.5, 0.9, 0.99};
    for (size_t i = 0; i < sizeof gs / sizeof gs[0]; i++) {
        double total = sphere_moment(gs[i], 0);
        printf("# g = %+.2f: integral of P over the sphere = %.15f\n", gs[i], total);
        CHECK_NEAR(total, 1.0, 1e-4);
        CHECK_NEAR(total, 1.0, 1e-10); /* the normalisation is analytic: much better than 1e-4 */
    }
    /* The substitution agrees with a plain (very fine) midpoint rule. */
    CHECK_NEAR(sphere_integral_brute(0.99), 1.0, 1e-4);
    CHECK_NEAR(sphere_integral_brute(-0.99), 1.0, 1e-4);
}

CHECK_TEST(mean_cosine_is_cornette_shanks)
{
    /* <cos θ> of the Cornette–Shanks function: 3g(4 + g^2) / (5(2 + g^2)); positive for g > 0,
     * i.e. the light mostly goes on in its direction of travel. */
    double gs[] = {-0.99, -0.5, 0.0, 0.5, 0.99};
    for (size_t i = 0; i < sizeof gs / sizeof gs[0]; i++) {
        double g = gs[i], mean = sphere_moment(g, 1);
        CHECK_NEAR(mean, 3 * g * (4 + g * g) / (5 * (2 + g * g)), 1e-10);
        if (g > 0) CHECK(mean > 0);
        if (g < 0) CHECK(mean < 0);
    }
}

CHECK_TEST(forward_peak_for_positive_g)
{
    /* cos θ = 1: light goes straight on. Positive g must peak there. */
    double gs[] = {0.01, 0.2, 0.5, 0.8, 0.99};
    for (size_t i = 0; i < sizeof gs / sizeof gs[0]; i++) {
        double g = gs[i];
        CHECK(sbfx_phase(1, g) > sbfx_phase(-1, g), "g %g", g);
        CHECK(sbfx_phase(-1, -g) > sbfx_phase(1, -g), "g %g", -g);
        CHECK_NEAR(sbfx_phase(1, g), sbfx_phase(-1, -g), 1e-12 * sbfx_phase(1, g)); /* mirror */
        /* The maximum over cos θ is at cos θ = 1. */
        for (int k = 0; k < 2000; k++) CHECK(sbfx_phase(-1 + k / 1000.0, g) <= sbfx_phase(1, g));
    }
    /* Value at the peak for g = 0.99: 3(1-g²)·2 / (8π(2+g²)(1-g)³). */
    double g = 0.99;
    CHECK_NEAR(sbfx_phase(1, g), 3 * (1 - g * g) * 2 / (8 * PI * (2 + g * g) * pow(1 - g, 3)), 1e-9);
    printf("# P(1, 0.99) = %.6g /sr, P(-1, 0.99) = %.6g /sr\n", sbfx_phase(1, 0.99), sbfx_phase(-1, 0.99));
}

CHECK_TEST(seed_formula_with_w_prime_toward_the_light)
{
    /* The seed prints 1/(4π) · 3(1-g²)(1+(w'·w)²) / (2(2+g²)(1+g²+2g(w'·w))^{3/2}). With w'
     * pointing toward the light, w'·w = -cos θ, and the two agree everywhere. */
    for (double g = -0.99; g <= 0.99; g += 0.09) {
        for (double c = -1; c <= 1; c += 0.01) {
            double wdot = -c;
            double seed = 1 / (4 * PI) * 3 * (1 - g * g) * (1 + wdot * wdot) /
                          (2 * (2 + g * g) * pow(1 + g * g + 2 * g * wdot, 1.5));
            CHECK_NEAR(sbfx_phase(c, g), seed, 1e-12 * seed);
        }
    }
}

CHECK_TEST(symmetric_at_g_zero)
{
    for (double c = -1; c <= 1; c += 0.001) {
        CHECK_NEAR(sbfx_phase(c, 0), sbfx_phase(-c, 0), 1e-15);
        CHECK_NEAR(sbfx_phase(c, 0), 3 * (1 + c * c) / (16 * PI), 1e-15); /* Rayleigh */
    }
}

CHECK_TEST(g_and_cos_clamped_never_nan)
{
    for (double c = -1; c <= 1; c += 0.125) {
        CHECK(sbfx_phase(c, 1.0) == sbfx_phase(c, SBFX_PHASE_G_MAX));
        CHECK(sbfx_phase(c, 5.0) == sbfx_phase(c, SBFX_PHASE_G_MAX));
        CHECK(sbfx_phase(c, INFINITY) == sbfx_phase(c, SBFX_PHASE_G_MAX));
        CHECK(sbfx_phase(c, -1.0) == sbfx_phase(c, -SBFX_PHASE_G_MAX));
        CHECK(sbfx_phase(c, -INFINITY) == sbfx_phase(c, -SBFX_PHASE_G_MAX));
    }
    CHECK(sbfx_phase(1.5, 0.5) == sbfx_phase(1.0, 0.5));
    CHECK(sbfx_phase(-7.0, 0.5) == sbfx_phase(-1.0, 0.5));
    CHECK(sbfx_phase(NAN, 0.5) == 0.0);
    CHECK(sbfx_phase(0.5, NAN) == 0.0);
    for (double g = -1.2; g <= 1.2; g += 0.001)
        for (double c = -1; c <= 1; c += 0.05) {
            double p = sbfx_phase(c, g);
            CHECK(isfinite(p) && p > 0, "P(%g, %g) = %g", c, g, p);
        }
}

CHECK_TEST(table_layout)
{
    enum { NC = 17, NG = 9 };
    double table[NC * NG];
    sbfx_phase_table(NC, NG, table);
    for (int j = 0; j < NG; j++) {
        double g = -SBFX_PHASE_G_MAX + 2 * SBFX_PHASE_G_MAX * j / (NG - 1);
        for (int i = 0; i < NC; i++) {
            double c = -1 + 2.0 * i / (NC - 1);
            CHECK(table[j * NC + i] == sbfx_phase(c, g), "entry (%d, %d)", i, j);
            /* The grid position of a node may round to just below it: equal to rounding. */
            CHECK_NEAR(sbfx_phase_table_lookup(table, NC, NG, c, g), table[j * NC + i],
                       1e-12 * table[j * NC + i]);
        }
    }
    /* Out of range arguments clamp to the edges. */
    CHECK(sbfx_phase_table_lookup(table, NC, NG, 3, 2) == table[(NG - 1) * NC + NC - 1]);
    CHECK(sbfx_phase_table_lookup(table, NC, NG, -3, -2) == table[0]);
    CHECK(sbfx_phase_table_lookup(table, NC, NG, NAN, 0) == 0.0);
}

/* Largest relative error of the lookup for |g| <= g_max, on a grid 8x finer than the table. */
static double lookup_rel_error(const double *table, double g_max, double *abs_out)
{
    double worst = 0, worst_abs = 0;
    int ng = 8 * TABLE_G, nc = 8 * TABLE_COS;
    for (int j = 0; j <= ng; j++) {
        double g = -g_max + 2 * g_max * j / ng;
        for (int i = 0; i <= nc; i++) {
            double c = -1 + 2.0 * i / nc;
            double want = sbfx_phase(c, g);
            double e = fabs(sbfx_phase_table_lookup(table, TABLE_COS, TABLE_G, c, g) - want);
            if (e / want > worst) worst = e / want;
            if (e > worst_abs) worst_abs = e;
        }
    }
    if (abs_out) *abs_out = worst_abs;
    return worst;
}

/* ∫ over the sphere of the looked-up function: the energy the table adds or loses. */
static double lookup_normalisation(const double *table, double g)
{
    const int n = 2000000;
    double sum = 0;
    for (int i = 0; i < n; i++)
        sum += sbfx_phase_table_lookup(table, TABLE_COS, TABLE_G, -1 + (i + 0.5) * 2.0 / n, g);
    return 2 * PI * sum * 2.0 / n;
}

CHECK_TEST(table_lookup_error_bounded)
{
    static double table[TABLE_COS * TABLE_G];
    sbfx_phase_table(TABLE_COS, TABLE_G, table);
    double bands[] = {0.5, 0.8, 0.9, 0.99}, errs[4], abs_e[4];
    for (int b = 0; b < 4; b++) {
        errs[b] = lookup_rel_error(table, bands[b], &abs_e[b]);
        printf("# phase table %dx%d, |g| <= %.2f: max rel err %.3g, max abs err %.3g /sr\n",
               TABLE_COS, TABLE_G, bands[b], errs[b], abs_e[b]);
    }
    double n0 = lookup_normalisation(table, 0.0), n99 = lookup_normalisation(table, 0.99);
    printf("# integral of the looked-up function over the sphere: g = 0: %.6f, g = 0.99: %.4f "
           "(analytic: 1)\n", n0, n99);
    CHECK(errs[0] < 0.01, "%g", errs[0]);
    CHECK(errs[1] < 0.2, "%g", errs[1]);
    CHECK(fabs(n0 - 1) < 1e-3, "%g", n0);
    /* Near |g| = 0.99 the peak (1e-4 wide in cos θ) is narrower than a table cell (0.016): the
     * LUT is poor there — relative errors in the hundreds — which is why the analytic
     * evaluation is the named alternative. Bilinear weights are convex, so the error can never
     * exceed the table's largest entry. */
    CHECK(abs_e[3] <= sbfx_phase(1, 0.99), "%g", abs_e[3]);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
