/* Unit tests of the CPU opacity reference (ref/opacity_ref.c), docs/design.md §2.1 and the opacity
 * hard cases of §2.2. No GL. */
#include <float.h>
#include "check.h"
#include "reference.h"

#define ALL_MODES_N 5
static const sbfx_opacity_mode all_modes[ALL_MODES_N] = {
    SBFX_OPACITY_DEFAULT, SBFX_OPACITY_PLANAR, SBFX_OPACITY_SOFT, SBFX_OPACITY_SPHERICAL,
    SBFX_OPACITY_EXACT};

static sbfx_ref_particle particle(double x, double y, double z, double r, double tau)
{
    sbfx_ref_particle p = {{x, y, z}, r, tau};
    return p;
}

/* Pixel whose ray passes through view-space point (x, y, z), z < 0. */
static sbfx_ref_pixel pixel_through(double x, double y, double z, double zs, double near)
{
    sbfx_ref_pixel px = {{x / -z, y / -z, -1.0}, zs, near, 0.0};
    return px;
}

static double od(sbfx_opacity_mode m, sbfx_ref_particle p, sbfx_ref_pixel px)
{
    return sbfx_ref_optical_depth(m, &p, &px);
}

static double alpha(sbfx_opacity_mode m, sbfx_ref_particle p, sbfx_ref_pixel px)
{
    return sbfx_ref_opacity(m, &p, &px);
}

static double rel_err(double a, double b)
{
    double scale = fabs(b) > 0 ? fabs(b) : 1.0;
    return fabs(a - b) / scale;
}

/* Every mode: finite, alpha in [0, 1], optical depth in [0, 1e30]. */
static void check_sane(sbfx_ref_particle p, sbfx_ref_pixel px, const char *what)
{
    for (int m = 0; m < ALL_MODES_N; m++) {
        double a = alpha(all_modes[m], p, px), o = od(all_modes[m], p, px);
        CHECK(isfinite(a) && a >= 0.0 && a <= 1.0, "%s: mode %d alpha %g", what, all_modes[m], a);
        CHECK(isfinite(o) && o >= 0.0 && o <= 1e30, "%s: mode %d od %g", what, all_modes[m], o);
    }
}

static void check_all_zero(sbfx_ref_particle p, sbfx_ref_pixel px, const char *what)
{
    for (int m = 0; m < ALL_MODES_N; m++) {
        double a = alpha(all_modes[m], p, px), o = od(all_modes[m], p, px);
        CHECK(a == 0.0 && o == 0.0, "%s: mode %d alpha %g od %g", what, all_modes[m], a, o);
    }
}

/* ---- independent long-double brute force of the exact model --------------------------- */

/* ∫ tau (1 - |x - c|/r)+ along the ray direction `ray`, for the ray parameter range allowed by
 * the near plane and the opaque depth, by `n` midpoint samples. Sphere entry and exit come from
 * the quadratic |t u - c|^2 = r^2, a different route from the reference's. */
static long double brute_exact(sbfx_ref_particle p, sbfx_ref_pixel px, int n)
{
    long double len = sqrtl((long double)px.ray[0] * px.ray[0] + (long double)px.ray[1] * px.ray[1] +
                            (long double)px.ray[2] * px.ray[2]);
    long double u[3] = {px.ray[0] / len, px.ray[1] / len, px.ray[2] / len};
    long double c[3] = {p.center[0], p.center[1], p.center[2]}, r = p.radius;
    long double b = u[0] * c[0] + u[1] * c[1] + u[2] * c[2];
    long double cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    long double disc = b * b - cc + r * r;
    if (disc <= 0) return 0;
    long double t1 = b - sqrtl(disc), t2 = b + sqrtl(disc);
    long double tn = (long double)(px.near > 0 ? px.near : 0) / -u[2];
    long double ts = isinf(px.opaque_depth) ? INFINITY : (long double)px.opaque_depth / -u[2];
    long double lo = t1 > tn ? t1 : tn, hi = t2 < ts ? t2 : ts;
    if (!(hi > lo)) return 0;
    long double step = (hi - lo) / n, sum = 0;
    for (int i = 0; i < n; i++) {
        long double t = lo + (i + 0.5L) * step;
        long double e0 = t * u[0] - c[0], e1 = t * u[1] - c[1], e2 = t * u[2] - c[2];
        long double f = 1 - sqrtl(e0 * e0 + e1 * e1 + e2 * e2) / r;
        if (f > 0) sum += f;
    }
    return (long double)p.tau * sum * step;
}

/* x - asinh(x), by series for small x (no cancellation). */
static long double x_minus_asinh(long double x)
{
    if (x < 1e-2L) {
        long double x2 = x * x;
        return x * x2 * (1.0L / 6 - x2 * (3.0L / 40 - x2 * (5.0L / 112 - x2 * 35.0L / 1152)));
    }
    return x - asinhl(x);
}

/* Exact model, full chord (no clipping), at ray–centre distance D: τ[w(1 - D/r) + (h/r) E(w/D)]
 * with E(x) = x - asinh(x) — the closed form rearranged so nothing cancels. */
static long double exact_full_chord(long double tau, long double r, long double dist)
{
    long double w = sqrtl((r - dist) * (r + dist));
    if (dist == 0) return tau * (w - 0);
    return tau * (w * (r - dist) / r + dist * dist / r * x_minus_asinh(w / dist));
}

/* ---- model values ------------------------------------------------------------------------ */

CHECK_TEST(spherical_through_centre_is_2_tau_r)
{
    sbfx_ref_particle p = particle(0, 0, -10, 1.5, 0.4);
    sbfx_ref_pixel px = pixel_through(0, 0, -10, INFINITY, 0.1);
    CHECK_NEAR(od(SBFX_OPACITY_SPHERICAL, p, px), 2 * 0.4 * 1.5, 1e-14);
    CHECK_NEAR(alpha(SBFX_OPACITY_SPHERICAL, p, px), -expm1(-1.2), 1e-15);
}

CHECK_TEST(exact_through_centre_is_tau_r)
{
    /* Far from the camera and unclipped: the exact linear profile integrates to τr. */
    sbfx_ref_particle p = particle(0, 0, -10, 1.5, 0.4);
    sbfx_ref_pixel px = pixel_through(0, 0, -10, INFINITY, 0.1);
    CHECK_NEAR(od(SBFX_OPACITY_EXACT, p, px), 0.4 * 1.5, 1e-14);
    CHECK_NEAR(od(SBFX_OPACITY_DEFAULT, p, px), 0.4 * 1.5, 1e-14);
    /* Off-axis centre, ray aimed at it: still τr (the model difference is not rescaled). */
    p = particle(3, -2, -20, 0.7, 2.0);
    px = pixel_through(3, -2, -20, INFINITY, 0.1);
    CHECK_NEAR(od(SBFX_OPACITY_EXACT, p, px), 2.0 * 0.7, 1e-13);
}

/* The module's default is the exact model (issue 12: chosen from the bench's Pareto front). */
CHECK_TEST(default_mode_is_exact)
{
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 7);
    for (int i = 0; i < 1000; i++) {
        sbfx_ref_particle p = particle(sbfx_rng_range(&rng, -2, 2), sbfx_rng_range(&rng, -2, 2),
                                       sbfx_rng_range(&rng, -12, -1), sbfx_rng_range(&rng, 0.1, 2),
                                       sbfx_rng_range(&rng, 0.1, 3));
        sbfx_ref_pixel px = pixel_through(sbfx_rng_range(&rng, -3, 3), sbfx_rng_range(&rng, -3, 3),
                                          -1, sbfx_rng_range(&rng, 0.5, 14), 0.3);
        CHECK(od(SBFX_OPACITY_DEFAULT, p, px) == od(SBFX_OPACITY_EXACT, p, px), "case %d", i);
    }
}

CHECK_TEST(spherical_matches_seed_formula)
{
    /* The seed's Opacity() (absolute form) and the relative form agree at moderate depths. */
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 11);
    for (int i = 0; i < 2000; i++) {
        double zc = sbfx_rng_range(&rng, 0.5, 20), r = sbfx_rng_range(&rng, 0.05, 3);
        double tau = sbfx_rng_range(&rng, 0.01, 5);
        double cx = sbfx_rng_range(&rng, -3, 3), cy = sbfx_rng_range(&rng, -3, 3);
        double qx = cx + sbfx_rng_range(&rng, -1.2, 1.2) * r, qy = cy + sbfx_rng_range(&rng, -1.2, 1.2) * r;
        double zs = sbfx_rng_uniform(&rng) < 0.2 ? INFINITY : sbfx_rng_range(&rng, 0.1, 25);
        double n = sbfx_rng_range(&rng, 0.05, 2);
        sbfx_ref_particle p = particle(cx, cy, -zc, r, tau);
        sbfx_ref_pixel px = pixel_through(qx, qy, -zc, zs, n);
        double d = hypot(qx - cx, qy - cy), want = 0;
        if (d < r) {
            double w = sqrt(r * r - d * d);
            double ds = fmin(zs, zc + w) - fmax(n, zc - w);
            if (ds > 0) want = tau * (1 - d / r) * ds;
        }
        CHECK(fabs(od(SBFX_OPACITY_SPHERICAL, p, px) - want) <= 1e-12 * (1 + want), "case %d: %g vs %g",
              i, od(SBFX_OPACITY_SPHERICAL, p, px), want);
    }
}

CHECK_TEST(planar_is_full_chord_with_depth_test_and_near_clip)
{
    sbfx_ref_particle p = particle(0.2, 0.1, -5, 1.0, 0.5);
    sbfx_ref_pixel px = pixel_through(0.5, 0.1, -5, INFINITY, 0.1);
    double d = 0.3, w = sqrt(1 - d * d);
    CHECK_NEAR(od(SBFX_OPACITY_PLANAR, p, px), 0.5 * (1 - d) * 2 * w, 1e-14);
    /* Opaque surface just behind the plane: drawn in full (the clipping artifact's bright side). */
    px.opaque_depth = 5.01;
    CHECK_NEAR(od(SBFX_OPACITY_PLANAR, p, px), 0.5 * (1 - d) * 2 * w, 1e-14);
    /* ...just in front of it: not drawn at all. */
    px.opaque_depth = 4.99;
    CHECK(od(SBFX_OPACITY_PLANAR, p, px) == 0.0);
    /* Near plane just past the plane: popped out although most of the sphere is visible. */
    px.opaque_depth = INFINITY;
    px.near = 5.01;
    CHECK(od(SBFX_OPACITY_PLANAR, p, px) == 0.0);
    CHECK(od(SBFX_OPACITY_SPHERICAL, p, px) > 0.0);
}

CHECK_TEST(soft_fade_curve)
{
    CHECK(sbfx_ref_soft_fade(0.0, 2.0) == 0.0);
    CHECK_NEAR(sbfx_ref_soft_fade(0.5, 2.0), 0.5, 1e-15);
    CHECK(sbfx_ref_soft_fade(1.0, 2.0) == 1.0);
    CHECK(sbfx_ref_soft_fade(-3.0, 2.0) == 0.0);
    CHECK(sbfx_ref_soft_fade(7.0, 2.0) == 1.0);
    CHECK(sbfx_ref_soft_fade(NAN, 2.0) == 0.0);
    CHECK(sbfx_ref_soft_fade(INFINITY, 2.0) == 1.0);
    CHECK_NEAR(sbfx_ref_soft_fade(0.25, 2.0), 0.125, 1e-15);
    CHECK_NEAR(sbfx_ref_soft_fade(0.3, 1.0), 0.3, 1e-15);           /* p = 1: linear */
    CHECK_NEAR(sbfx_ref_soft_fade(0.3, NAN), 0.3, 1e-15);           /* degenerate power */
    double prev = -1;
    for (int i = 0; i <= 1000; i++) {
        double x = i / 1000.0, f = sbfx_ref_soft_fade(x, 2.0);
        CHECK(f >= prev, "not monotone at %g", x);
        CHECK_NEAR(f + sbfx_ref_soft_fade(1 - x, 2.0), 1.0, 1e-14); /* S-curve symmetry */
        prev = f;
    }
}

CHECK_TEST(soft_is_planar_times_fade)
{
    sbfx_ref_particle p = particle(0, 0, -5, 1.0, 0.5);
    sbfx_ref_pixel px = pixel_through(0.3, 0, -5, INFINITY, 0.1);
    double planar = alpha(SBFX_OPACITY_PLANAR, p, px);
    CHECK_NEAR(alpha(SBFX_OPACITY_SOFT, p, px), planar, 1e-15); /* nothing opaque: no fade */
    for (double zs = 4.0; zs <= 7.0; zs += 0.125) {
        px.opaque_depth = zs;
        px.soft_scale = 0.0; /* <= 0: the radius */
        CHECK_NEAR(alpha(SBFX_OPACITY_SOFT, p, px), planar * sbfx_ref_soft_fade((zs - 5) / 1.0, 2), 1e-15);
        px.soft_scale = 0.5;
        CHECK_NEAR(alpha(SBFX_OPACITY_SOFT, p, px), planar * sbfx_ref_soft_fade((zs - 5) / 0.5, 2), 1e-15);
        double a = alpha(SBFX_OPACITY_SOFT, p, px);
        CHECK_NEAR(od(SBFX_OPACITY_SOFT, p, px), a < 1 ? -log1p(-a) : 1e30, 1e-13);
    }
    px.opaque_depth = INFINITY;
    px.near = 5.5; /* the billboard plane is in front of the near plane: popped, as planar */
    CHECK(alpha(SBFX_OPACITY_SOFT, p, px) == 0.0);
}

CHECK_TEST(alpha_is_minus_expm1_of_optical_depth)
{
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 3);
    sbfx_opacity_mode modes[3] = {SBFX_OPACITY_PLANAR, SBFX_OPACITY_SPHERICAL, SBFX_OPACITY_EXACT};
    for (int i = 0; i < 3000; i++) {
        sbfx_ref_particle p = particle(sbfx_rng_range(&rng, -1, 1), sbfx_rng_range(&rng, -1, 1),
                                       sbfx_rng_range(&rng, -8, -0.5), sbfx_rng_range(&rng, 0.05, 2),
                                       exp(sbfx_rng_range(&rng, -10, 6)));
        sbfx_ref_pixel px = pixel_through(sbfx_rng_range(&rng, -2, 2), sbfx_rng_range(&rng, -2, 2),
                                          -1, sbfx_rng_range(&rng, 0.5, 10), 0.2);
        for (int m = 0; m < 3; m++) {
            double o = od(modes[m], p, px), a = alpha(modes[m], p, px);
            CHECK(a == -expm1(-o), "mode %d case %d", modes[m], i);
            CHECK(a >= 0 && a <= 1);
        }
    }
}

/* ---- chord integral ---------------------------------------------------------------------- */

static long double chord_f(long double h, long double u)
{
    return sqrtl(h + u * u);
}

/* Adaptive Simpson in long double: the integrand has a near-kink of width sqrt(h) at 0. */
static long double adaptive_simpson(long double h, long double a, long double b, long double fa,
                                    long double fm, long double fb, long double whole,
                                    long double tol, int depth)
{
    long double m = 0.5L * (a + b), lm = 0.5L * (a + m), rm = 0.5L * (m + b);
    long double flm = chord_f(h, lm), frm = chord_f(h, rm);
    long double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
    long double diff = left + right - whole;
    if (depth <= 0 || fabsl(diff) <= 15 * tol) return left + right + diff / 15;
    return adaptive_simpson(h, a, m, fa, flm, fm, left, tol / 2, depth - 1) +
           adaptive_simpson(h, m, b, fm, frm, fb, right, tol / 2, depth - 1);
}

static long double chord_numeric(long double h, long double a, long double b)
{
    if (a > b) return -chord_numeric(h, b, a);
    if (a < 0 && b > 0) return chord_numeric(h, a, 0) + chord_numeric(h, 0, b);
    long double fa = chord_f(h, a), fb = chord_f(h, b), fm = chord_f(h, 0.5L * (a + b));
    long double whole = (b - a) / 6 * (fa + 4 * fm + fb);
    return adaptive_simpson(h, a, b, fa, fm, fb, whole, 1e-16L * (fabsl(whole) + 1e-30L), 40);
}

CHECK_TEST(chord_integral_vs_numeric)
{
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 5);
    double worst = 0;
    for (int i = 0; i < 400; i++) {
        double h = i % 4 == 0 ? 0.0 : pow(10.0, sbfx_rng_range(&rng, -12, 2));
        double a = sbfx_rng_range(&rng, -5, 5), b = sbfx_rng_range(&rng, -5, 5);
        long double want = chord_numeric(h, a, b);
        double got = sbfx_ref_chord_integral(h, a, b);
        double e = fabs(got - (double)want) / (fabsl(want) + 1e-300);
        if (e > worst) worst = e;
        CHECK(e < 1e-10, "h %g a %g b %g: %.17g vs %.17Lg", h, a, b, got, want);
    }
    printf("# chord integral vs adaptive Simpson (long double): max rel err %.3g\n", worst);
    /* Closed forms. */
    CHECK_NEAR(sbfx_ref_chord_integral(0, -2, 3), (9 + 4) / 2.0, 1e-14);
    CHECK_NEAR(sbfx_ref_chord_integral(1, 0, 1), 0.5 * (sqrt(2) + asinh(1)), 1e-15);
    CHECK(sbfx_ref_chord_integral(2, 1, 1) == 0.0);
    CHECK_NEAR(sbfx_ref_chord_integral(2, 3, 1), -sbfx_ref_chord_integral(2, 1, 3), 1e-15);
}

CHECK_TEST(chord_integral_h_to_zero)
{
    /* h·asinh(u/√h) -> 0: the value approaches ½(b|b| - a|a|) smoothly, never inf/NaN. */
    double a = -0.7, b = 1.3, limit = 0.5 * (b * fabs(b) - a * fabs(a));
    double hs[] = {1e-2, 1e-8, 1e-20, 1e-100, 1e-300, DBL_MIN, 4.9406564584124654e-324, 0.0};
    double prev_err = INFINITY;
    for (size_t i = 0; i < sizeof hs / sizeof hs[0]; i++) {
        double v = sbfx_ref_chord_integral(hs[i], a, b);
        CHECK_FINITE(v);
        double e = fabs(v - limit);
        CHECK(e <= prev_err, "not converging at h = %g: err %g", hs[i], e);
        prev_err = e;
    }
    CHECK(sbfx_ref_chord_integral(0.0, a, b) == limit);
    /* Huge u / √h ratio (the asinh argument would overflow). */
    CHECK_FINITE(sbfx_ref_chord_integral(1e-320, 0, 1e10));
    CHECK_NEAR(sbfx_ref_chord_integral(1e-320, 0, 1e10), 0.5e20, 1e6);
    /* Out-of-contract inputs stay finite. */
    CHECK(sbfx_ref_chord_integral(NAN, 0, 1) == 0.0);
    CHECK(sbfx_ref_chord_integral(1, 0, INFINITY) == 0.0);
    CHECK(sbfx_ref_chord_integral(1e-300, -1e300, 1e300) == 0.0); /* beyond the double range */
    CHECK_FINITE(sbfx_ref_chord_integral(DBL_MIN, 0, 1e150));
    CHECK_NEAR(sbfx_ref_chord_integral(-1, 0, 2), 2.0, 1e-15); /* h < 0 taken as 0 */
}

/* ---- exact mode against brute force -------------------------------------------------------- */

CHECK_TEST(exact_vs_bruteforce_random)
{
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 20240601);
    double worst = 0;
    int tested = 0;
    for (int i = 0; i < 300; i++) {
        double zc = sbfx_rng_range(&rng, 0.2, 30);
        double r = sbfx_rng_range(&rng, 0.05, 1) * (i % 5 == 0 ? 3 * zc : 0.5 * zc);
        sbfx_ref_particle p = particle(sbfx_rng_range(&rng, -0.5, 0.5) * zc,
                                       sbfx_rng_range(&rng, -0.5, 0.5) * zc, -zc, r,
                                       exp(sbfx_rng_range(&rng, -3, 2)));
        /* Aim at a random point of the ball, so most rays hit. */
        double aim[3];
        for (int k = 0; k < 3; k++) aim[k] = p.center[k] + sbfx_rng_range(&rng, -1, 1) * r;
        if (aim[2] > -0.01) aim[2] = -0.01;
        double near = sbfx_rng_range(&rng, 0.01, 1.0);
        double zs;
        switch (i % 4) {
        case 0: zs = INFINITY; break;                                      /* far clear value */
        case 1: zs = zc + sbfx_rng_range(&rng, -1, 1) * r; break;          /* inside the ball */
        case 2: zs = sbfx_rng_range(&rng, near, zc + 2 * r); break;
        default: zs = 1000.0; break;                                       /* the far plane */
        }
        sbfx_ref_pixel px = pixel_through(aim[0], aim[1], aim[2], zs, near);
        double got = od(SBFX_OPACITY_EXACT, p, px);
        long double want = brute_exact(p, px, 100000);
        CHECK_FINITE(got);
        if (want < 1e-12L * p.tau * r) { /* no segment (or a negligible one) */
            CHECK(got <= 1e-9 * p.tau * r, "case %d: got %g, brute force %Lg", i, got, want);
            continue;
        }
        tested++;
        double e = fabs(got - (double)want) / (double)want;
        if (e > worst) worst = e;
        CHECK(e < 1e-6, "case %d: exact %.12g, brute force %.12Lg, rel err %.3g", i, got, want, e);
    }
    printf("# exact vs 1e5-sample midpoint brute force: %d rays, max rel err %.3g\n", tested, worst);
    CHECK(tested > 150, "only %d rays hit", tested);
}

CHECK_TEST(exact_grazing_ray_uses_stable_form)
{
    /* d -> r from below, unclipped, compared with the cancellation-free closed form in long
     * double down to d = r(1 - 1e-15). The naive closed form would lose all digits here.
     * First along the axis with the centre moved sideways: the ray–centre distance is exactly d,
     * so any error is the integral's own. */
    double r = 0.8, zc = 6, tau = 1.3, worst = 0;
    for (int k = 1; k <= 15; k++) {
        double d = r * (1 - pow(10.0, -k));
        sbfx_ref_particle p = particle(d, 0, -zc, r, tau);
        sbfx_ref_pixel px = {{0, 0, -1}, INFINITY, 0.1, 0};
        long double want = exact_full_chord(tau, r, d);
        double got = od(SBFX_OPACITY_EXACT, p, px);
        double e = fabs(got - (double)want) / (double)want;
        if (e > worst) worst = e;
        CHECK(e < 1e-12, "1 - d/r = 1e-%d: exact %.17g, want %.17Lg, rel err %.3g", k, got, want, e);
    }
    printf("# exact grazing rays, exact geometry (1 - d/r = 1e-1 .. 1e-15): max rel err %.3g\n", worst);
    /* Then an oblique ray: now the distance itself carries the rounding of c - t0 u, about
     * 1e-16 * zc absolute, and the optical depth ~ (r - d)^{3/2} amplifies it by
     * 1.5 * 1e-16 * zc / (r - d): that is the conditioning of the problem, not of the integral. */
    worst = 0;
    for (int k = 1; k <= 15; k++) {
        double d = r * (1 - pow(10.0, -k));
        sbfx_ref_particle p = particle(0, 0, -zc, r, tau);
        double s = d / zc, c = sqrt(1 - s * s); /* ray at angle θ, sin θ = d / zc */
        sbfx_ref_pixel px = {{s / c, 0, -1}, INFINITY, 0.1, 0};
        long double t = px.ray[0], dist = (long double)zc * t / sqrtl(1 + t * t);
        long double want = exact_full_chord(tau, r, dist);
        double got = od(SBFX_OPACITY_EXACT, p, px);
        double e = fabs(got - (double)want) / (double)want;
        double allowed = 1e-12 + 4e-15 * zc / (r - d);
        printf("#   oblique, 1 - d/r = 1e-%02d: rel err %.3g (conditioning bound %.3g)\n", k, e, allowed);
        CHECK(e < allowed, "1 - d/r = 1e-%d: exact %.17g, want %.17Lg, rel err %.3g", k, got, want, e);
        CHECK_FINITE(got);
    }
}

CHECK_TEST(exact_quadrature_and_closed_form_agree_at_switch)
{
    /* The closed form is used while the mean density of the clipped chord is > 5% of the
     * centre's; the quadrature below that. Rays around the switch must agree with brute force. */
    sbfx_ref_particle p = particle(0, 0, -4, 1.0, 1.0);
    double worst = 0, worst_analytic = 0;
    for (int i = 0; i <= 60; i++) {
        double d = 0.80 + 0.0025 * i; /* mean density of the full chord crosses 5% near d ~ 0.93 */
        /* A ray at angle θ from the axis, sin θ = d / 4, passes at distance d. */
        sbfx_ref_pixel px = pixel_through(4 * d / sqrt(16 - d * d), 0, -4, INFINITY, 0.1);
        double got = od(SBFX_OPACITY_EXACT, p, px);
        long double want = brute_exact(p, px, 100000);
        double e = fabs(got - (double)want) / (double)want;
        if (e > worst) worst = e;
        CHECK(e < 1e-6, "d %g: %.15g vs %.15Lg", d, got, want);
        /* Unclipped, so the cancellation-free long-double closed form applies too. */
        long double t = px.ray[0], dist = 4 * t / sqrtl(1 + t * t);
        long double analytic = exact_full_chord(1.0, 1.0, dist);
        double e2 = fabs(got - (double)analytic) / (double)analytic;
        if (e2 > worst_analytic) worst_analytic = e2;
        CHECK(e2 < 1e-12, "d %g: %.17g vs analytic %.17Lg", d, got, analytic);
    }
    printf("# exact around the closed-form/quadrature switch: max rel err %.3g vs brute force, "
           "%.3g vs analytic\n", worst, worst_analytic);
}

CHECK_TEST(far_small_particle_relative_form)
{
    /* zc = 1e4, r = 0.05 (docs/design.md §2.2). Spherical: d and the clipped chord are known exactly;
     * exact: long-double analytic value. */
    double zc = 1e4, r = 0.05, tau = 0.4, off = 0.03;
    sbfx_ref_particle p = particle(0, 0, -zc, r, tau);
    sbfx_ref_pixel px = pixel_through(off, 0, -zc, INFINITY, 0.1);
    double w = sqrt((r - off) * (r + off));
    CHECK(rel_err(od(SBFX_OPACITY_SPHERICAL, p, px), tau * (1 - off / r) * 2 * w) < 1e-12);
    /* Opaque surface 1 cm behind the centre: only zc - w .. zc + 0.01 counts. */
    px.opaque_depth = zc + 0.01;
    CHECK(rel_err(od(SBFX_OPACITY_SPHERICAL, p, px), tau * (1 - off / r) * (w + 0.01)) < 1e-9,
          "%.17g vs %.17g", od(SBFX_OPACITY_SPHERICAL, p, px), tau * (1 - off / r) * (w + 0.01));
    /* Exact, unclipped. */
    px.opaque_depth = INFINITY;
    long double t = px.ray[0]; /* the ray as given, tan of its angle to the axis */
    long double dist = (long double)zc * t / sqrtl(1 + t * t);
    long double want = exact_full_chord(tau, r, dist);
    double got = od(SBFX_OPACITY_EXACT, p, px);
    CHECK(rel_err(got, (double)want) < 1e-9, "%.17g vs %.17Lg", got, want);
    printf("# zc=1e4 r=0.05: exact %.15g, analytic %.15Lg, rel err %.3g\n", got, want,
           rel_err(got, (double)want));
    /* Exact, clipped by a surface through the centre's depth: brute force (fine samples). */
    px.opaque_depth = zc;
    long double brute = brute_exact(p, px, 100000);
    got = od(SBFX_OPACITY_EXACT, p, px);
    CHECK(rel_err(got, (double)brute) < 1e-6, "%.17g vs %.17Lg", got, brute);
    /* Through the centre, far away: still τr and 2τr. */
    px = pixel_through(0, 0, -zc, INFINITY, 0.1);
    CHECK(rel_err(od(SBFX_OPACITY_EXACT, p, px), tau * r) < 1e-12);
    CHECK(rel_err(od(SBFX_OPACITY_SPHERICAL, p, px), 2 * tau * r) < 1e-12);
    check_sane(p, px, "far");
}

/* ---- hard cases of docs/design.md §2.2 ------------------------------------------------------- */

CHECK_TEST(d_to_r_from_below)
{
    /* zc = 4 (a power of two) so that Q = ray * zc reproduces d exactly. */
    double r = 1.0, prev_sph = INFINITY, prev_ex = INFINITY;
    for (int k = 1; k <= 17; k++) {
        double d = r * (1 - pow(2.0, -3 * k));
        sbfx_ref_particle p = particle(0, 0, -4, r, 0.7);
        sbfx_ref_pixel px = pixel_through(d, 0, -4, INFINITY, 0.1);
        double s = od(SBFX_OPACITY_SPHERICAL, p, px), e = od(SBFX_OPACITY_EXACT, p, px);
        CHECK(isfinite(s) && s >= 0 && s <= prev_sph, "spherical %g at 1-d/r=2^-%d", s, 3 * k);
        CHECK(isfinite(e) && e >= 0 && e <= prev_ex, "exact %g at 1-d/r=2^-%d", e, 3 * k);
        /* Spherical's value is exact: 0.7 (1-d/r) 2 sqrt((r-d)(r+d)). */
        CHECK(rel_err(s, 0.7 * (r - d) / r * 2 * sqrt((r - d) * (r + d))) < 1e-13);
        check_sane(p, px, "d->r");
        prev_sph = s;
        prev_ex = e;
    }
    CHECK(prev_sph < 1e-20, "%g", prev_sph); /* ~ 2.8 (r-d)^{3/2} with r - d = 2^-51 */
}

CHECK_TEST(d_equal_and_beyond_r)
{
    sbfx_ref_particle p = particle(0, 0, -5, 1.0, 0.7);
    /* Spherical/planar/soft: d = |Q.xy - c.xy| exactly r, slightly more, far more. */
    double ds[] = {1.0, nextafter(1.0, 2.0), 1.0 + 1e-9, 2.0, 1e300};
    for (size_t i = 0; i < sizeof ds / sizeof ds[0]; i++) {
        sbfx_ref_pixel px = pixel_through(ds[i], 0, -5, INFINITY, 0.1);
        CHECK(od(SBFX_OPACITY_SPHERICAL, p, px) == 0 && od(SBFX_OPACITY_PLANAR, p, px) == 0 &&
                  alpha(SBFX_OPACITY_SOFT, p, px) == 0,
              "d = %.17g", ds[i]);
        check_sane(p, px, "d>=r");
    }
    /* Exact: a ray tangent to the sphere (distance exactly r) or passing beyond it. */
    double s = 1.0 / 5.0, c = sqrt(1 - s * s);
    sbfx_ref_pixel px = {{s / c * 1.0000001, 0, -1}, INFINITY, 0.1, 0};
    CHECK(od(SBFX_OPACITY_EXACT, p, px) == 0);
    px.ray[0] = 3;
    check_all_zero(p, px, "far miss");
}

CHECK_TEST(radius_zero_negative_and_underflowing)
{
    double rs[] = {0.0, -0.0, -1.0, 1e-300, DBL_MIN, 4.9406564584124654e-324, 1e-160};
    for (size_t i = 0; i < sizeof rs / sizeof rs[0]; i++) {
        sbfx_ref_particle p = particle(0, 0, -5, rs[i], 0.4);
        sbfx_ref_pixel px = pixel_through(0, 0, -5, INFINITY, 0.1);
        check_all_zero(p, px, "tiny radius");
        p.tau = 1e300; /* even with absurd density */
        check_all_zero(p, px, "tiny radius, huge tau");
    }
    /* Small but representable radii keep working, and scale linearly (no underflow). */
    for (double r = 1e-3; r > 1e-150; r *= 1e-7) {
        sbfx_ref_particle p = particle(0, 0, -5, r, 1.0);
        sbfx_ref_pixel px = pixel_through(0, 0, -5, INFINITY, 0.1);
        CHECK(rel_err(od(SBFX_OPACITY_SPHERICAL, p, px), 2 * r) < 1e-12, "r %g", r);
        CHECK(rel_err(od(SBFX_OPACITY_EXACT, p, px), r) < 1e-9, "r %g: %g", r, od(SBFX_OPACITY_EXACT, p, px));
        check_sane(p, px, "small r");
    }
}

CHECK_TEST(camera_inside_sphere)
{
    /* F < n: the part of the chord in front of the near plane is cut off, no popping. */
    sbfx_ref_particle p = particle(0, 0, -0.5, 2.0, 0.6);
    sbfx_ref_pixel px = pixel_through(0.3, 0.2, -1, INFINITY, 0.1);
    double zc = 0.5, d = hypot(0.3 * 0.5, 0.2 * 0.5), w = sqrt(4 - d * d);
    CHECK(rel_err(od(SBFX_OPACITY_SPHERICAL, p, px), 0.6 * (1 - d / 2) * (zc + w - 0.1)) < 1e-13);
    double got = od(SBFX_OPACITY_EXACT, p, px);
    long double want = brute_exact(p, px, 100000);
    CHECK(rel_err(got, (double)want) < 1e-6, "%.15g vs %.15Lg", got, want);
    /* Less than the unclipped chord, more than 0. */
    CHECK(got > 0 && got < 0.6 * 2.0);
    /* Planar draws while its plane (zc = 0.5) is beyond the near plane, and pops out as soon as
     * the near plane passes it; spherical and exact keep what is left of the chord. */
    CHECK(od(SBFX_OPACITY_PLANAR, p, px) > 0);
    px.near = 0.6;
    CHECK(od(SBFX_OPACITY_PLANAR, p, px) == 0 && alpha(SBFX_OPACITY_SOFT, p, px) == 0);
    CHECK(od(SBFX_OPACITY_SPHERICAL, p, px) > 0 && od(SBFX_OPACITY_EXACT, p, px) > 0);
    check_sane(p, px, "inside");
}

CHECK_TEST(sphere_behind_camera)
{
    sbfx_ref_particle p = particle(0, 0, 5, 1.0, 0.6); /* centre at +5: behind */
    sbfx_ref_pixel px = pixel_through(0, 0, -1, INFINITY, 0.1);
    check_all_zero(p, px, "behind");
    px = pixel_through(0.3, -0.1, -1, INFINITY, 0.1);
    check_all_zero(p, px, "behind, off axis");
    /* Straddling the camera plane: only the part beyond the near plane counts. */
    p = particle(0, 0, 0.5, 1.0, 0.6);
    px = pixel_through(0, 0, -1, INFINITY, 0.1);
    CHECK(rel_err(od(SBFX_OPACITY_SPHERICAL, p, px), 0.6 * (0.5 - 0.1)) < 1e-13);
    double got = od(SBFX_OPACITY_EXACT, p, px);
    /* ∫_{0.6}^{1} (1 - s) ds along the axis (s = distance from the centre) = 0.08 */
    CHECK(rel_err(got, 0.6 * 0.08) < 1e-12, "%.17g", got);
    CHECK(od(SBFX_OPACITY_PLANAR, p, px) == 0 && alpha(SBFX_OPACITY_SOFT, p, px) == 0);
    /* Negative near is treated as 0: nothing behind the camera is seen. */
    px.near = -3;
    CHECK(rel_err(od(SBFX_OPACITY_SPHERICAL, p, px), 0.6 * 0.5) < 1e-13);
}

CHECK_TEST(opaque_surface_in_front_of_sphere)
{
    /* Z_s < F: Δs = 0 in every mode. */
    sbfx_ref_particle p = particle(0.1, 0, -5, 1.0, 0.6);
    sbfx_ref_pixel px = pixel_through(0.2, 0.1, -5, 3.5, 0.1);
    check_all_zero(p, px, "wall in front");
    /* Just in front of the sphere along the ray through the centre. */
    px = pixel_through(0.1, 0, -5, 4.0 - 1e-9, 0.1);
    CHECK(od(SBFX_OPACITY_SPHERICAL, p, px) == 0 && od(SBFX_OPACITY_EXACT, p, px) == 0);
    px.opaque_depth = -INFINITY;
    check_all_zero(p, px, "wall at -inf");
    px.opaque_depth = 0.0;
    check_all_zero(p, px, "wall at 0");
}

CHECK_TEST(opaque_surface_inside_sphere)
{
    /* Z_s = z_c: half the chord. Exact through the centre: half of τr. */
    sbfx_ref_particle p = particle(0, 0, -5, 1.0, 0.6);
    sbfx_ref_pixel px = pixel_through(0, 0, -5, 5.0, 0.1);
    CHECK(rel_err(od(SBFX_OPACITY_SPHERICAL, p, px), 0.6) < 1e-14);
    CHECK(rel_err(od(SBFX_OPACITY_EXACT, p, px), 0.3) < 1e-14);
    /* Anywhere inside: spherical = τ(1-d/r)(Zs - F). */
    px = pixel_through(0.4, 0, -5, 5.3, 0.1);
    double w = sqrt(1 - 0.16);
    CHECK(rel_err(od(SBFX_OPACITY_SPHERICAL, p, px), 0.6 * 0.6 * (0.3 + w)) < 1e-13);
    long double want = brute_exact(p, px, 100000);
    CHECK(rel_err(od(SBFX_OPACITY_EXACT, p, px), (double)want) < 1e-6);
    /* Planar draws the whole chord because the plane is in front of Zs: the clipping artifact. */
    CHECK(rel_err(od(SBFX_OPACITY_PLANAR, p, px), 0.6 * 0.6 * 2 * w) < 1e-13);
}

CHECK_TEST(particle_fully_behind_opaque_wall)
{
    sbfx_ref_particle p = particle(0.5, -0.2, -20, 2.0, 3.0);
    for (int i = 0; i < 50; i++) {
        sbfx_ref_pixel px = pixel_through(0.5 + 0.07 * (i - 25), -0.2, -20, 10.0, 0.1);
        for (int m = 0; m < ALL_MODES_N; m++)
            CHECK(alpha(all_modes[m], p, px) == 0.0, "mode %d pixel %d", all_modes[m], i);
    }
}

CHECK_TEST(depth_at_far_clear_value)
{
    /* The depth texture cleared to the far plane (or +inf): same as no opaque surface. */
    sbfx_ref_particle p = particle(0.3, 0.1, -15, 1.2, 0.5);
    sbfx_ref_pixel far = pixel_through(0.5, 0.0, -15, 1000.0, 0.1);
    sbfx_ref_pixel inf = far;
    inf.opaque_depth = INFINITY;
    for (int m = 0; m < ALL_MODES_N; m++) {
        CHECK(alpha(all_modes[m], p, inf) > 0);
        CHECK_NEAR(alpha(all_modes[m], p, far), alpha(all_modes[m], p, inf), 1e-15);
    }
    check_sane(p, inf, "Zs=+inf");
    inf.opaque_depth = DBL_MAX;
    check_sane(p, inf, "Zs=DBL_MAX");
}

CHECK_TEST(tau_zero_and_huge)
{
    sbfx_ref_particle p = particle(0, 0, -5, 1.0, 0.0);
    sbfx_ref_pixel px = pixel_through(0.2, 0, -5, INFINITY, 0.1);
    check_all_zero(p, px, "tau 0");
    p.tau = -1;
    check_all_zero(p, px, "tau < 0");
    p.tau = 1e6;
    for (int m = 0; m < ALL_MODES_N; m++) {
        CHECK(alpha(all_modes[m], p, px) == 1.0, "mode %d: %.17g", all_modes[m], alpha(all_modes[m], p, px));
        CHECK_FINITE(od(all_modes[m], p, px));
    }
    p.tau = 1e300;
    p.radius = 1e200;
    p.center[2] = -1e200;
    px.opaque_depth = INFINITY;
    for (int m = 0; m < ALL_MODES_N; m++) {
        double o = od(all_modes[m], p, px);
        CHECK(isfinite(o) && o <= 1e30, "mode %d od %g", all_modes[m], o);
    }
    check_sane(p, px, "tau 1e300");
    /* Grazing edge with huge tau: alpha rises continuously from 0 to 1, never NaN. */
    p = particle(0, 0, -5, 1.0, 1e6);
    for (int k = 1; k <= 16; k++) {
        px = pixel_through(1 - pow(10.0, -k), 0, -5, INFINITY, 0.1);
        check_sane(p, px, "tau 1e6 grazing");
    }
}

CHECK_TEST(nan_inf_inputs_give_zero)
{
    const double bad[] = {NAN, INFINITY, -INFINITY};
    sbfx_ref_particle good_p = particle(0, 0, -5, 1.0, 0.5);
    sbfx_ref_pixel good_px = pixel_through(0.1, 0.1, -5, 6.0, 0.1);
    good_px.soft_scale = 0.5;
    for (int m = 0; m < ALL_MODES_N; m++)
        CHECK(alpha(all_modes[m], good_p, good_px) > 0, "mode %d", all_modes[m]);
    for (size_t b = 0; b < 3; b++) {
        for (int f = 0; f < 5; f++) {
            sbfx_ref_particle p = good_p;
            if (f < 3) p.center[f] = bad[b];
            else if (f == 3) p.radius = bad[b];
            else p.tau = bad[b];
            check_all_zero(p, good_px, "bad particle field");
        }
        for (int f = 0; f < 6; f++) {
            sbfx_ref_pixel px = good_px;
            if (f < 3) px.ray[f] = bad[b];
            else if (f == 3) px.near = bad[b];
            else if (f == 4) px.soft_scale = bad[b];
            else if (isnan(bad[b])) px.opaque_depth = bad[b]; /* +inf is a valid depth */
            else continue;
            check_all_zero(good_p, px, "bad pixel field");
        }
    }
    /* NULL pointers. */
    for (int m = 0; m < ALL_MODES_N; m++) {
        CHECK(sbfx_ref_opacity(all_modes[m], NULL, &good_px) == 0);
        CHECK(sbfx_ref_optical_depth(all_modes[m], &good_p, NULL) == 0);
    }
    /* A ray that does not go forward. */
    good_px.ray[2] = 0;
    check_all_zero(good_p, good_px, "ray z = 0");
    good_px.ray[2] = 1;
    check_all_zero(good_p, good_px, "ray z = +1");
}

CHECK_TEST(ray_scale_is_irrelevant)
{
    sbfx_ref_particle p = particle(0.4, -0.3, -6, 1.1, 0.9);
    sbfx_ref_pixel px = pixel_through(0.7, -0.1, -6, 6.4, 0.2), scaled = px;
    for (int k = 0; k < 3; k++) scaled.ray[k] *= 2.5;
    for (int m = 0; m < ALL_MODES_N; m++)
        CHECK(rel_err(od(all_modes[m], p, scaled), od(all_modes[m], p, px)) < 1e-14, "mode %d", all_modes[m]);
}

/* ---- continuity: the fixes for popping and clipping ---------------------------------------- */

/* Largest |alpha(x + step) - alpha(x)| as `set` moves a parameter from lo to hi. */
typedef void (*setter)(sbfx_ref_pixel *px, double x);
static void set_near(sbfx_ref_pixel *px, double x) { px->near = x; }
static void set_depth(sbfx_ref_pixel *px, double x) { px->opaque_depth = x; }

static double max_jump(sbfx_opacity_mode m, sbfx_ref_particle p, sbfx_ref_pixel px, setter set,
                       double lo, double hi, int steps)
{
    double prev = 0, worst = 0;
    for (int i = 0; i <= steps; i++) {
        set(&px, lo + (hi - lo) * i / steps);
        double a = alpha(m, p, px);
        if (i > 0 && fabs(a - prev) > worst) worst = fabs(a - prev);
        prev = a;
    }
    return worst;
}

CHECK_TEST(near_plane_sweep_is_continuous)
{
    /* Camera moving through the particle = near plane sweeping through it. dα/dn <= τ, so a step
     * of 1e-4 can change alpha by at most τ·1e-4 (spherical: τ(1-d/r), exact: τ(1-|x-c|/r)/cos). */
    sbfx_ref_particle p = particle(0.2, 0.1, -5, 1.0, 2.0);
    sbfx_ref_pixel px = pixel_through(0.35, 0.05, -5, INFINITY, 0.1);
    double step = 2.4 / 24000;
    double js = max_jump(SBFX_OPACITY_SPHERICAL, p, px, set_near, 3.8, 6.2, 24000);
    double je = max_jump(SBFX_OPACITY_EXACT, p, px, set_near, 3.8, 6.2, 24000);
    double jp = max_jump(SBFX_OPACITY_PLANAR, p, px, set_near, 3.8, 6.2, 24000);
    printf("# near sweep, step %.2g: max jump spherical %.3g, exact %.3g, planar %.3g (pops)\n",
           step, js, je, jp);
    CHECK(js <= 2.0 * step * 1.0001, "spherical jump %g", js);
    CHECK(je <= 2.0 * step * 1.01, "exact jump %g", je);
    CHECK(jp > 0.5, "planar should pop: %g", jp); /* the artifact the spherical mode fixes */
}

CHECK_TEST(opaque_depth_sweep_is_continuous)
{
    /* An opaque surface moving through the particle (the clipping artifact). */
    sbfx_ref_particle p = particle(0.2, 0.1, -5, 1.0, 2.0);
    sbfx_ref_pixel px = pixel_through(0.35, 0.05, -5, INFINITY, 0.1);
    double step = 2.4 / 24000;
    double js = max_jump(SBFX_OPACITY_SPHERICAL, p, px, set_depth, 3.8, 6.2, 24000);
    double je = max_jump(SBFX_OPACITY_EXACT, p, px, set_depth, 3.8, 6.2, 24000);
    double jp = max_jump(SBFX_OPACITY_PLANAR, p, px, set_depth, 3.8, 6.2, 24000);
    double jsoft = max_jump(SBFX_OPACITY_SOFT, p, px, set_depth, 3.8, 6.2, 24000);
    printf("# depth sweep, step %.2g: max jump spherical %.3g, exact %.3g, soft %.3g, planar %.3g\n",
           step, js, je, jsoft, jp);
    CHECK(js <= 2.0 * step * 1.0001, "spherical jump %g", js);
    CHECK(je <= 2.0 * step * 1.01, "exact jump %g", je);
    CHECK(jsoft < 0.01, "soft jump %g", jsoft);
    CHECK(jp > 0.5, "planar should clip hard: %g", jp);
}

CHECK_TEST(random_fuzz_never_nan)
{
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 99);
    const double specials[] = {0.0, -0.0, 1e-320, 1e-300, 1e-30, 1.0, 1e30, 1e300, -1e300,
                               DBL_MAX, -DBL_MAX, INFINITY, -INFINITY, NAN};
    const int ns = (int)(sizeof specials / sizeof specials[0]);
    for (int i = 0; i < 100000; i++) {
        double v[11];
        for (int k = 0; k < 11; k++) {
            double u = sbfx_rng_uniform(&rng);
            if (u < 0.15) v[k] = specials[sbfx_rng_u32(&rng) % ns];
            else v[k] = sbfx_rng_range(&rng, -1, 1) * pow(10.0, sbfx_rng_range(&rng, -5, 5));
        }
        sbfx_ref_particle p = {{v[0], v[1], v[2]}, fabs(v[3]), fabs(v[4])};
        sbfx_ref_pixel px = {{v[5], v[6], -fabs(v[7])}, fabs(v[8]), v[9], v[10]};
        for (int m = 0; m < ALL_MODES_N; m++) {
            double a = alpha(all_modes[m], p, px), o = od(all_modes[m], p, px);
            if (!(isfinite(a) && a >= 0 && a <= 1 && isfinite(o) && o >= 0 && o <= 1e30)) {
                CHECK(0, "case %d mode %d: alpha %g od %g", i, all_modes[m], a, o);
                return;
            }
        }
    }
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
