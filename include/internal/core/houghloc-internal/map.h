/*
 * map.h (internal) - making and changing a map of tangent vectors: the map module's
 * params, its culls and stamps, for the tracker (slam.c), loop closure and the
 * laboratory. A program reads a tracker's map through houghloc/map.h.
 *
 * The map holds at most `capacity` vectors (the paper used 1500). When a new vector
 * arrives at a full map, one vector chosen uniformly at random among the old ones and
 * the new one is dropped, so old information "ages" out at random, as in the paper.
 * The random choice comes from a PCG32 held in the map, seeded at creation.
 *
 * Ownership: hl_map_create_with (and hl_map_create) allocates everything; nothing else
 * allocates.
 */
#ifndef HOUGHLOC_INTERNAL_MAP_H
#define HOUGHLOC_INTERNAL_MAP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc/map.h"
#include "houghloc/rng.h"
#include "houghloc/scan.h"
#include "houghloc/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_MAP_MAX_PER_PLACE 1000u
#define HL_MAP_MIN_SQUARE_MM 10
#define HL_MAP_MAX_SQUARE_MM 1000
#define HL_MAP_MAX_CHOICES 64
#define HL_MAP_NEAR_MAX 64      /* a round place's vectors counted at most: the lowest
                                   slots */
/* The evidence cull's confirm distance (was slam.confirm_mm): 60-150 mm measured, 100
 * best (docs/design/expert-keys.md). */
#define HL_MAP_CONFIRM_MM 100

/*
 * What a map is made with: its capacity, its culling generator's seed, and how it culls
 * (all fixed for the map's life). Not in the paper, each off by default:
 *  - the density bound (per_place): at most per_place vectors of one place, a square_mm
 *    square seen from one side (normals in one eighth of a turn). A new vector for a full
 *    place takes the place of one of its vectors, or is dropped, chosen uniformly at
 *    random among them and it; the capacity then spans more of a building instead of
 *    holding the same wall many times over (a laser re-sees every wall on every scan).
 *    Round places (round_places): the place of a new vector is the disc of the square's
 *    area about it (radius square_mm / sqrt(pi)), its normals within a sixteenth of a
 *    turn of the new one's (at most HL_MAP_NEAR_MAX of them counted, the lowest slots,
 *    so that the choice depends on the vectors alone): a bound that lies the same way in
 *    any frame the map is drawn in, where squares cut a wall differently as the frame
 *    turns;
 *  - the evidence cull (cull_choices > 1): each scan added by hl_map_add_scan first
 *    confirms the map vectors it agrees with (a new vector within confirm_mm, normals
 *    within 30 degrees), and a full map drops the least confirmed of cull_choices
 *    vectors drawn at random for each new one, instead of one drawn uniformly. A sonar's
 *    spurious echoes (multipath, side lobes) are seldom seen twice, a wall's echoes
 *    often: the capacity goes to surfaces. The new vector is always kept. The counts are
 *    not saved (hl_map_restore starts them at 0);
 *  - the crowding cull (cull_crowded, with cull_choices > 1 and the density bound;
 *    instead of the evidence cull): a full map drops, for each new vector, the most
 *    crowded of cull_choices vectors drawn at random: the one with the most vectors in
 *    its square of crowd_square_mm (0: its density-bound place and the 8 squares around
 *    it, or with round places the disc of three times their radius, at most
 *    HL_MAP_NEAR_MAX), seen from the same side. The capacity then spreads over every
 *    surface seen rather than over how often each was seen, so a corridor driven once
 *    keeps its walls in a map of a whole building (a laser's: the global search needs
 *    every place). In
 *    the 3 x 3 places every wall held at the density bound is equally crowded, so ties
 *    go at random and a place seen once still thins out as fast as one seen always; a
 *    square a few places wide tells a thinned wall from a full one.
 * Every choice depends only on the vectors and the generator, so a restored map
 * continues exactly.
 */
typedef struct hl_map_params {
    uint32_t capacity;          /* vectors, 1..HL_MAP_MAX_CAPACITY */
    uint64_t seed;              /* seeds the culling generator; default 1 */
    uint32_t per_place;         /* 0 (no bound, the default) .. HL_MAP_MAX_PER_PLACE */
    int32_t square_mm;          /* HL_MAP_MIN_SQUARE_MM .. HL_MAP_MAX_SQUARE_MM when
                                   per_place > 0; default 50 */
    uint32_t cull_choices;      /* 1 (the paper's uniform cull, the default) ..
                                   HL_MAP_MAX_CHOICES */
    int32_t confirm_mm;         /* 1 .. HL_MAP_MAX_SQUARE_MM for the evidence cull;
                                   default 100 */
    bool cull_crowded;          /* the crowding cull instead; default false */
    int32_t crowd_square_mm;    /* 0 (the default), or HL_MAP_MIN_SQUARE_MM ..
                                   HL_MAP_MAX_SQUARE_MM */
    bool round_places;          /* the density bound's place is round: the vectors within
                                   a disc of the square's area about the new one, normals
                                   within a sixteenth of a turn of its (the default);
                                   false: squares along the map frame's axes */
} hl_map_params_t;

/** Fills @p p with the defaults above: the paper's map of 1,500 vectors. */
void hl_map_params_default(hl_map_params_t *p);
/** A one-line description of what is wrong with @p p, or NULL if nothing. */
const char *hl_map_params_error(const hl_map_params_t *p);

/**
 * A map made with @p p (hl_map_params_t), empty.
 * @return the map, or NULL on bad params (hl_map_params_error) or out of memory.
 */
hl_map_t *hl_map_create_with(const hl_map_params_t *p);
/** The paper's map: @p capacity vectors culled uniformly at random, the generator seeded
 *  with @p seed (hl_map_create_with with the other params at their defaults). */
hl_map_t *hl_map_create(uint32_t capacity, uint64_t seed);
/** Frees the map. Accepts NULL. */
void hl_map_destroy(hl_map_t *map);

/** Removes every vector; the culling generator keeps its state. */
void hl_map_clear(hl_map_t *map);

/**
 * Adds one vector, culling when full as the map was made to (hl_map_params_t).
 * @return HL_OK, HL_ERR_RANGE when the vector's fields are out of range (not added).
 */
hl_status_t hl_map_add(hl_map_t *map, const hl_vector_t *v);

/**
 * Transforms the valid readings of @p scan, taken at @p pose, into world tangent
 * vectors and adds them (paper, section 6: shifted to the computed position and rotated
 * by the computed orientation). Readings whose surface point falls outside
 * HL_COORD_MAX_MM are skipped.
 * @param[out] added  number of vectors added; may be NULL.
 */
hl_status_t hl_map_add_scan(hl_map_t *map, const hl_scan_t *scan, hl_pose_t pose,
                            uint32_t *added);

/** The tangent vector for one reading at a pose. @return false if out of range. */
bool hl_vector_from_reading(hl_pose_t pose, const hl_reading_t *r, hl_vector_t *out);
/** The culling generator's state, for saving. */
hl_rng_t hl_map_rng(const hl_map_t *map);

/**
 * Replaces the contents with @p n saved vectors, a version and a culling state.
 * @return HL_ERR_CAPACITY when n > capacity, HL_ERR_RANGE when a vector is out of range
 *         or the version above HL_COUNT_MAX; on error the map is unchanged.
 */
hl_status_t hl_map_restore(hl_map_t *map, const hl_vector_t *vectors, uint32_t n,
                           uint64_t version, hl_rng_t rng);

/**
 * Exchanges the contents of @p a and @p b (vectors, stamps, culling state and indexes),
 * maps made with the same capacity and settings (the caller's promise: a map drawn
 * aside, in the background, then put in place at once). @p a's version then differs
 * from both versions before, so that its readers see a change (unless both were at
 * HL_COUNT_MAX, where versions stop).
 */
void hl_map_swap(hl_map_t *a, hl_map_t *b);

/*
 * Stamps. Each vector keeps the stamp the map had when it was added (a stop's number, for
 * loop closure: slam.h), so that a fit of the stops can tell which vectors it draws
 * again. Restored vectors have stamp 0.
 */
/** Vectors added from now on get @p stamp. */
void hl_map_set_stamp(hl_map_t *map, uint32_t stamp);
/** The first @p n vectors (at most the count) get @p stamps: those they had before a
 *  restore. */
void hl_map_restore_stamps(hl_map_t *map, const uint32_t *stamps, uint32_t n);
/** Each vector's stamp, in the order of hl_map_vectors. */
const uint32_t *hl_map_stamps(const hl_map_t *map);

/** Bytes allocated by the map. */
size_t hl_map_mem_bytes(const hl_map_t *map);

#ifdef __cplusplus
}
#endif
#endif
