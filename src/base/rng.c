/* Small deterministic RNG shared by simulation, tests and tools: SplitMix64 (Steele, Lea,
 * Flood 2014). One 64-bit word of state fits sbfx_rng as declared, every seed (0 included) gives
 * a full-period sequence, and the output passes BigCrush — plenty for spawn jitter and tests.
 * Same seed, same sequence, on every platform (no floating point in the state update). */
#include <math.h>
#include "base/rng.h"

static uint64_t splitmix64_next(sbfx_rng *rng)
{
    uint64_t z = (rng->state += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

void sbfx_rng_seed(sbfx_rng *rng, uint64_t seed)
{
    if (rng) rng->state = seed;
}

uint32_t sbfx_rng_u32(sbfx_rng *rng)
{
    if (!rng) return 0;
    return (uint32_t)(splitmix64_next(rng) >> 32); /* the high bits are the best mixed */
}

double sbfx_rng_uniform(sbfx_rng *rng)
{
    if (!rng) return 0.0;
    /* 53 random bits scaled by 2^-53: every value is exact and < 1. */
    return (double)(splitmix64_next(rng) >> 11) * 0x1.0p-53;
}

double sbfx_rng_range(sbfx_rng *rng, double lo, double hi)
{
    /* lo + (hi - lo) * u can round up to hi for some u; keep the interval half-open. */
    double x = lo + (hi - lo) * sbfx_rng_uniform(rng);
    return (x < hi || !(hi > lo)) ? x : nextafter(hi, lo);
}
