/* Debounce and rate limit of GPIO trigger lines (platform/gpio/trigger_filter.c). */
#include "check.h"
#include "gpio/trigger_filter.h"

#define MS INT64_C(1000000)

static int run(struct trigger_filter *f, const int64_t *edges, int count)
{
    int fired = 0;
    for (int i = 0; i < count; i++) fired += trigger_filter_edge(f, edges[i]);
    return fired;
}

CHECK_TEST(clean_presses_fire_each)
{
    struct trigger_filter f;
    trigger_filter_init(&f, 30, 250);
    const int64_t presses[] = {1000 * MS, 1400 * MS, 1800 * MS, 2200 * MS};
    CHECK(run(&f, presses, 4) == 4);
    CHECK(f.edges == 4 && f.fires == 4);
}

CHECK_TEST(contact_bounce_fires_once)
{
    struct trigger_filter f;
    trigger_filter_init(&f, 30, 0);
    /* a press that bounces for 6 ms, then a clean second press */
    const int64_t edges[] = {100 * MS, 101 * MS, 103 * MS, 106 * MS, 500 * MS, 502 * MS};
    CHECK(run(&f, edges, 6) == 2);
}

CHECK_TEST(storm_of_1000_edges_fires_once)
{
    struct trigger_filter f;
    trigger_filter_init(&f, 30, 250);
    int fired = 0;
    for (int i = 0; i < 1000; i++) fired += trigger_filter_edge(&f, 5000 * MS + i * MS);
    CHECK(fired == 1, "fired %d", fired);
    CHECK(trigger_filter_edge(&f, 5999 * MS + 31 * MS), "a clean press after the storm fires");
}

CHECK_TEST(dropped_edges_do_not_look_quiet)
{
    /* The kernel FIFO holds 16 events: a storm read every 200 ms shows 16 edges, a gap, 16 more.
     * Marking the line busy until each full read keeps the gaps from counting as quiet. */
    struct trigger_filter f;
    trigger_filter_init(&f, 30, 0);
    int fired = 0;
    for (int burst = 0; burst < 5; burst++) {
        int64_t t0 = burst * 200 * MS;
        for (int i = 0; i < 16; i++) fired += trigger_filter_edge(&f, t0 + i * MS);
        trigger_filter_busy_until(&f, t0 + 199 * MS); /* the read that found the FIFO full */
    }
    CHECK(fired == 1, "fired %d", fired);
}

CHECK_TEST(rate_limit_holds_a_noisy_line)
{
    /* edges 40 ms apart pass the 30 ms debounce; the 250 ms rate limit lets one in 7 through */
    struct trigger_filter f;
    trigger_filter_init(&f, 30, 250);
    int fired = 0;
    for (int i = 0; i < 25; i++) fired += trigger_filter_edge(&f, i * 40 * MS);
    CHECK(fired == 4, "fired %d over 960 ms", fired);
}

CHECK_TEST(time_going_backwards_is_safe)
{
    struct trigger_filter f;
    trigger_filter_init(&f, 30, 250);
    CHECK(trigger_filter_edge(&f, 1000 * MS));
    CHECK(!trigger_filter_edge(&f, 10 * MS), "an edge from before the last one does not fire");
    CHECK(trigger_filter_edge(&f, 1300 * MS));
}

CHECK_TEST(zero_settings_fire_every_edge)
{
    struct trigger_filter f;
    trigger_filter_init(&f, 0, 0);
    const int64_t edges[] = {1, 2, 3, 3};
    CHECK(run(&f, edges, 4) == 4);
    trigger_filter_init(&f, -5, -5);
    CHECK(run(&f, edges, 4) == 4, "negative settings mean none");
}

int main(int argc, char **argv)
{
    return check_main_args(argc, argv);
}
