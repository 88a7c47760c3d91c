/* The frame-budget governor (docs/design.md §6): which rung of a quality ladder to render next, from
 * GPU times that arrive a few frames late. Pure logic: no GL, no clock, no allocation, no
 * randomness — the same measurements give the same levels (tests/unit/test_governor.c drives
 * it with a synthetic cost model).
 *
 * Levels: 0 is the top (most accurate), level_count - 1 the last resort. Each measurement is
 * tagged with the level its frame was rendered at; only measurements of the current level move
 * the level (a late one from a level already left only teaches the cost model), and an invalid
 * one (disjoint, lost, NaN, negative, unknown level) is ignored entirely.
 *
 * Cost model: rel[i], the relative cost of level i (a prior: given by the ladder through
 * governor_set_prior, else 0.7^i), corrected by what was measured: when the governor leaves
 * level a for b it remembers a's smoothed time, and once b has settled it rescales the prior
 * between a and b so that rel[a] / rel[b] is the measured ratio. The cost of any level j at
 * the present load is estimated as  est(j) = smoothed × rel[j] / rel[current]  — it follows the
 * load, so a ladder walked down under a heavy load is walked up again when the load falls.
 *
 * Down, at once: when GOVERNOR_DOWN_SAMPLES consecutive measurements of the current level are
 * over the budget (one spike does not move it), or its smoothed time (the median of its last
 * GOVERNOR_WINDOW measurements: isolated frames stretched by other jobs move neither it nor the
 * estimates) is after GOVERNOR_LEARN_SAMPLES of them — to the first level below whose estimate fits
 * GOVERNOR_DOWN_FILL × budget (from the least time of the over-budget run, when a run moved it):
 * several rungs at once when far over; at least one.
 * Up, slowly: one rung, after a run of GOVERNOR_UP_FRAMES (doubled per failed attempt at that
 * rung) consecutive measurements at which est(level - 1) × GOVERNOR_UP_MARGIN fits the budget.
 * A load on the boundary between two rungs (the upper just over, the lower under) therefore
 * never flip-flops: the upper rung's learned estimate stays over budget / GOVERNOR_UP_MARGIN.
 * An ascent that had to come back down within GOVERNOR_SETTLE_FRAMES of it doubles that rung's
 * wait (up to GOVERNOR_UP_FRAMES_MAX): noise near a boundary costs a bounded number of changes.
 *
 * A budget that is not a finite positive number disables the governor: it stays at level 0. */
#ifndef SBFX_GOVERNOR_H
#define SBFX_GOVERNOR_H

#include <stdbool.h>

#define GOVERNOR_MAX_LEVELS 16
#define GOVERNOR_WINDOW 5           /* smoothed: the median of the last measurements */
#define GOVERNOR_DOWN_SAMPLES 2     /* consecutive measurements over budget that move it */
#define GOVERNOR_DOWN_FILL 0.85     /* stepping down aims at this share of the budget */
#define GOVERNOR_UP_MARGIN 1.15     /* the upper rung's estimate × this must fit */
#define GOVERNOR_UP_FRAMES 30       /* run of frames with room before one rung up */
#define GOVERNOR_UP_FRAMES_MAX 960  /* after repeated failed ascents */
#define GOVERNOR_SETTLE_FRAMES 60   /* an ascent undone within this many frames failed */
#define GOVERNOR_LEARN_SAMPLES 4    /* measurements of a new level before its ratio is learned */

typedef struct governor {
    double budget_ms;
    int level_count;
    int level;                      /* rendered next */
    double rel[GOVERNOR_MAX_LEVELS];        /* relative cost (prior corrected by measurements) */
    double last_ms[GOVERNOR_MAX_LEVELS];    /* last smoothed time seen at each level (0: never) */
    int up_wait[GOVERNOR_MAX_LEVELS];       /* frames with room needed to go up to level i */
    double window[GOVERNOR_WINDOW]; /* the current level's last measurements */
    double smoothed;                /* their median */
    int samples;                    /* measurements of the current level since it was chosen */
    int room_run;                   /* consecutive measurements with room for level - 1 */
    int over_run;                   /* consecutive measurements over budget */
    double over_min;                /* the least of them */
    int from_level;                 /* the level left for this one (-1: none) */
    double from_ms;                 /* its smoothed time when left */
    bool learned;                   /* the ratio from_level / level is in rel[] */
    bool went_up;                   /* this level was reached by an ascent */
    int frames_here;                /* valid measurements since this level was chosen */
    long observed;                  /* valid measurements in all */
    int frames_over;                /* valid measurements over budget */
    int changes;                    /* level changes */
} governor;

void governor_init(governor *g, double budget_ms, int level_count);
/* The ladder's relative costs (e.g. the bench's milliseconds), level 0 first; any positive
 * scale. Levels without a cost (count short, or not finite and positive) are filled in at the
 * default step (0.7 a rung) from their neighbour above (below, for those above the first
 * cost). Call after init. */
void governor_set_prior(governor *g, const double *cost, int count);
void governor_observe(governor *g, int level_rendered, double gpu_ms, bool valid);
int governor_level(const governor *g);
double governor_smoothed_ms(const governor *g);
int governor_frames_over(const governor *g);
int governor_changes(const governor *g);
/* The current estimate of level i's time at the present load (0 before any measurement). */
double governor_estimate_ms(const governor *g, int level);

#endif
