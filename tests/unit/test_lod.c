/* Unit tests of the particle level of detail (src/sim/lod.c, the ladder's last resort): at most N
 * particles, the integrated optical depth (Σ w = Σ I r³ / D² per medium) and the light
 * (Σ w·I per medium) conserved, deterministic, NaN-free, nothing changed at or under N, and the
 * image's optical depth integrated over the view (CPU reference, exact model) kept. */
#include <stdlib.h>
#include "check.h"
#include "sim/lod.h"
#include "reference.h"

#define MAX 4096

static sbfx_view_particle cloud[MAX], work[MAX];
static unsigned rng_state;

static double rnd(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (rng_state >> 8) / 16777216.0;
}

/* A barrage-like cloud: n particles around 12 explosion centres, three media. */
static int make_cloud(int n, unsigned seed)
{
    rng_state = seed;
    double centres[12][3];
    for (int e = 0; e < 12; e++) {
        centres[e][0] = -4 + 8 * rnd();
        centres[e][1] = -2 + 4 * rnd();
        centres[e][2] = -8 - 8 * rnd();
    }
    for (int i = 0; i < n; i++) {
        const double *c = centres[i % 12];
        sbfx_view_particle *p = &cloud[i];
        *p = (sbfx_view_particle){0};
        for (int k = 0; k < 3; k++) {
            p->center[k] = (float)(c[k] + 1.5 * (rnd() - 0.5) * (1 + rnd()));
            p->previous_center[k] = p->center[k] + 0.01f;
            p->detail[k] = (float)rnd();
        }
        p->radius = (float)(0.2 + 0.8 * rnd());
        p->intensity = (float)rnd();
        p->medium = (sbfx_medium)(i % 7 < 4 ? SBFX_FIRE : i % 7 < 6 ? SBFX_SMOKE : SBFX_DUST);
    }
    return n;
}

static particle_lod lod;
static void *lod_memory;

static int reduce(int n, int max_count)
{
    if (!lod_memory) {
        lod_memory = calloc(1, lod_work_size(MAX));
        lod_init(&lod, lod_memory, MAX);
    }
    memcpy(work, cloud, sizeof(cloud[0]) * (size_t)n);
    return lod_reduce(&lod, work, n, max_count);
}

static void sums(const sbfx_view_particle *v, int n, double w[SBFX_MEDIUM_COUNT], double wi[SBFX_MEDIUM_COUNT])
{
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) w[m] = wi[m] = 0.0;
    for (int i = 0; i < n; i++) {
        double x = lod_weight(&v[i]);
        w[v[i].medium] += x;
        wi[v[i].medium] += x * v[i].intensity;
    }
}

CHECK_TEST(count_and_conservation)
{
    int n = make_cloud(3800, 7u);
    const int levels[] = {2048, 1024, 512, 256, 128, 64, 16, 3};
    double worst_w = 0, worst_wi = 0;
    for (size_t k = 0; k < sizeof(levels) / sizeof(levels[0]); k++) {
        int got = reduce(n, levels[k]);
        CHECK(got <= levels[k] && got > 0, "lod%d: %d particles", levels[k], got);
        double w0[SBFX_MEDIUM_COUNT], wi0[SBFX_MEDIUM_COUNT], w1[SBFX_MEDIUM_COUNT], wi1[SBFX_MEDIUM_COUNT];
        sums(cloud, n, w0, wi0);
        sums(work, got, w1, wi1);
        for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) {
            if (w0[m] == 0) continue;
            worst_w = fmax(worst_w, fabs(w1[m] / w0[m] - 1));
            worst_wi = fmax(worst_wi, fabs(wi1[m] / wi0[m] - 1));
        }
        for (int i = 0; i < got; i++) {
            const sbfx_view_particle *p = &work[i];
            CHECK(sbfx_view_particle_valid(p), "lod%d particle %d: r %g I %g c %g %g %g", levels[k], i,
                  p->radius, p->intensity, p->center[0], p->center[1], p->center[2]);
            CHECK(p->intensity >= 0 && p->intensity <= 1, "I %g", p->intensity);
            for (int c = 0; c < 3; c++) CHECK_FINITE(p->previous_center[c]);
        }
        if (levels[k] == 3) /* fewer than the media: merged to one per medium, nothing dropped */
            CHECK(lod.drops == 0 && got == 3, "%d drops, %d left", lod.drops, got);
    }
    printf("# 3800 particles -> lod2048..lod3: Σ I r³/D² per medium within %.2g, Σ w·I within %.2g "
           "(relative)\n", worst_w, worst_wi);
    CHECK(worst_w < 1e-4, "%g", worst_w);
    CHECK(worst_wi < 1e-4, "%g", worst_wi);
}

CHECK_TEST(unchanged_at_or_under_n_and_deterministic)
{
    int n = make_cloud(500, 11u);
    int got = reduce(n, 500);
    CHECK(got == n && memcmp(work, cloud, sizeof(cloud[0]) * (size_t)n) == 0, "changed at N = count");
    got = reduce(n, 4096);
    CHECK(got == n && memcmp(work, cloud, sizeof(cloud[0]) * (size_t)n) == 0, "changed under N");
    static sbfx_view_particle first[MAX];
    int a = reduce(n, 100);
    memcpy(first, work, sizeof(work[0]) * (size_t)a);
    int b = reduce(n, 100);
    CHECK(a == b && memcmp(first, work, sizeof(work[0]) * (size_t)a) == 0, "two runs differ");
}

CHECK_TEST(one_medium_fewer_than_n_drops)
{
    /* N below the number of media present: the least weighty go */
    int n = make_cloud(700, 3u);
    int got = reduce(n, 1);
    CHECK(got == 1 && lod.drops == 2, "%d left, %d dropped", got, lod.drops);
    CHECK(sbfx_view_particle_valid(&work[0]));
}

CHECK_TEST(extreme_inputs_stay_finite)
{
    int n = make_cloud(64, 5u);
    cloud[0].center[0] = cloud[0].center[1] = cloud[0].center[2] = 0.0f; /* at the camera */
    cloud[1].radius = 1e-30f;
    cloud[2].radius = 1e30f;
    cloud[3].intensity = 0.0f;
    cloud[4].intensity = 0.0f, cloud[5].intensity = 0.0f;
    cloud[5].medium = cloud[4].medium;
    cloud[6].center[2] = 1e30f;
    cloud[7].center[2] = 5.0f; /* behind the camera */
    for (int max = 1; max <= 64; max *= 2) {
        int got = reduce(n, max);
        CHECK(got <= max, "%d > %d", got, max);
        for (int i = 0; i < got; i++)
            CHECK(sbfx_view_particle_valid(&work[i]) || work[i].intensity == 0.0f, "lod%d #%d: r %g I %g", max,
                  i, work[i].radius, work[i].intensity);
    }
}

/* The view's optical depth, Σ over a 200x200 grid of rays (x, y in ±0.7, z = -1) of the exact
 * model's optical depth summed over particles, each ray weighted by its solid angle. */
static double view_optical_depth(const sbfx_view_particle *v, int n)
{
    const int grid = 200;
    double total = 0;
    for (int j = 0; j < grid; j++)
        for (int i = 0; i < grid; i++) {
            double x = -0.7 + 1.4 * (i + 0.5) / grid, y = -0.7 + 1.4 * (j + 0.5) / grid;
            sbfx_ref_pixel px = {.ray = {x, y, -1}, .opaque_depth = 1e30, .near = 0.1};
            double tau = 0;
            for (int k = 0; k < n; k++) {
                sbfx_ref_particle p = {{v[k].center[0], v[k].center[1], v[k].center[2]}, v[k].radius,
                                       v[k].intensity};
                tau += sbfx_ref_optical_depth(SBFX_OPACITY_EXACT, &p, &px);
            }
            total += tau / pow(1 + x * x + y * y, 1.5);
        }
    return total;
}

CHECK_TEST(view_optical_depth_kept)
{
    int n = make_cloud(1200, 21u);
    double before = view_optical_depth(cloud, n);
    double worst = 0;
    for (int max = 600; max >= 75; max /= 2) {
        int got = reduce(n, max);
        double after = view_optical_depth(work, got);
        printf("# 1200 -> lod%d (%d): view's optical depth %.4f of the original\n", max, got, after / before);
        worst = fmax(worst, fabs(after / before - 1));
    }
    CHECK(worst < 0.05, "%g", worst);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
