/*
 * closure_internal.h (private) - loop closure's state, shared by its files: closure.c
 * (the record of stops, their candidates and matches), closure_seek.c (the correlative
 * search for a stop's matches and their agreement) and closure_fit.c (the fit of every
 * stop and the map drawn again at the fitted poses).
 */
#ifndef HOUGHLOC_CORE_CLOSURE_INTERNAL_H
#define HOUGHLOC_CORE_CLOSURE_INTERNAL_H

#include "houghloc-internal/closure.h"
#include "houghloc-internal/corrmatch.h"
#include "houghloc-internal/posegraph.h"

struct hl_closure {
    uint32_t cap;           /* stops recorded at most */
    uint32_t first;         /* the oldest recorded stop's stamp */
    uint32_t count;         /* stops recorded: stamps first .. first + count - 1 */
    uint32_t next;          /* the next stop's stamp (from 1: 0 is no stop's) */
    hl_scan_t *scans;       /* [cap] by stamp % cap: the scan as mapped */
    /* [cap] by stamp - first: */
    hl_pg_pose_t *poses;    /* fitted */
    hl_pose_t *placed;      /* where the stop's vectors lie in the map (poses, rounded, as
                               of the last fit) */
    hl_rng_t *rng_before;   /* the map's culling generator before the stop was drawn */
    double *wall_axis;      /* the walls' axis in the stop's frame, radians (square walls;
                               its scan's, worked out once when recorded rather than a
                               sine and a cosine a reading of every stop at every fit) */
    double *wall_sigma;     /* ... its sigma, radians; 0: the stop says nothing of walls */
    double *path;           /* the path driven to the stop since the record began, mm */
    double closed_path;     /* ... to the newest stop a match was taken for */
    hl_pg_heading_t *headings;  /* [cap] scratch: the stops' headings for a fit */
    bool square_walls;
    double building_axis;   /* radians */
    hl_pg_edge_t *edges;    /* steps and matches, poses by stamp - first */
    uint32_t n_edges, max_edges;
    hl_posegraph_t *graph;
    hl_vector_t *kept;      /* [map_capacity] scratch: the vectors a fit does not redraw */
    uint32_t *kept_stamps;  /* [map_capacity] ... and their stamps */
    uint32_t map_capacity;
    hl_map_t *sub;          /* the map a match is sought in */
    hl_scan_t *query;       /* the scan a match is sought for, thinned (hl_closure_query) */
    hl_corr_t *corr;        /* the correlative search (hl_closure_seek) ... */
    hl_corr_point_t *sub_points, *query_points; /* ... its submap's and query's points */
    struct pending {        /* ... the matches it found for one query, not yet settled */
        uint32_t stamp;
        hl_pose_t found;
        double gate_mm, gate_rad;
    } pending[HL_CLOSURE_MAX_MATCHES];
    uint32_t n_pending, pending_query;
    /* A redraw spread over the scans that follow a fit (hl_closure_fit_spread): */
    bool redrawing;
    uint32_t next_drawn;    /* ... the stamp of the next stop to draw into the shadow map */
    hl_pg_pose_t fit_before, fit_after; /* ... the newest stop fitted, before and after the
                                           fit: the frame change the slam's pose and the
                                           stops recorded meanwhile go through */
    hl_rng_t sub_rng;       /* ... started afresh each time */
    double redraw_mm;       /* a fit is drawn only when it moves a stop this far (0: always) */
    double redraw_stop_mm;  /* ... and then only the stops it moved this far (0: all) */
    bool *to_draw;          /* [cap] by stamp - first: the redraw under way draws the stop
                               again (else its vectors stay where they lie) */
    bool undrawn;           /* the last fit was not drawn: the map (and the slam) are in the
                               frame before it, the fit's poses after it */
};

/* Whether stop @p query found at @p found in stop @p stamp's submap lies within @p gate_mm
 * and @p gate_rad of where the fit has it from that stop (both recorded, at least
 * HL_CLOSURE_GAP apart); *@p said the pose it gives the query from the stop. closure.c. */
bool hl_closure_gate(const hl_closure_t *c, uint32_t stamp, uint32_t query, hl_pose_t found,
                     double gate_mm, double gate_rad, hl_pg_pose_t *said);

/* The record's scan of the stop @p i stops after the oldest recorded (its stamp is
 * first + i; the scans are kept by stamp, round the record). */
static inline hl_scan_t *scan_of(const hl_closure_t *c, uint32_t i)
{
    return &c->scans[(c->first + i) % c->cap];
}

/* Stop @p i's neighbour @p d (-HL_CLOSURE_SIDE..HL_CLOSURE_SIDE) in the submap that stop
 * @p k is matched against: whether it is drawn there (recorded, and HL_CLOSURE_GAP stops
 * or more before k), and its index in *@p q. */
static inline bool submap_stop(uint32_t i, int32_t d, uint32_t k, uint32_t *q)
{
    int64_t at = (int64_t)i + d;
    if (at < 0 || at + HL_CLOSURE_GAP > k)
        return false;
    *q = (uint32_t)at;
    return true;
}

#endif
