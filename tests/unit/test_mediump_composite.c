/* The composite's half-precision arithmetic (shaders_es/composite.frag, docs/gpus.md "Precision"),
 * emulated with _Float16 exactly where the shader declares mediump, against double. llvmpipe
 * computes mediump at full precision, so the GL suites cannot see these roundings; this bounds
 * them. Each half operation is done in double (exact for a product or a sum of two halves) and
 * rounded to _Float16 once, as an IEEE half unit does. u = 2^-11, half's unit roundoff.
 *   fetch + clamp:    the texel as stored in RGBA16F (exact), light clamped to [0, 65504],
 *                     transmittance to [0, 1] (1 where it is NaN); after the weighted sum, one NaN
 *                     test on (r + b) + (g + a) of the sum (sanitize)
 *   bilinear weights: each rounded to half once (the function returns mediump)
 *   upsample:         sum = t0 w0; sum += t1 w1; sum += t2 w2; sum += t3 w3, every product and
 *                     sum rounded to half
 * Bound: four weights (1 rounding each), four products (1 each), three sums (1 each): every
 * term of the non-negative sum passes through at most 5 roundings, so
 *     |sum_half - sum_double| <= gamma(5) sum_double + 2^-25 (1.01 sum_k t_k + 7)
 * gamma(n) = n u / (1 - n u); the second term is half's subnormal range (spacing 2^-24): a weight
 * below 2^-14 is rounded to within 2^-25 absolute, which a texel up to 65504 multiplies, and
 * each of the 7 operations may land there. For sbfx's divisors (1, 2, 4, 8) every weight is
 * (odd / 2d)(odd / 2d) or 0 or 1, exact in half, and the bound is gamma(4) sum_double. */
#include <math.h>
#include <stdint.h>
#include "check.h"
#include "tables/tables.h"

#define CASES 200000
#define UNIT_ROUNDOFF 4.8828125e-4                 /* 2^-11 */
#define SUBNORMAL_HALF_ULP 2.98023223876953125e-8  /* 2^-25 */
#define HALF_MAX 65504.0

typedef _Float16 half;

static half mul(half a, half b) { return (half)((double)a * (double)b); }
static half add(half a, half b) { return (half)((double)a + (double)b); }

/* composite.frag's clamp_texel(): light to [0, 65504] (a NaN passes on, as a GPU whose min and
 * max propagate NaN does), transmittance to [0, 1] and 1 where it is not a number or below 0 */
static void clamp_texel(half p[4])
{
    for (int k = 0; k < 3; k++) {
        double v = (double)p[k];
        p[k] = (half)(v < 0.0 ? 0.0 : v > HALF_MAX ? HALF_MAX : v);
    }
    double a = (double)p[3];
    p[3] = (half)(a >= 0.0 ? fmin(a, 1.0) : 1.0);
}

/* composite.frag's sanitize(), on the weighted sum: true when it is replaced by transparent */
static bool sanitize(half p[4])
{
    half pair0 = add(p[0], p[2]), pair1 = add(p[1], p[3]);
    if (isnan((double)add(pair0, pair1))) {
        p[0] = p[1] = p[2] = (half)0.0, p[3] = (half)1.0;
        return true;
    }
    return false;
}

/* A texel as an RGBA16F target holds it: light spread over 10 decades, transmittance in [0, 1]. */
static void random_texel(sbfx_rng *rng, half p[4])
{
    for (int k = 0; k < 3; k++) p[k] = (half)pow(10.0, sbfx_rng_range(rng, -6.0, 4.8));
    p[3] = (half)sbfx_rng_range(rng, 0.0, 1.0);
}

static double gamma_n(int n) { return n * UNIT_ROUNDOFF / (1.0 - n * UNIT_ROUNDOFF); }

/* composite.frag's upsample() for channel k: the four texels' weighted sum in half, one running
 * sum (as the shader keeps it), and the same sum in double in *exact. */
static half weighted_sum(half t[4][4], const double w[4], int k, double *exact)
{
    half sum = mul(t[0][k], (half)w[0]);
    *exact = (double)t[0][k] * w[0];
    for (int c = 1; c < 4; c++) {
        sum = add(sum, mul(t[c][k], (half)w[c]));
        *exact += (double)t[c][k] * w[c];
    }
    return sum;
}

CHECK_TEST(upsample_within_half_rounding_bound)
{
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 2111);
    double worst_ratio = 0.0, worst_relative = 0.0;
    int over = 0, differ = 0;
    for (int i = 0; i < CASES; i++) {
        half t[4][4];
        for (int c = 0; c < 4; c++) random_texel(&rng, t[c]), clamp_texel(t[c]);
        double fx = sbfx_rng_range(&rng, 0.0, 1.0), fy = sbfx_rng_range(&rng, 0.0, 1.0);
        double w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
        for (int k = 0; k < 4; k++) {
            double exact;
            half sum = weighted_sum(t, w, k, &exact);
            double texels = (double)t[0][k] + (double)t[1][k] + (double)t[2][k] + (double)t[3][k];
            double err = fabs((double)sum - exact);
            double bound = gamma_n(5) * exact + SUBNORMAL_HALF_ULP * (1.01 * texels + 7.0);
            over += err > bound;
            differ += (double)sum != exact;
            worst_ratio = fmax(worst_ratio, err / bound);
            if (exact > 1e-3) worst_relative = fmax(worst_relative, err / exact);
        }
    }
    printf("# %d upsampled pixels x 4 channels: largest |half - double| / bound = %.3f, largest "
           "relative error %.2e (5u = %.2e, 7u = %.2e, one 8-bit level 3.9e-3)\n",
           CASES, worst_ratio, worst_relative, 5 * UNIT_ROUNDOFF, 7 * UNIT_ROUNDOFF);
    CHECK(over == 0, "%d channels exceed gamma(5) x sum + the subnormal term", over);
    CHECK(differ > 0, "the emulation rounded nothing (a test of the test)");
}

/* composite.frag's f at pixel x: low = (x + 0.5) / d - 0.5, f = low - floor(low). */
static double grid_fraction(double x, int d)
{
    double low = (x + 0.5) / d - 0.5;
    return low - floor(low);
}

/* At the divisors sbfx uses the weights are exact in half and the error is within gamma(4). */
CHECK_TEST(upsample_at_sbfx_divisors_within_gamma4)
{
    static const int divisors[] = {1, 2, 4, 8};
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 8);
    double worst_relative = 0.0;
    int over = 0;
    for (int i = 0; i < CASES; i++) {
        int d = divisors[i % 4];
        double fx = grid_fraction(floor(sbfx_rng_range(&rng, 0.0, 4096.0)), d);
        double fy = grid_fraction(floor(sbfx_rng_range(&rng, 0.0, 4096.0)), d);
        double w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
        half t[4][4];
        for (int c = 0; c < 4; c++) {
            random_texel(&rng, t[c]), clamp_texel(t[c]);
            CHECK((double)(half)w[c] == w[c], "divisor %d: weight %g not exact in half", d, w[c]);
        }
        for (int k = 0; k < 4; k++) {
            double exact;
            half sum = weighted_sum(t, w, k, &exact);
            double err = fabs((double)sum - exact);
            over += err > gamma_n(4) * exact + 7.0 * SUBNORMAL_HALF_ULP;
            if (exact > 1e-3) worst_relative = fmax(worst_relative, err / exact);
        }
    }
    printf("# divisors 1, 2, 4, 8: largest relative error %.2e (4u = %.2e)\n", worst_relative, 4 * UNIT_ROUNDOFF);
    CHECK(over == 0, "%d channels exceed gamma(4)", over);
}

/* The four texels clamped, weighted and summed, then one test on the sum's (r + b) + (g + a): a
 * NaN light in any texel reaches the sum (every weight times a clamped texel is finite, 0 where
 * the weight is 0) and the pixel is dropped (transparent); a NaN transmittance is 1 (the scene
 * shows through); Inf is clamped; and no finite texels are taken for a NaN: non-negative halves
 * only overflow to +Inf when summed, never to NaN. The output is never NaN. */
CHECK_TEST(sanitize_finds_every_nan_and_only_nans)
{
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 77);
    int missed = 0, false_alarms = 0;
    for (int i = 0; i < CASES / 4; i++) {
        half t[4][4];
        bool light_nan = false;
        for (int c = 0; c < 4; c++) {
            half *p = t[c];
            int j = 4 * i + c;
            random_texel(&rng, p);
            if (j % 11 == 0) p[j % 4] = (half)NAN;
            if (j % 5 == 0) p[(j / 5) % 4] = (half)HALF_MAX;   /* sums that overflow half */
            if (j % 7 == 0) p[(j / 7) % 3] = (half)INFINITY;   /* clamped, not dropped */
            for (int k = 0; k < 3; k++) light_nan = light_nan || isnan((double)p[k]);
            clamp_texel(p);
            for (int k = 0; k < 4; k++) CHECK(isnan((double)p[k]) || (double)p[k] <= (k == 3 ? 1.0 : HALF_MAX));
            CHECK(!isnan((double)p[3]), "case %d: a NaN transmittance kept", j);
        }
        double fx = sbfx_rng_range(&rng, 0.0, 1.0), fy = sbfx_rng_range(&rng, 0.0, 1.0);
        double w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
        if (i % 2) w[0] = 1.0, w[1] = w[2] = w[3] = 0.0;   /* nearest-depth's one texel */
        half sum[4];
        for (int k = 0; k < 4; k++) {
            double exact;
            sum[k] = weighted_sum(t, w, k, &exact);
        }
        bool dropped = sanitize(sum);
        missed += light_nan && !dropped;
        false_alarms += !light_nan && dropped;
        for (int k = 0; k < 4; k++) CHECK(!isnan((double)sum[k]), "case %d: channel %d NaN", i, k);
    }
    CHECK(missed == 0, "%d pixels with a NaN light kept", missed);
    CHECK(false_alarms == 0, "%d pixels of finite texels dropped", false_alarms);
}

/* The shimmer offsets are stored in RGBA16F and summed there by the blend (heat adds): each
 * particle's offset is rounded to half, and so is every running sum, so n particles at a pixel
 * are within gamma(n) sum |offset_i| of the exact sum (recursive summation). The campfire's
 * strength, 0.012 UV, is the largest of the scenes; a dozen particles at one pixel. */
CHECK_TEST(shimmer_offsets_in_half)
{
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 5);
    double worst_pixels = 0.0, worst_ratio = 0.0;
    for (int i = 0; i < CASES / 10; i++) {
        half sum = (half)0.0;
        double exact = 0.0, magnitude = 0.0;
        for (int n = 0; n < 12; n++) {
            double o = sbfx_rng_range(&rng, -0.012, 0.012);
            sum = add(sum, (half)o);
            exact += o, magnitude += fabs(o);
        }
        double err = fabs((double)sum - exact);
        worst_pixels = fmax(worst_pixels, err * 1920.0);
        worst_ratio = fmax(worst_ratio, err / (gamma_n(12) * magnitude));
    }
    printf("# 12 offsets of up to 0.012 UV blended in RGBA16F: at most %.3f pixels off at 1920 "
           "pixels across; largest error / gamma(12) sum |offset| = %.3f\n", worst_pixels, worst_ratio);
    CHECK(worst_ratio <= 1.0, "offsets beyond the recursive-summation bound: %g", worst_ratio);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
