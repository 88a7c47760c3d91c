/* Unit tests of the frame-budget governor (src/budget/governor.c, docs/design.md §6, issue 11 item 4) with a
 * synthetic cost model, no GL: a ladder of 8 rungs whose true costs are load × COST[i], each
 * frame's time measured LATENCY frames late (tagged with the level it was rendered at), with
 * deterministic noise (an LCG) of ±NOISE where a test asks for it. The measured numbers are
 * printed as "# ..." lines. */
#include "check.h"
#include "budget/governor.h"

#define LEVELS 8
#define LATENCY 3   /* frames between rendering and the measurement's arrival (the timer ring) */
#define BUDGET 16.0
static const double COST[LEVELS] = {1.0, 0.62, 0.47, 0.33, 0.21, 0.14, 0.08, 0.03};

typedef struct sim {
    governor g;
    int pending_level[LATENCY];
    double pending_ms[LATENCY];
    unsigned rng;
    int frame;
    int changes_after[2];  /* changes counted after frame 200 / 500 */
    int last_change_frame; /* frame of the last level change */
} sim;

static double sim_noise(sim *s, double amount)
{
    s->rng = s->rng * 1664525u + 1013904223u;
    return 1.0 + amount * ((s->rng >> 8) / 8388608.0 - 1.0); /* uniform in [1 - a, 1 + a) */
}

static void sim_init(sim *s, bool with_prior)
{
    *s = (sim){.rng = 12345u};
    governor_init(&s->g, BUDGET, LEVELS);
    if (with_prior)
        governor_set_prior(&s->g, COST, LEVELS);
    for (int i = 0; i < LATENCY; i++)
        s->pending_level[i] = -1;
}

/* One frame at `load` (ms of level 0): render at the governor's level, observe the frame
 * rendered LATENCY frames ago. */
static void sim_frame(sim *s, double load, double noise)
{
    int slot = s->frame % LATENCY;
    if (s->pending_level[slot] >= 0)
        governor_observe(&s->g, s->pending_level[slot], s->pending_ms[slot], true);
    int before = governor_level(&s->g);
    s->pending_level[slot] = before;
    s->pending_ms[slot] = load * COST[before] * sim_noise(s, noise);
    (void)before;
    s->frame++;
}

static void sim_run(sim *s, int frames, double load, double noise)
{
    for (int i = 0; i < frames; i++) {
        int level = governor_level(&s->g), changes = governor_changes(&s->g);
        sim_frame(s, load, noise);
        if (governor_level(&s->g) != level || governor_changes(&s->g) != changes) {
            s->last_change_frame = s->frame;
            s->changes_after[0] += s->frame > 200;
            s->changes_after[1] += s->frame > 500;
        }
    }
}

/* Where the governor must settle at a constant load (±noise): a rung that fits the budget and
 * whose upper neighbour does not fit with the ascent's margin (the hysteresis: a rung that
 * fits by less than GOVERNOR_UP_MARGIN is not climbed back to). */
static bool settled_ok(double load, int level, double noise)
{
    bool fits = load * COST[level] <= BUDGET * (1.0 + noise) || level == LEVELS - 1;
    bool upper_not = level == 0 || load * COST[level - 1] * GOVERNOR_UP_MARGIN > BUDGET * (1.0 - noise);
    return fits && upper_not;
}

/* The level a perfect governor picks: the most accurate rung whose cost fits the budget. */
static int ideal_level(double load)
{
    for (int i = 0; i < LEVELS; i++)
        if (load * COST[i] <= BUDGET)
            return i;
    return LEVELS - 1;
}

CHECK_TEST(converges_quickly_when_far_over)
{
    /* load 4x the budget at the top: the right rung is 4 (0.21 × 64 = 13.4 ms) */
    for (int prior = 0; prior < 2; prior++) {
        sim s;
        sim_init(&s, prior);
        sim_run(&s, 1000, 4.0 * BUDGET, 0.0);
        int level = governor_level(&s.g);
        printf("# converges (%s prior): 4x over -> level %d (ideal %d) at frame %d, %d changes\n",
               prior ? "bench" : "default", level, ideal_level(4.0 * BUDGET), s.last_change_frame,
               governor_changes(&s.g));
        CHECK(level == ideal_level(4.0 * BUDGET) && settled_ok(4.0 * BUDGET, level, 0.0), "level %d", level);
        CHECK(s.last_change_frame <= (prior ? 12 : 120), "settled at frame %d", s.last_change_frame);
        CHECK(governor_changes(&s.g) <= (prior ? 1 : 6), "%d changes", governor_changes(&s.g));
    }
}

CHECK_TEST(first_step_skips_rungs_when_far_over)
{
    sim s;
    sim_init(&s, true);
    int frames = 0;
    while (governor_level(&s.g) == 0 && frames < 100)
        sim_run(&s, 1, 8.0 * BUDGET, 0.0), frames++;
    printf("# 8x over: first step 0 -> %d after %d frames (latency %d)\n", governor_level(&s.g),
           frames, LATENCY);
    CHECK(governor_level(&s.g) >= 5, "stepped to %d", governor_level(&s.g));
    CHECK(frames <= LATENCY + GOVERNOR_DOWN_SAMPLES, "%d frames", frames);
}

CHECK_TEST(bounded_changes_under_constant_noisy_load)
{
    /* 60 loads from 0.5x to 12x the budget, ±10 % noise per frame, 1000 frames each */
    int worst = 0, worst_late = 0, wrong = 0;
    double worst_load = 0;
    for (int k = 0; k < 60; k++) {
        double load = BUDGET * 0.5 * pow(24.0, k / 59.0);
        sim s;
        sim_init(&s, k % 2);
        sim_run(&s, 1000, load, 0.10);
        if (governor_changes(&s.g) > worst)
            worst = governor_changes(&s.g), worst_load = load / BUDGET;
        if (s.changes_after[1] > worst_late)
            worst_late = s.changes_after[1];
        wrong += !settled_ok(load, governor_level(&s.g), 0.10);
    }
    printf("# 1000 frames at constant load, ±10 %% noise, 60 loads 0.5x-12x: at most %d changes "
           "(at %.2fx), at most %d after frame 500; %d runs ended on a wrong rung\n",
           worst, worst_load, worst_late, wrong);
    CHECK(worst <= 16, "%d changes", worst);
    CHECK(worst_late <= 4, "%d changes after frame 500", worst_late);
    CHECK(wrong == 0, "%d", wrong);
}

/* A shared machine: other jobs stretch some frames. One frame in 20 takes 3x as long (alone,
 * not in runs): single spikes must not move it, and what they cost stays bounded. */
CHECK_TEST(isolated_spikes_bounded)
{
    int worst = 0, wrong = 0;
    for (int k = 0; k < 30; k++) {
        double load = BUDGET * 0.6 * pow(15.0, k / 29.0);
        sim s;
        sim_init(&s, true);
        for (int f = 0; f < 1000; f++) {
            int level = governor_level(&s.g), changes = governor_changes(&s.g);
            sim_frame(&s, load * (f % 20 == 7 ? 3.0 : 1.0), 0.05);
            (void)level, (void)changes;
        }
        if (governor_changes(&s.g) > worst) worst = governor_changes(&s.g);
        wrong += !settled_ok(load, governor_level(&s.g), 0.05);
    }
    printf("# one frame in 20 at 3x, 30 loads 0.6x-9x: at most %d changes in 1000 frames, %d runs on a wrong rung\n",
           worst, wrong);
    CHECK(worst <= 3, "%d changes", worst);
    CHECK(wrong == 0, "%d", wrong);
}

/* Two frames over the budget in a row, one of them stretched 10x by another job: the step down
 * goes by the lesser (1.2x: one rung), not by the stretched one. */
CHECK_TEST(step_down_by_the_least_of_the_over_run)
{
    governor g;
    governor_init(&g, BUDGET, LEVELS);
    governor_set_prior(&g, COST, LEVELS);
    for (int i = 0; i < 5; i++) governor_observe(&g, 0, 0.9 * BUDGET, true);
    governor_observe(&g, 0, 10.0 * BUDGET, true);
    governor_observe(&g, 0, 1.05 * BUDGET, true);
    printf("# at 0.9x, then 10x and 1.05x: level 0 -> %d\n", governor_level(&g));
    CHECK(governor_level(&g) == 1, "level %d", governor_level(&g)); /* 0.62 x 1.05 fits 0.85 */
}

CHECK_TEST(no_oscillation_at_a_boundary)
{
    /* loads that put a rung just over or just at the budget, without noise: after the descent
     * (and at most one failed probe of an unmeasured rung), not one change */
    int worst_after = 0;
    for (int rung = 0; rung < LEVELS - 1; rung++) {
        for (int side = -1; side <= 1; side++) {
            double load = BUDGET / COST[rung] * (1.0 + 0.001 * side);
            sim s;
            sim_init(&s, side == 0);
            sim_run(&s, 1000, load, 0.0);
            if (s.changes_after[0] > worst_after)
                worst_after = s.changes_after[0];
            int level = governor_level(&s.g);
            CHECK(settled_ok(load, level, 0.0) && level <= ideal_level(load) + 1,
                  "rung %d side %d: level %d, ideal %d", rung, side, level, ideal_level(load));
        }
    }
    /* with noise straddling the boundary: ±3 % around the boundary of rung 2 */
    sim s;
    sim_init(&s, true);
    sim_run(&s, 1000, BUDGET / COST[2], 0.03);
    printf("# boundary loads: %d changes after frame 200 without noise; ±3 %% noise on the "
           "boundary: %d changes in 1000 frames, %d after frame 500, ends at %d\n",
           worst_after, governor_changes(&s.g), s.changes_after[1], governor_level(&s.g));
    CHECK(worst_after == 0, "%d", worst_after);
    CHECK(governor_changes(&s.g) <= 4, "%d", governor_changes(&s.g));
    CHECK(s.changes_after[1] <= 1, "%d", s.changes_after[1]);
}

CHECK_TEST(recovers_when_load_falls)
{
    sim s;
    sim_init(&s, true);
    sim_run(&s, 300, 6.0 * BUDGET, 0.05);
    int low = governor_level(&s.g);
    int frames = 0;
    while (governor_level(&s.g) != 0 && frames < 2000)
        sim_run(&s, 1, 0.5 * BUDGET, 0.05), frames++;
    printf("# recovery: 6x -> level %d; load falls to 0.5x: back at level 0 after %d frames "
           "(%d rungs, %d frames a rung)\n", low, frames, low, GOVERNOR_UP_FRAMES);
    CHECK(low >= 5, "%d", low);
    CHECK(governor_level(&s.g) == 0, "level %d", governor_level(&s.g));
    CHECK(frames <= low * (GOVERNOR_UP_FRAMES + LATENCY + GOVERNOR_LEARN_SAMPLES), "%d", frames);
    /* and the partial case: 6x -> 2x goes up to the rung that fits, no further */
    sim t;
    sim_init(&t, true);
    sim_run(&t, 300, 6.0 * BUDGET, 0.0);
    sim_run(&t, 700, 2.0 * BUDGET, 0.0);
    CHECK(settled_ok(2.0 * BUDGET, governor_level(&t.g), 0.0), "level %d, ideal %d",
          governor_level(&t.g), ideal_level(2.0 * BUDGET));
}

CHECK_TEST(invalid_measurements_do_not_move_it)
{
    governor g;
    governor_init(&g, BUDGET, LEVELS);
    for (int i = 0; i < 500; i++) {
        governor_observe(&g, 0, 1000.0, false); /* disjoint */
        governor_observe(&g, 0, NAN, true);
        governor_observe(&g, 0, INFINITY, true);
        governor_observe(&g, 0, -5.0, true);
        governor_observe(&g, LEVELS, 1000.0, true); /* unknown level */
        governor_observe(&g, -1, 1000.0, true);
    }
    CHECK(governor_level(&g) == 0 && governor_changes(&g) == 0 && governor_frames_over(&g) == 0,
          "level %d changes %d over %d", governor_level(&g), governor_changes(&g),
          governor_frames_over(&g));
    /* settled at a rung with room: disjoint frames with huge times interleaved change nothing */
    sim s;
    sim_init(&s, true);
    sim_run(&s, 400, 3.0 * BUDGET, 0.0);
    int level = governor_level(&s.g), changes = governor_changes(&s.g);
    for (int i = 0; i < 300; i++) {
        governor_observe(&s.g, level, 50.0 * BUDGET, false);
        sim_run(&s, 1, 3.0 * BUDGET, 0.0);
    }
    CHECK(governor_level(&s.g) == level && governor_changes(&s.g) == changes, "level %d -> %d",
          level, governor_level(&s.g));
    /* a budget that is not a finite positive number disables it */
    const double bad[] = {0.0, -1.0, NAN, INFINITY};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
        governor_init(&g, bad[i], LEVELS);
        for (int k = 0; k < 50; k++)
            governor_observe(&g, 0, 100.0, true);
        CHECK(governor_level(&g) == 0 && governor_changes(&g) == 0, "budget %g", bad[i]);
    }
}

CHECK_TEST(late_measurements_of_old_levels_are_not_misread)
{
    governor g;
    governor_init(&g, BUDGET, LEVELS);
    governor_set_prior(&g, COST, LEVELS);
    governor_observe(&g, 0, 2.0 * BUDGET, true);
    governor_observe(&g, 0, 2.0 * BUDGET, true);
    int level = governor_level(&g);
    CHECK(level == 3, "2x over: level %d", level); /* 0.47 × 32 = 15.0 > 0.85 × 16; 0.33 × 32 fits */
    /* frames still in flight from level 0 arrive: they must not push it further down */
    for (int i = 0; i < 10; i++)
        governor_observe(&g, 0, 2.0 * BUDGET, true);
    CHECK(governor_level(&g) == level && governor_changes(&g) == 1, "level %d, %d changes",
          governor_level(&g), governor_changes(&g));
    /* cheap frames measured at a lower rung do not count as room at this one */
    for (int i = 0; i < 200; i++)
        governor_observe(&g, LEVELS - 1, 0.1, true);
    CHECK(governor_level(&g) == level && governor_changes(&g) == 1, "level %d", governor_level(&g));
    printf("# 2x over: 0 -> %d; 10 late frames of level 0 and 200 of level %d: still %d, 1 change\n",
           level, LEVELS - 1, governor_level(&g));
}

CHECK_TEST(deterministic)
{
    sim a, b;
    sim_init(&a, false);
    sim_init(&b, false);
    for (int i = 0; i < 1000; i++) {
        double load = BUDGET * (1.0 + 3.0 * (i / 250 % 2));
        sim_run(&a, 1, load, 0.1);
        sim_run(&b, 1, load, 0.1);
        if (governor_level(&a.g) != governor_level(&b.g)) {
            CHECK(0, "frame %d: %d vs %d", i, governor_level(&a.g), governor_level(&b.g));
            break;
        }
    }
    CHECK(governor_changes(&a.g) == governor_changes(&b.g), "");
    CHECK(governor_smoothed_ms(&a.g) == governor_smoothed_ms(&b.g), "");
}

CHECK_TEST(prior_with_gaps_is_filled_on_one_scale)
{
    governor g;
    governor_init(&g, BUDGET, 5);
    const double cost[5] = {NAN, 40.0, 0.0, 10.0, -1.0}; /* level 0, 2 and 4 unknown */
    governor_set_prior(&g, cost, 4);
    CHECK_NEAR(g.rel[0], 40.0 / 0.7, 1e-9);
    CHECK_NEAR(g.rel[1], 40.0, 1e-12);
    CHECK_NEAR(g.rel[2], 28.0, 1e-9);
    CHECK_NEAR(g.rel[3], 10.0, 1e-12);
    CHECK_NEAR(g.rel[4], 7.0, 1e-9);
    const double none[2] = {NAN, 0.0};
    governor_init(&g, BUDGET, 3);
    governor_set_prior(&g, none, 2);
    CHECK_NEAR(g.rel[2], 0.49, 1e-12); /* nothing given: the default prior */
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
