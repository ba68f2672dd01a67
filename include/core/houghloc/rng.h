/*
 * rng.h - the seeded pseudo-random generator behind every random choice in the core (map
 * culling) and in the tests' and the laboratory's made-up inputs. PCG32 (XSH RR variant,
 * after O'Neill, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
 * Algorithms for Random Number Generation", 2014): 64-bit state, 32-bit output,
 * deterministic across platforms, so a run is reproducible from its seed.
 *
 * Header-only: the state is a value (hl_slam_state_t carries the map's), and drawing from
 * it needs nothing of the library.
 */
#ifndef HOUGHLOC_RNG_H
#define HOUGHLOC_RNG_H

#include <stdint.h>

/* The state; a seeded state's inc is odd. */
typedef struct hl_rng {
    uint64_t state;
    uint64_t inc;
} hl_rng_t;

static inline uint32_t hl_rng_next(hl_rng_t *rng)
{
    uint64_t old = rng->state;
    rng->state = old * 6364136223846793005ULL + rng->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((0u - rot) & 31u));
}

/** The generator's state after seeding with @p seed. */
static inline void hl_rng_seed(hl_rng_t *rng, uint64_t seed)
{
    rng->state = 0;
    rng->inc = (seed << 1u) | 1u;
    (void)hl_rng_next(rng);
    rng->state += 0x853c49e6748fea9bULL ^ seed;
    (void)hl_rng_next(rng);
}

/** Uniform integer in [0, bound), without modulo bias. bound must be > 0. */
static inline uint32_t hl_rng_below(hl_rng_t *rng, uint32_t bound)
{
    /* Reject the low values that would make the modulo biased. */
    uint32_t threshold = (0u - bound) % bound;
    for (;;) {
        uint32_t r = hl_rng_next(rng);
        if (r >= threshold)
            return r % bound;
    }
}

#endif
