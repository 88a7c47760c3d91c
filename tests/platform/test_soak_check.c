/* sbfx-soak's flatness check (tools/soak/soak_check.c) on made-up series: flat passes; any growth
 * of what sbfx or the context holds, memory beyond its tolerance, lost time or an idle run is
 * named with how much. */
#include "check.h"
#include "soak/soak_check.h"

#define N 100
#define DT 0.25

static struct soak_sample series[N];

/* A healthy soak: one sample every 100 frames, memory wandering within 600 KiB. */
static void flat_series(void)
{
    for (int i = 0; i < N; i++)
        series[i] = (struct soak_sample){.frames = i * 100, .sim_seconds = i * 100 * DT, .rss_anon_kib = 120000 + (i * 37) % 600,
                                         .rss_kib = 150000 + i * 1000,
                                         .heap_bytes = 70000000 + (i % 3) * 100000, .programs = 35, .textures = 40,
                                         .framebuffers = 20, .gpu_bytes = 2975648, .gl_textures = 42,
                                         .gl_framebuffers = 22, .gl_buffers = 6, .particles_alive = 700 + i % 50,
                                         .triggers_fired = 125 * i, .triggers_refused = 0};
}

static int check_series(char *report, size_t n)
{
    struct soak_limits lim;
    soak_limits_default(&lim);
    lim.dt = DT;
    lim.step = 1.0 / 120.0;
    return soak_check(series, N, &lim, report, n);
}

CHECK_TEST(flat_run_passes)
{
    char report[4096];
    flat_series();
    for (int i = 0; i < N / 5; i++) series[i].rss_anon_kib += 30000 - i * 1000, series[i].textures = i < 3 ? 30 : 40;
    int problems = check_series(report, sizeof(report));
    CHECK(problems == 0, "%d problems: %s", problems, report);
    CHECK(strstr(report, "# rss_anon_kib: ") != NULL && strstr(report, "# rss_kib: ") != NULL, "no RSS summary: %s",
          report);
}

CHECK_TEST(one_leaked_texture_is_named)
{
    char report[4096];
    flat_series();
    for (int i = 60; i < N; i++) series[i].gl_textures = 43;
    CHECK(check_series(report, sizeof(report)) == 1);
    CHECK(strstr(report, "gl_textures grew from 42 to 43 (+1)") != NULL, "%s", report);
}

CHECK_TEST(every_exact_counter_is_checked)
{
    char report[4096];
    flat_series();
    series[N - 1].programs++, series[N - 1].framebuffers++, series[N - 1].gpu_bytes += 4096;
    series[N - 1].heap_allocs = 1, series[N - 1].gl_buffers++, series[N - 1].gl_framebuffers++;
    series[50].textures = 39;
    int problems = check_series(report, sizeof(report));
    CHECK(problems == 7, "%d problems: %s", problems, report);
    const char *const named[] = {"programs grew", "framebuffers grew", "gpu_bytes grew from 2975648 to 2979744 (+4096)",
                                 "heap_allocs grew", "gl_buffers grew", "gl_framebuffers grew", "textures fell"};
    for (size_t i = 0; i < sizeof(named) / sizeof(named[0]); i++)
        CHECK(strstr(report, named[i]) != NULL, "'%s' not in: %s", named[i], report);
}

CHECK_TEST(memory_growth_beyond_tolerance_is_named)
{
    char report[4096];
    flat_series();
    for (int i = 0; i < N; i++) series[i].rss_anon_kib += i * 100, series[i].heap_bytes += (int64_t)i * 80000;
    CHECK(check_series(report, sizeof(report)) == 2, "%s", report);
    CHECK(strstr(report, "rss_anon_kib grew by ") != NULL && strstr(report, "(tolerance 4096)") != NULL, "%s", report);
    CHECK(strstr(report, "heap_bytes grew by ") != NULL, "%s", report);
}

CHECK_TEST(idle_run_and_lost_time_fail)
{
    char report[4096];
    flat_series();
    for (int i = 0; i < N; i++) series[i].triggers_fired = 7;
    series[N - 1].sim_seconds -= 1.0;
    CHECK(check_series(report, sizeof(report)) == 2, "%s", report);
    CHECK(strstr(report, "nothing happened") != NULL, "%s", report);
    CHECK(strstr(report, "1.000000 s lost") != NULL, "%s", report);
}

CHECK_TEST(too_few_samples_fail)
{
    char report[512];
    struct soak_limits lim;
    soak_limits_default(&lim);
    flat_series();
    CHECK(soak_check(series, 5, &lim, report, sizeof(report)) == 1);
    CHECK(strstr(report, "only 5 samples") != NULL, "%s", report);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
