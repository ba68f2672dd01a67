/*
 * rng.h - the state of the seeded pseudo-random generator behind every random choice in
 * the core (map culling). PCG32 (O'Neill 2014): 64-bit state, 32-bit output,
 * deterministic across platforms, so a run is reproducible from its seed. Drawing from it
 * is the core's own business (houghloc-internal/rng.h).
 */
#ifndef HOUGHLOC_RNG_H
#define HOUGHLOC_RNG_H

#include <stdint.h>

/* The state (hl_slam_state_t.cull_rng carries it; a seeded state's inc is odd). */
typedef struct hl_rng {
    uint64_t state;
    uint64_t inc;
} hl_rng_t;

#endif
