/* rng.h (internal) - drawing from the core's PCG32 generator (houghloc/rng.h). */
#ifndef HOUGHLOC_INTERNAL_RNG_H
#define HOUGHLOC_INTERNAL_RNG_H

#include <stdint.h>

#include "houghloc/rng.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The generator's state after seeding with @p seed (a map's culling generator starts
 *  from its slam.seed this way). */
void hl_rng_seed(hl_rng_t *rng, uint64_t seed);
uint32_t hl_rng_next(hl_rng_t *rng);
/** Uniform integer in [0, bound), without modulo bias. bound must be > 0. */
uint32_t hl_rng_below(hl_rng_t *rng, uint32_t bound);

#ifdef __cplusplus
}
#endif
#endif
