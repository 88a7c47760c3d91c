/* Unit tests of the phase function reference (src/tables/phase.c): normalisation, the forward-peak
 * convention, the per-medium table in its warped coordinate and its lookup (docs/design.md §2.3,
 * g = ±0.99 and 0 of §2.2). */
#include "check.h"
#include "reference.h"

#define PI 3.14159265358979323846
#define TABLE_SIZE 256 /* the module's table size (SBFX_PHASE_SIZE) */

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

/* The coordinate: 0 at the back, 1 at the peak, monotone; cos itself for g ~ 0. */
CHECK_TEST(table_coordinate)
{
    const double gs[] = {-0.99, -0.95, -0.5, -0.02, 0.0, 0.019, 0.02, 0.3, 0.95, 0.99};
    for (size_t j = 0; j < sizeof gs / sizeof gs[0]; j++) {
        double g = gs[j], peak = g < 0 ? -1.0 : 1.0, prev = -1.0;
        CHECK_NEAR(sbfx_phase_coordinate(peak, g), 1.0, 1e-12);
        CHECK_NEAR(sbfx_phase_coordinate(-peak, g), 0.0, 1e-12);
        for (int i = 0; i <= 1000; i++) {
            double t = sbfx_phase_coordinate(-peak + peak * 2.0 * i / 1000, g);
            CHECK(t >= prev, "g %g: not monotone at step %d", g, i);
            prev = t;
        }
    }
    CHECK_NEAR(sbfx_phase_coordinate(0.3, 0.0), 0.65, 1e-15);
    CHECK(sbfx_phase_coordinate(NAN, 0.5) == 0.0);
}

/* Entries sit at the coordinate's grid: entry i at t = i / (n - 1), the ends exact. */
CHECK_TEST(table_layout)
{
    enum { N = 33 };
    const double gs[] = {-0.9, 0.0, 0.6};
    for (size_t j = 0; j < sizeof gs / sizeof gs[0]; j++) {
        float table[N];
        double g = gs[j], peak = g < 0 ? -1.0 : 1.0;
        sbfx_phase_table(g, N, table);
        CHECK(table[0] == (float)sbfx_phase(-peak, g) && table[N - 1] == (float)sbfx_phase(peak, g), "g %g", g);
        for (int i = 0; i < N; i++) {
            /* the entry's own cos, by bisection of the coordinate */
            double lo = -1, hi = 1;
            for (int k = 0; k < 60; k++) {
                double mid = 0.5 * (lo + hi);
                if ((sbfx_phase_coordinate(mid, g) < (double)i / (N - 1)) == (g >= 0)) lo = mid;
                else hi = mid;
            }
            double c = 0.5 * (lo + hi);
            CHECK_NEAR(table[i], sbfx_phase(c, g), 1e-6 * sbfx_phase(c, g));
            CHECK_NEAR(sbfx_phase_table_lookup(table, N, g, c), table[i], 1e-6 * table[i]);
        }
        CHECK(sbfx_phase_table_lookup(table, N, g, 3.0) == table[g < 0 ? 0 : N - 1]);
        CHECK(sbfx_phase_table_lookup(table, N, g, NAN) == 0.0);
    }
}

/* ∫ over the sphere of the looked-up function: the energy the table adds or loses. */
static double lookup_normalisation(const float *table, double g)
{
    const int n = 2000000;
    double sum = 0;
    for (int i = 0; i < n; i++) sum += sbfx_phase_table_lookup(table, TABLE_SIZE, g, -1 + (i + 0.5) * 2.0 / n);
    return 2 * PI * sum * 2.0 / n;
}

/* Within 1e-3 relative at every angle for |g| <= 0.95 (docs/design.md §4); at 0.99 the module falls
 * back to the analytic function, so the table's error there only has to be what is printed. */
CHECK_TEST(table_lookup_error_bounded)
{
    static float table[TABLE_SIZE];
    const double gs[] = {0.0, 0.5, -0.8, 0.9, 0.95, -0.95, 0.99};
    for (size_t j = 0; j < sizeof gs / sizeof gs[0]; j++) {
        sbfx_phase_table(gs[j], TABLE_SIZE, table);
        double err = sbfx_phase_table_error(table, TABLE_SIZE, gs[j]);
        printf("# phase table %d entries, g = %+.2f: max rel err %.3g, integral over the sphere %.6f\n",
               TABLE_SIZE, gs[j], err, lookup_normalisation(table, gs[j]));
        if (fabs(gs[j]) <= 0.95) CHECK(err < 5e-4, "g %g: %g", gs[j], err);
    }
    sbfx_phase_table(0.0, TABLE_SIZE, table);
    CHECK(fabs(lookup_normalisation(table, 0.0) - 1) < 1e-4);
    sbfx_phase_table(0.95, 64, table);
    CHECK(sbfx_phase_table_error(table, 64, 0.95) > 1e-3, "a coarse table must show its error");
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
