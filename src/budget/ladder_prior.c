/* The governor's prior (governor_set_prior) for a budget's ladder: the accuracy bench's time of
 * each level that the default ladder names (src/budget/ladder_default.h, make ladder); levels it does
 * not name, and levels of detail, are filled in by the governor at its default step (0.7 a
 * rung): what a level of detail saves depends on the load (the bench's explosion, 159
 * particles, shows no saving beyond the noise; a barrage of 3800 does), so the explosion's time
 * is no prior for it. The relative costs let the first step down skip as many rungs as the
 * measured overrun calls for. */
#include "budget/governor.h"
#include "budget/ladder_default.h"
#include "budget/budget.h"

void sbfx_ladder_prior(const sbfx_quality *ladder, int count, governor *g)
{
    double cost[GOVERNOR_MAX_LEVELS] = {0};
    for (int k = 0; k < SBFX_LADDER_DEFAULT_COUNT; k++) {
        sbfx_quality q;
        char err[128];
        if (sbfx_quality_parse(sbfx_ladder_default[k], &q, err, sizeof(err)) != SBFX_OK ||
            !sbfx_quality_resolve(&q, NULL, 0) || q.lod_particles)
            continue;
        for (int i = 0; i < count && i < GOVERNOR_MAX_LEVELS; i++)
            if (sbfx_quality_equal(&q, &ladder[i])) cost[i] = sbfx_ladder_default_ms[k];
    }
    governor_set_prior(g, cost, count < GOVERNOR_MAX_LEVELS ? count : GOVERNOR_MAX_LEVELS);
}
