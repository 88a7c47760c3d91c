/* GPU against the CPU reference: every opacity mode on a few hundred random configurations,
 * plus the scene-level promises (wall, moving camera, bad particles). */
#include "gl_fixture.h"
#include "reference.h"

#define SIZE 48
#define CONFIGS 300
/* float shader arithmetic vs double reference, and the depth texture's float quantisation. The
 * same at GPU precision (tests/precision.sh): opacity is highp in particle.frag, and with the
 * detail strength 0 nothing it depends on is read through the texture filter. */
#define ALPHA_TOLERANCE 5e-5

typedef struct config {
    sbfx_view_particle particle;
    double tau;
    int depth_kind;     /* 0: far, 1: plane, 2: wall on the left half */
    double depth_value;
} config;

static double config_depth(int x, int y, void *user)
{
    const config *c = user;
    (void)y;
    if (c->depth_kind == 0) return INFINITY;
    if (c->depth_kind == 1) return c->depth_value;
    return x < SIZE / 2 ? c->depth_value : INFINITY;
}

static config random_config(sbfx_rng *rng)
{
    config c = {0};
    double zc = sbfx_rng_range(rng, 0.3, 25.0);
    double r = sbfx_rng_range(rng, 0.05, 0.3) * zc + sbfx_rng_range(rng, 0.0, 1.0);
    c.particle = (sbfx_view_particle){
        .center = {(float)(sbfx_rng_range(rng, -0.4, 0.4) * zc), (float)(sbfx_rng_range(rng, -0.4, 0.4) * zc),
                   (float)-zc},
        .radius = (float)r, .intensity = 1.0f, .medium = SBFX_SMOKE};
    c.tau = sbfx_rng_range(rng, 0.02, 2.0);
    c.depth_kind = (int)(sbfx_rng_u32(rng) % 3);
    c.depth_value = zc + sbfx_rng_range(rng, -1.2, 1.2) * r;
    if (c.depth_value <= 0.2) c.depth_value = 0.2;
    return c;
}

static double compare_config(gl_fixture *f, sbfx *fx, sbfx_opacity_mode mode, config *c, int *bad)
{
    sbfx_media(fx)[SBFX_SMOKE].tau = (float)c->tau;
    sbfx_media(fx)[SBFX_SMOKE].detail_strength = 0.0f;
    fixture_depth(f, config_depth, c);
    CHECK(sbfx_render_view_particles(fx, &f->frame, &c->particle, 1) == SBFX_OK, "%s", sbfx_last_error(fx));
    int w, h;
    float *rgba = fixture_read_target(fx, &w, &h);
    double worst = 0.0;
    sbfx_ref_particle rp = {{c->particle.center[0], c->particle.center[1], c->particle.center[2]},
                            c->particle.radius, c->tau};
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            sbfx_ref_pixel px = {{0}, fixture_stored_distance(&f->frame, config_depth(x, y, c)),
                                 fixture_near(&f->frame), 0.0};
            fixture_ray(f, &f->frame, w, h, x, y, px.ray);
            double cpu = sbfx_ref_opacity(mode, &rp, &px);
            double gpu = 1.0 - rgba[4 * (y * w + x) + 3];
            double e = fabs(cpu - gpu);
            if (e > worst) worst = e;
            if (!isfinite(gpu)) (*bad)++;
        }
    free(rgba);
    return worst;
}

static void gpu_matches_cpu(sbfx_opacity_mode mode)
{
    gl_fixture f;
    fixture_open(&f, SIZE, SIZE);
    fixture_projection(&f, 1.0f, 0.1f, 100.0f);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.target_divisor = 1, .target_format = SBFX_FORMAT_RGBA32F,
                                              .opacity = mode, .max_particles = 8});
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 20261121);
    double worst = 0.0;
    int bad = 0, over = 0;
    for (int i = 0; i < CONFIGS; i++) {
        config c = random_config(&rng);
        double e = compare_config(&f, fx, mode, &c, &bad);
        if (e > ALPHA_TOLERANCE) over++;
        if (e > worst) worst = e;
    }
    printf("# mode %d: %d configurations x %d pixels, max |GPU - CPU| alpha = %.3g (tolerance %.0e)\n",
           mode, CONFIGS, SIZE * SIZE, worst, ALPHA_TOLERANCE);
    CHECK(bad == 0, "%d non-finite pixels", bad);
    CHECK(over == 0, "%d of %d configurations exceed the tolerance (worst %.3g)", over, CONFIGS, worst);
    sbfx_destroy(fx);
    fixture_close(&f);
}

CHECK_TEST(gpu_matches_cpu_planar) { gpu_matches_cpu(SBFX_OPACITY_PLANAR); }
CHECK_TEST(gpu_matches_cpu_soft) { gpu_matches_cpu(SBFX_OPACITY_SOFT); }
CHECK_TEST(gpu_matches_cpu_spherical) { gpu_matches_cpu(SBFX_OPACITY_SPHERICAL); }
CHECK_TEST(gpu_matches_cpu_exact) { gpu_matches_cpu(SBFX_OPACITY_EXACT); }

static double wall_at_5(int x, int y, void *user)
{
    (void)x, (void)y, (void)user;
    return 5.0;
}

/* A particle wholly behind an opaque wall adds nothing, in every mode. */
CHECK_TEST(particle_behind_wall_contributes_nothing)
{
    gl_fixture f;
    fixture_open(&f, SIZE, SIZE);
    fixture_projection(&f, 1.0f, 0.1f, 100.0f);
    for (int mode = SBFX_OPACITY_PLANAR; mode <= SBFX_OPACITY_EXACT; mode++) {
        sbfx *fx = fixture_module(&f, (sbfx_desc){.target_divisor = 1, .target_format = SBFX_FORMAT_RGBA32F,
                                                  .opacity = mode, .max_particles = 8});
        fixture_depth(&f, wall_at_5, NULL);
        sbfx_view_particle p = {.center = {0.2f, -0.1f, -8.0f}, .radius = 2.0f, .intensity = 1.0f,
                                .medium = SBFX_SMOKE};
        sbfx_media(fx)[SBFX_SMOKE].detail_strength = 0.0f;
        CHECK(sbfx_render_view_particles(fx, &f.frame, &p, 1) == SBFX_OK);
        int w, h;
        float *rgba = fixture_read_target(fx, &w, &h);
        double most = 0.0;
        for (int i = 0; i < w * h; i++) most = fmax(most, 1.0 - rgba[4 * i + 3]);
        /* soft fades over one radius: the sphere's front is 1 m behind the wall, its centre 3 m */
        CHECK(most == 0.0, "mode %d: alpha up to %g behind the wall", mode, most);
        free(rgba);
        sbfx_destroy(fx);
    }
    fixture_close(&f);
}

/* The camera moves through a particle in 1 cm steps: spherical and exact opacity change
 * smoothly; the planar billboard pops (which shows the test can see a pop). */
static double largest_step(gl_fixture *f, sbfx_opacity_mode mode)
{
    sbfx *fx = fixture_module(f, (sbfx_desc){.target_divisor = 1, .target_format = SBFX_FORMAT_RGBA32F,
                                             .opacity = mode, .max_particles = 8});
    sbfx_media(fx)[SBFX_SMOKE].detail_strength = 0.0f;
    sbfx_media(fx)[SBFX_SMOKE].tau = 1.0f;
    fixture_depth(f, depth_far_everywhere, NULL);
    double previous = -1.0, jump = 0.0;
    for (double zc = 2.0; zc >= -2.0; zc -= 0.01) {
        sbfx_view_particle p = {.center = {0.03f, 0.02f, (float)-zc}, .radius = 1.0f, .intensity = 1.0f,
                                .medium = SBFX_SMOKE};
        CHECK(sbfx_render_view_particles(fx, &f->frame, &p, 1) == SBFX_OK);
        int w, h;
        float *rgba = fixture_read_target(fx, &w, &h);
        sbfx_counters c;
        sbfx_stats(fx, &c);
        double alpha = c.passes ? 1.0 - rgba[4 * ((h / 2) * w + w / 2) + 3] : 0.0;
        if (previous >= 0.0) jump = fmax(jump, fabs(alpha - previous));
        previous = alpha;
        free(rgba);
    }
    sbfx_destroy(fx);
    return jump;
}

CHECK_TEST(camera_through_particle_has_no_popping)
{
    gl_fixture f;
    fixture_open(&f, SIZE, SIZE);
    fixture_projection(&f, 1.0f, 0.1f, 100.0f);
    double spherical = largest_step(&f, SBFX_OPACITY_SPHERICAL);
    double exact = largest_step(&f, SBFX_OPACITY_EXACT);
    double planar = largest_step(&f, SBFX_OPACITY_PLANAR);
    printf("# largest alpha step per 1 cm: spherical %.4f, exact %.4f, planar %.4f\n", spherical, exact, planar);
    CHECK(spherical < 0.02, "spherical pops by %g", spherical);
    CHECK(exact < 0.02, "exact pops by %g", exact);
    CHECK(planar > 0.3, "planar should pop at the near plane, largest step %g", planar);
    fixture_close(&f);
}

/* Bad particles are skipped: the target is bit-identical with and without them. */
CHECK_TEST(bad_particles_change_no_pixel)
{
    gl_fixture f;
    fixture_open(&f, SIZE, SIZE);
    fixture_projection(&f, 1.0f, 0.1f, 100.0f);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.target_divisor = 1, .target_format = SBFX_FORMAT_RGBA16F,
                                              .max_particles = 16});
    fixture_depth(&f, depth_far_everywhere, NULL);
    sbfx_view_particle good[3] = {
        {.center = {0, 0, -6}, .radius = 1.5f, .detail = {0.1f, 0.2f, 0.3f}, .intensity = 1, .medium = SBFX_SMOKE},
        {.center = {1, 0.5f, -7}, .radius = 1.0f, .detail = {0.5f, 0.1f, 0.9f}, .intensity = 1, .medium = SBFX_FIRE},
        {.center = {-1, -0.5f, -5}, .radius = 1.2f, .detail = {0.7f, 0.3f, 0.2f}, .intensity = 0.8f, .medium = SBFX_DUST}};
    sbfx_view_particle all[8];
    memcpy(all, good, sizeof(good));
    all[3] = good[0], all[3].center[0] = NAN;
    all[4] = good[1], all[4].radius = INFINITY;
    all[5] = good[2], all[5].intensity = NAN;
    all[6] = good[0], all[6].radius = -1.0f;
    all[7] = good[1], all[7].detail[2] = -INFINITY;
    int w, h;
    CHECK(sbfx_render_view_particles(fx, &f.frame, good, 3) == SBFX_OK);
    float *before = fixture_read_target(fx, &w, &h);
    CHECK(sbfx_render_view_particles(fx, &f.frame, all, 8) == SBFX_OK);
    sbfx_counters c;
    sbfx_stats(fx, &c);
    float *after = fixture_read_target(fx, &w, &h);
    CHECK(c.particles_skipped == 5, "skipped %d of 5 bad particles", c.particles_skipped);
    CHECK(memcmp(before, after, sizeof(float) * 4 * w * h) == 0, "bad particles changed pixels");
    CHECK(all_finite(after, 4u * w * h), "non-finite pixel");
    free(before);
    free(after);
    sbfx_destroy(fx);
    fixture_close(&f);
}
int main(int argc, char **argv) { return check_main_args(argc, argv); }
