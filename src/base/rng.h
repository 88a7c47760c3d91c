/* The ground floor's deterministic RNG (base/rng.c): the simulation's spawn jitter, the
 * procedural textures, tests and tools draw from it. */
#ifndef SBFX_BASE_RNG_H
#define SBFX_BASE_RNG_H

#include <stdint.h>

typedef struct sbfx_rng { uint64_t state; } sbfx_rng;
void sbfx_rng_seed(sbfx_rng *rng, uint64_t seed);
uint32_t sbfx_rng_u32(sbfx_rng *rng);
double sbfx_rng_uniform(sbfx_rng *rng); /* [0,1) */
double sbfx_rng_range(sbfx_rng *rng, double lo, double hi);

#endif
