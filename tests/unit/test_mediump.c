/* The Mali case (docs/design.md §2.2, issue #4): particle.frag declares its light and colour mediump —
 * phase(), in_scattered() (and its running sum), emitted() and the `light` accumulator — which a
 * Mali-class GPU runs at IEEE half precision. The CPU reference (ref/reference_frame.c) emulates
 * that by rounding to _Float16 (nearest even) at exactly those points, and these tests bound how
 * far the emulated frame strays from the double reference. No GL.
 *
 * The bound, and why. Let u = 2^-11, the unit roundoff of binary16 (11-bit significand), and
 * gamma(n) = n u / (1 - n u). With N lights, every value that reaches the particle target is a
 * sum of non-negative terms, each of which passes through at most N + 3 roundings:
 *   phase (1) + the running sum of in_scattered (N, the ambient's initial store included) +
 *   the store of albedo x in_scattered into `light` (1) + `light += emitted` (1),
 * and emitted() itself is rounded once before that last sum. Non-negative terms keep their
 * relative errors (no cancellation), alpha and the back-to-front blend stay highp (exact here:
 * the emulation blends in double), and the blend is linear with non-negative weights, so
 *     |C_mediump - C_double| <= gamma(N + 3) * C_double + n_layers * (N + 3) * 2^-25
 * per channel, where the second term covers half's subnormal range (absolute spacing 2^-24
 * below 2^-14, so rounding errors of at most 2^-25 there). Transmittance is untouched.
 * The bound holds while every mediump value stays below 65504 (above, half overflows to inf):
 * the random configurations keep their lights inside that range, and the last test shows the
 * module's own media and explosion lights leave a wide margin. Compilers may run more of the
 * arithmetic at half than GLSL's rules require (the rules only demand it at these stores); that
 * extra loss is not modelled. */
#include <float.h>
#include <stdint.h>
#include "check.h"
#include "reference_frame.h"

#define GRID 6
#define CONFIGS 3000
#define MAX_PARTICLES 6
#define MAX_RANDOM_LIGHTS 4
#define HALF_MAX 65504.0
#define UNIT_ROUNDOFF 4.8828125e-4          /* 2^-11 */
#define SUBNORMAL_HALF_ULP 2.98023223876953125e-8 /* 2^-25 */
#define FOUR_PI 12.566370614359172

static sbfx_cmf cmf;

static void load_cmf(void)
{
    cmf = sbfx_cie1931_2deg;
}

static double gamma_n(int n)
{
    return n * UNIT_ROUNDOFF / (1.0 - n * UNIT_ROUNDOFF);
}

typedef struct mp_config {
    sbfx_rf_frame f;
    sbfx_rf_light lights[MAX_RANDOM_LIGHTS];
    sbfx_rf_particle particles[MAX_PARTICLES];
    int count;
    double distance[GRID * GRID];
} mp_config;

static double rnd(sbfx_rng *rng, double lo, double hi) { return sbfx_rng_range(rng, lo, hi); }

static void random_media(sbfx_rng *rng, sbfx_rf_frame *f)
{
    for (int m = SBFX_DUST; m <= SBFX_SMOKE; m++)
        f->media[m] = (sbfx_rf_medium){.albedo = rnd(rng, 0.05, 1.0), .tau = rnd(rng, 0.05, 3.0),
                                       .phase_g = rnd(rng, -0.99, 0.99),
                                       .color = {rnd(rng, 0, 1), rnd(rng, 0, 1), rnd(rng, 0, 1)}};
    f->media[SBFX_FIRE] = (sbfx_rf_medium){.tau = rnd(rng, 0.05, 3.0), .t0 = rnd(rng, 300, 2500),
                                           .t1 = rnd(rng, 0, 3000), .cooling = rnd(rng, 0, 0.6),
                                           .emission_scale = rnd(rng, 1, 400)};
}

/* Largest in-scattered value any particle of this configuration can produce, in double:
 * ambient + sum over lights of E * falloff * max phase * 4 pi. */
static double scattered_ceiling(const mp_config *c)
{
    double g = fmax(fabs(c->f.media[SBFX_DUST].phase_g), fabs(c->f.media[SBFX_SMOKE].phase_g));
    double peak = sbfx_phase(1.0, g) * FOUR_PI, sum = 0.0;
    for (int k = 0; k < 3; k++) sum = fmax(sum, c->f.ambient[k]);
    for (int i = 0; i < c->f.light_count; i++) {
        const sbfx_rf_light *l = &c->lights[i];
        double e = fmax(l->color[0], fmax(l->color[1], l->color[2]));
        sum += e * (l->vector[3] > 0.5 ? 1.0 / SBFX_RF_MIN_LIGHT_D2 : 1.0) * peak;
    }
    return sum;
}

static void random_light(sbfx_rng *rng, sbfx_rf_light *l)
{
    bool point = sbfx_rng_u32(rng) % 2;
    if (point) {
        double pos[4] = {rnd(rng, -3, 3), rnd(rng, -3, 3), rnd(rng, -12, 1), 1.0};
        memcpy(l->vector, pos, sizeof(pos));
    } else {
        double z = rnd(rng, -1, 1), a = rnd(rng, 0, 6.283185307179586), s = sqrt(1 - z * z);
        double dir[4] = {s * cos(a), s * sin(a), z, 0.0};
        memcpy(l->vector, dir, sizeof(dir));
    }
    for (int k = 0; k < 3; k++) l->color[k] = rnd(rng, 0, point ? 6.0 : 2.0);
}

/* Lights drawn until the in-scattered sum provably stays inside half's range. */
static void random_lights(sbfx_rng *rng, mp_config *c)
{
    do {
        c->f.light_count = 1 + (int)(sbfx_rng_u32(rng) % MAX_RANDOM_LIGHTS);
        for (int i = 0; i < c->f.light_count; i++) random_light(rng, &c->lights[i]);
        for (int k = 0; k < 3; k++) c->f.ambient[k] = rnd(rng, 0, 0.5);
    } while (scattered_ceiling(c) > HALF_MAX / 2);
}

static void random_particles(sbfx_rng *rng, mp_config *c)
{
    c->count = 1 + (int)(sbfx_rng_u32(rng) % MAX_PARTICLES);
    for (int i = 0; i < c->count; i++) {
        double z = rnd(rng, 1.0, 12.0);
        c->particles[i] = (sbfx_rf_particle){
            .center = {rnd(rng, -0.3, 0.3) * z, rnd(rng, -0.3, 0.3) * z, -z}, .radius = rnd(rng, 0.2, 2.0),
            .detail = {rnd(rng, 0, 1), rnd(rng, 0, 1), rnd(rng, 0, 1)}, .intensity = rnd(rng, 0.05, 1.0),
            .medium = (sbfx_medium)(sbfx_rng_u32(rng) % 3)};
    }
}

static void random_config(sbfx_rng *rng, mp_config *c)
{
    memset(c, 0, sizeof(*c));
    random_media(rng, &c->f);
    random_lights(rng, c);
    random_particles(rng, c);
    double wall = sbfx_rng_u32(rng) % 2 ? rnd(rng, 1.0, 12.0) : INFINITY;
    for (int i = 0; i < GRID * GRID; i++) c->distance[i] = wall;
    c->f.width = c->f.height = GRID;
    c->f.projection[0] = c->f.projection[1] = 1.5;
    c->f.near = 0.1;
    c->f.opaque_distance = c->distance;
    c->f.opacity = SBFX_OPACITY_EXACT;
    c->f.lights = c->lights;
    c->f.cmf = &cmf;
    c->f.blackbody_norm = sbfx_blackbody_norm(&cmf, 6000.0);
}

typedef struct mp_stats {
    double worst_ratio;   /* largest |error| / bound */
    double worst_relative; /* largest |error| / C where C > 1e-3 */
    int over, nonfinite;
} mp_stats;

static void compare(const mp_config *c, mp_stats *st)
{
    double ref[GRID * GRID * 4], half[GRID * GRID * 4];
    sbfx_rf_frame f = c->f;
    f.precision = SBFX_RF_DOUBLE;
    sbfx_rf_render_layer(&f, c->particles, c->count, ref, NULL);
    f.precision = SBFX_RF_MEDIUMP;
    sbfx_rf_render_layer(&f, c->particles, c->count, half, NULL);
    int n = f.light_count;
    for (int i = 0; i < GRID * GRID * 4; i++) {
        if (!isfinite(half[i])) {
            st->nonfinite++;
            continue;
        }
        bool alpha = i % 4 == 3;
        double err = fabs(half[i] - ref[i]);
        double bound = alpha ? 0.0 : gamma_n(n + 3) * fabs(ref[i]) + c->count * (n + 3) * SUBNORMAL_HALF_ULP;
        if (err > bound) st->over++;
        if (bound > 0) st->worst_ratio = fmax(st->worst_ratio, err / bound);
        if (!alpha && ref[i] > 1e-3) st->worst_relative = fmax(st->worst_relative, err / ref[i]);
    }
}

CHECK_TEST(mediump_light_within_half_rounding_bound)
{
    load_cmf();
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 4242);
    mp_stats st = {0};
    for (int i = 0; i < CONFIGS; i++) {
        mp_config c;
        random_config(&rng, &c);
        compare(&c, &st);
    }
    printf("# %d random configurations x %d pixels: largest |mediump - double| / bound = %.3f, "
           "largest relative error %.2e (u = 2^-11 = %.2e)\n",
           CONFIGS, GRID * GRID, st.worst_ratio, st.worst_relative, UNIT_ROUNDOFF);
    CHECK(st.nonfinite == 0, "%d non-finite values", st.nonfinite);
    CHECK(st.over == 0, "%d values exceed gamma(N+3) C + subnormal term", st.over);
}

/* The emulation really rounds: some configuration must differ from double (a test of the test). */
CHECK_TEST(mediump_emulation_rounds)
{
    load_cmf();
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 7);
    mp_config c;
    random_config(&rng, &c);
    double ref[GRID * GRID * 4], half[GRID * GRID * 4];
    sbfx_rf_render_layer(&c.f, c.particles, c.count, ref, NULL);
    c.f.precision = SBFX_RF_MEDIUMP;
    sbfx_rf_render_layer(&c.f, c.particles, c.count, half, NULL);
    int differ = 0;
    for (int i = 0; i < GRID * GRID * 4; i++) differ += half[i] != ref[i];
    CHECK(differ > 0, "mediump emulation changed nothing");
}

/* The module's own media (g = 0) and the explosion's lights (sun 1.6, flash 6 seen from 0.5 m
 * at the closest) stay far below half's 65504; emission is capped at 16384 by the shader. The
 * phase function's peak is what could overflow: the g at which the flash alone would. */
CHECK_TEST(mediump_range_of_default_lights)
{
    double peak_g0 = sbfx_phase(1.0, 0.0) * FOUR_PI;
    double worst = 0.4 + (1.6 + 6.0 / SBFX_RF_MIN_LIGHT_D2) * peak_g0;
    double g = 0.0;
    while (g < SBFX_PHASE_G_MAX && (6.0 / SBFX_RF_MIN_LIGHT_D2) * sbfx_phase(1.0, g) * FOUR_PI < HALF_MAX) g += 0.001;
    printf("# default media: largest in-scattered value %.1f (half max 65504); the flash at 0.5 m "
           "overflows half only for g >= %.3f\n", worst, g);
    CHECK(worst < HALF_MAX / 100, "in-scattered light %g leaves under 100x margin", worst);
    CHECK(SBFX_RF_RADIANCE_CEILING < HALF_MAX, "emission ceiling");
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
