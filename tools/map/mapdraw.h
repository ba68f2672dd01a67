/*
 * mapdraw.h - a picture of a map of tangent vectors (cairo, PNG): each vector a short
 * stroke along the surface it saw, optionally a tick along its normal toward the sensor,
 * and optionally paths (the daemon's POSE, the ground truth) over it.
 *
 * World x to the right, y up; a light grid every metre (every 10 m on a large map), a
 * 1 m scale bar and a legend in the top-left corner.
 */
#ifndef HOUGHLOC_TOOLS_MAPDRAW_H
#define HOUGHLOC_TOOLS_MAPDRAW_H

#include <stdbool.h>
#include <stddef.h>

#include "houghloc/map.h"

#define HL_MAPDRAW_WHY_LEN 256
#define HL_MAPDRAW_MIN_PX 200
#define HL_MAPDRAW_MAX_PX 8000

/** A path drawn over the map. */
typedef struct hl_mapdraw_path {
    const hl_pose_t *poses;     /* in the map frame */
    size_t n;
    const char *label;          /* in the legend */
    double rgb[3];              /* 0..1 */
} hl_mapdraw_path_t;

typedef struct hl_mapdraw_opts {
    int size_px;                /* the longer side of the drawing area, HL_MAPDRAW_MIN_PX ..
                                   HL_MAPDRAW_MAX_PX */
    bool normals;               /* draw a tick toward each vector's sensor */
} hl_mapdraw_opts_t;

/**
 * Draws @p n vectors and @p npaths paths into a PNG at @p path. The view spans every
 * surface point and every path pose.
 * @param[out] why  on failure, one line naming the file (HL_MAPDRAW_WHY_LEN bytes).
 * @return HL_OK; HL_ERR_ARG for a size out of range or nothing to draw; HL_ERR_OS when
 *         cairo cannot create or write the picture.
 */
hl_status_t hl_mapdraw_png(const char *path, const hl_vector_t *v, size_t n,
                           const hl_mapdraw_path_t *paths, size_t npaths,
                           const hl_mapdraw_opts_t *opts, char *why);

#endif
