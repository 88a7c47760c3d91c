/* presentation-time feedback into the display's counters (platform/wayland/present_feedback.c)
 * with made-up reports: frames shown and discarded, latency from commit to screen, and refresh
 * cycles that passed without a new frame, from the output's counter where the compositor keeps
 * one, else from the times and the refresh period. The real compositor path is tests/wayland.sh. */
#include "check.h"
#include "wayland/present_feedback.h"

#define MS INT64_C(1000000)
#define REFRESH (16667 * INT64_C(1000)) /* 60 Hz */

CHECK_TEST(counter_gives_missed_refreshes)
{
    struct present_feedback f = {0};
    struct display_counts c = {0};
    /* frames shown at refreshes 100, 101, 104 (two missed), 105 */
    const uint64_t seq[] = {100, 101, 104, 105};
    for (int i = 0; i < 4; i++)
        present_feedback_presented(&f, &c, (int64_t)seq[i] * REFRESH, seq[i], REFRESH,
                                   (int64_t)seq[i] * REFRESH - 5 * MS);
    CHECK(c.feedback_presented == 4, "presented %llu", (unsigned long long)c.feedback_presented);
    CHECK(c.missed == 2, "missed %llu, expected 2", (unsigned long long)c.missed);
    CHECK(c.latency_ns_sum == 4 * 5 * MS && c.latency_ns_max == 5 * MS, "latency sum %lld max %lld",
          (long long)c.latency_ns_sum, (long long)c.latency_ns_max);
}

CHECK_TEST(times_give_missed_refreshes_without_a_counter)
{
    struct present_feedback f = {0};
    struct display_counts c = {0};
    /* no counter (seq 0): 1, then 3 periods (two missed), then 1.4 periods (jitter: none) */
    const int64_t t[] = {10 * REFRESH, 11 * REFRESH, 14 * REFRESH, 14 * REFRESH + REFRESH * 14 / 10};
    for (int i = 0; i < 4; i++) present_feedback_presented(&f, &c, t[i], 0, REFRESH, t[i] - MS);
    CHECK(c.missed == 2, "missed %llu, expected 2", (unsigned long long)c.missed);
}

CHECK_TEST(unknown_refresh_counts_nothing_missed)
{
    struct present_feedback f = {0};
    struct display_counts c = {0};
    present_feedback_presented(&f, &c, 100 * MS, 0, 0, 90 * MS);
    present_feedback_presented(&f, &c, 900 * MS, 0, 0, 880 * MS);
    CHECK(c.missed == 0 && c.feedback_presented == 2, "missed %llu", (unsigned long long)c.missed);
    CHECK(c.latency_ns_max == 20 * MS && c.latency_ns_sum == 30 * MS, "latency max %lld sum %lld",
          (long long)c.latency_ns_max, (long long)c.latency_ns_sum);
}

CHECK_TEST(discarded_and_clock_skew)
{
    struct present_feedback f = {0};
    struct display_counts c = {0};
    present_feedback_discarded(&c);
    present_feedback_discarded(&c);
    /* shown "before" its commit (a clock read late): latency 0, never negative */
    present_feedback_presented(&f, &c, 50 * MS, 7, REFRESH, 60 * MS);
    CHECK(c.feedback_discarded == 2 && c.feedback_presented == 1, "discarded %llu presented %llu",
          (unsigned long long)c.feedback_discarded, (unsigned long long)c.feedback_presented);
    CHECK(c.latency_ns_sum == 0 && c.latency_ns_max == 0, "latency %lld", (long long)c.latency_ns_sum);
    CHECK(c.missed == 0, "the first presentation misses nothing");
}

int main(void)
{
    return check_main();
}
