/* The default quality ladder of the frame budget, most accurate first (sbfx_quality_parse
 * names). PROVISIONAL: from the accuracy bench's numbers in README "What accuracy costs"
 * (exact 1/4 nearest-depth 0.128 levels, bilinear 0.126 but worse at silhouettes, exact 1/8
 * 0.28, light per particle +70 % error for half the particle pass); budget-governor's `make
 * ladder` replaces this file with the Pareto front it measures. */
#ifndef SBFX_LADDER_DEFAULT_H
#define SBFX_LADDER_DEFAULT_H

static const char *const sbfx_ladder_default[] = {
    "exact/4/nd", "exact/4/bl", "exact/8/nd", "exact/8/bl", "exact/8/bl/lpp", "exact/8/bl/lpp/lod256",
};

#endif
