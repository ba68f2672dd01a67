/*
 * rng.h - the seeded pseudo-random generator behind every random choice in the core
 * (map culling, test-scene generation). PCG32 (O'Neill 2014): 64-bit state, 32-bit
 * output, deterministic across platforms, so a run is reproducible from its seed.
 */
#ifndef HOUGHLOC_RNG_H
#define HOUGHLOC_RNG_H

#include <stdint.h>

#include "houghloc/export.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_rng {
    uint64_t state;
    uint64_t inc;
} hl_rng_t;

HL_API void hl_rng_seed(hl_rng_t *rng, uint64_t seed);
HL_API uint32_t hl_rng_next(hl_rng_t *rng);
/** Uniform integer in [0, bound), without modulo bias. bound must be > 0. */
HL_API uint32_t hl_rng_below(hl_rng_t *rng, uint32_t bound);

#ifdef __cplusplus
}
#endif
#endif
