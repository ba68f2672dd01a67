/*
 * vgroup.h (private) - the map as localize.c's vote loop reads it: the vectors that can
 * vote into the raster, merged into groups and indexed by position, rebuilt every run.
 *
 * Why. A pair <reading, map vector> votes at map point - R(h) * reading. Two map
 * vectors a few millimetres apart put their votes in the same raster cell or the next
 * one, and the blur smears them together anyway; a map that keeps seeing the same wall
 * (a laser, 360 readings a scan) holds dozens of such vectors per cell. A group is the
 * vectors of one group_mm square: it votes once per heading, from its centroid, with the
 * weight of how many of its members pass the normal gate under that heading. The gate
 * is still applied to every member's own normal, so what votes is what the plain method
 * votes; only where it lands moves, by less than a group square. The cost per reading
 * then follows the number of occupied squares near it, not the map's density.
 *
 * Index. Groups are sorted by normal sector, then tile row (row_cells squares tall), then
 * by x square, then by y square, so that the groups a reading can reach, a box around where its votes
 * land, are a few runs found by binary search (hl_vgroups_gather): a search
 * touches the part of the map near the robot, not all of it.
 *
 * merge = false (group_mm 0 in the parameters) keeps every vector its own group at its
 * exact position, indexed the same way: the plain method's votes, bit for bit.
 *
 * Memory comes from hl_vgroups_init only.
 */
#ifndef HOUGHLOC_CORE_VGROUP_H
#define HOUGHLOC_CORE_VGROUP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc-internal/map.h"

/* Groups never mix normals from different eighths of a turn, so that a reading visits
 * only the sectors its normal gate can reach (3 of 8 with the defaults). */
#define HL_VGROUP_SECTOR_SHIFT 13
#define HL_VGROUP_SECTORS (1 << (16 - HL_VGROUP_SECTOR_SHIFT))

typedef struct hl_vgroups {
    int32_t cell_mm;        /* group square side (the index's cells when merge is off) */
    int32_t row_cells;      /* squares per tile row */
    bool merge;
    uint32_t capacity;      /* map vectors */
    uint32_t axis_cells;    /* the most squares along one side of the box */

    /* the result of hl_vgroups_build */
    uint32_t ngroups;
    int32_t nrows;
    int64_t cell_x0, cell_y0;   /* corner of square (0, 0), mm from the origin */
    int32_t *gx, *gy;       /* [capacity] centroid, 1/256 mm from the origin */
    int32_t *gcx;           /* [capacity] x square of each group: the key within a row */
    uint32_t *first;        /* [capacity + 1] members of group k: normal[first[k] ..
                               first[k + 1] - 1] */
    hl_bam_t *normal;       /* [capacity] the members' normals */
    uint32_t *row_start;    /* groups of sector s, tile row r: from row_start[s * nrows + r]
                               to the next entry */

    /* scratch */
    uint32_t *count;        /* [axis_cells + 1] */
    uint32_t *slot_a, *slot_b;  /* [capacity] vectors in sort order */
    uint32_t *index;        /* [capacity] the map index of each slot */
    int32_t *cx, *cy;       /* [capacity] each slot's square */
    int32_t *sector;        /* [capacity] each slot's normal sector */
    int32_t *row;           /* [capacity] each slot's tile row */
} hl_vgroups_t;

/** Allocates for @p capacity vectors in squares of @p group_mm (8..1000), or, when
 *  @p group_mm is 0, for vectors kept apart (and indexed in squares of 32 mm).
 *  @return false when memory is short; hl_vgroups_free releases what was allocated. */
bool hl_vgroups_init(hl_vgroups_t *g, uint32_t capacity, int32_t group_mm);
void hl_vgroups_free(hl_vgroups_t *g);
size_t hl_vgroups_mem_bytes(const hl_vgroups_t *g);

/**
 * Groups the vectors of map[0 .. n - 1] (n <= capacity) that lie in the box
 * [x_lo, x_hi] x [y_lo, y_hi] (mm, both sides at most 2^21 + 2^16 mm), with positions
 * relative to @p origin_x, @p origin_y. @return the number of groups.
 */
uint32_t hl_vgroups_build(hl_vgroups_t *g, const hl_vector_t *map, uint32_t n,
                          int64_t x_lo, int64_t x_hi, int64_t y_lo, int64_t y_hi,
                          int32_t origin_x, int32_t origin_y);

/** The square (x) or tile row (y) holding a point @p q8 1/256 mm from the origin, of
 *  the last build; below the first, -1; beyond the last, a value past it. */
int32_t hl_vgroups_square_x(const hl_vgroups_t *g, int64_t q8);
int32_t hl_vgroups_row_y(const hl_vgroups_t *g, int64_t q8);

/** The first group of @p sector and tile row @p row (0 .. nrows - 1) whose x square is at
 *  least @p square, and the end of that sector's row. */
uint32_t hl_vgroups_seek(const hl_vgroups_t *g, uint32_t sector, int32_t row,
                         int32_t square);
uint32_t hl_vgroups_row_end(const hl_vgroups_t *g, uint32_t sector, int32_t row);

/**
 * The groups that can pair with one reading under some heading of a search: those whose
 * centroid lands in the raster (@p width_q8 x @p height_q8, 1/256 mm) less the reading's
 * offset (@p tx, @p ty: 1/256 mm, for each of the @p nt headings, @p theta_step apart)
 * under some heading, in the normal sectors that the gate (@p gate, BAM, about the
 * reading's normal under the first heading, @p tn0) can reach. The gate itself is left
 * to the vote loop, member by member. @return how many were listed in @p out.
 */
uint32_t hl_vgroups_gather(const hl_vgroups_t *g, const int32_t *tx, const int32_t *ty,
                           int32_t nt, uint32_t width_q8, uint32_t height_q8,
                           uint32_t theta_step, uint16_t tn0, int32_t gate, uint32_t *out);

#endif
