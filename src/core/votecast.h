/*
 * votecast.h (private) - the vote loop of localize.c: every valid reading against the
 * map's groups (vgroup.h) that pass the normal gate under some heading, each pair voting
 * for map point - R(theta) * reading into the (x, y, theta) raster. A map of lone
 * vectors without vote_once takes votelone.h's loop; the general loop here handles
 * merged groups (a group's weight: how many of its members pass) and vote_once (a
 * reading votes a cell once). Allocation: none (the localizer's buffers).
 */
#ifndef HOUGHLOC_CORE_VOTECAST_H
#define HOUGHLOC_CORE_VOTECAST_H

#include <stdint.h>

#include "houghloc-internal/localize.h"
#include "loc_params.h"
#include "vgroup.h"
#include "votelone.h"

/* The raster and what one run's votes add up to. */
typedef struct hl_vote_ctx {
    int32_t nx, ny, nt;
    uint32_t width_q8, height_q8;   /* raster size in 1/256 mm, < 2^29 */
    uint64_t recip;         /* floor(2^32 / cell) + 1: exact division below 2^21 mm */
    /* the reading's offset under each heading, 1/256 mm (hl_polar_to_xy_q8) */
    int32_t tx[2 * HL_LOC_MAX_HALF_STEPS + 1], ty[2 * HL_LOC_MAX_HALF_STEPS + 1];
    uint32_t votes, pairs;
    uint16_t tag;           /* vote_once: the reading's stamp, index + 1 */
    uint16_t *most;         /* the sparse path's notes of its tiles (tiles.h), or NULL */
    uint32_t ntx;           /* ... tiles a row */
    int32_t cell_q8;
} hl_vote_ctx_t;

/* The localizer's buffers the loop reads and writes. */
typedef struct hl_vote_inputs {
    const hl_vgroups_t *groups;
    uint32_t *cand;         /* the groups one reading can reach */
    int32_t *slice_diff;    /* a group's weights, differenced; zero between readings */
    uint16_t *stamps;       /* vote_once: per cell, the last reading that voted; or NULL */
    hl_votelone_t *lone;    /* the lone vectors' loop, if it has capacity */
    uint16_t *votes;        /* the raster, [nt][ny][nx] */
    const int32_t *range;   /* the valid readings */
    const hl_bam_t *bearing;
    const int16_t *tilt;
    int32_t normal_gate;
} hl_vote_inputs_t;

/** Casts the votes of @p nread readings into the raster of surface @p s; adds the votes
 *  and the pairs that passed the gate to @p c. */
void hl_vote_cast(const hl_vote_inputs_t *in, uint32_t nread, const hl_loc_surface_t *s,
                  hl_vote_ctx_t *c);

#endif
