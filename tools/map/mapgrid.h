/*
 * mapgrid.h - an occupancy grid from a map of tangent vectors, written in the ROS
 * map_server format (a PGM image and a YAML file beside it).
 *
 * Each vector says two things: its surface point is occupied, and the sonar beam that
 * saw it crossed free space from the sensor (range_mm away along the normal) up to the
 * surface. So every vector's ray is traced, Bresenham, from the sensor's cell up to the
 * cell before the surface's cell and marked free; then every surface point's cell is
 * marked occupied (an obstacle seen by one beam wins over another beam passing through).
 * The rest is unknown.
 *
 * Cell (i, j) covers x in [origin_x + i res, origin_x + (i + 1) res), likewise y; the
 * PGM's first row is the top (largest y), as map_server reads it. Values: 0 occupied,
 * 254 free, 205 unknown (map_saver's), which with negate 0, occupied_thresh 0.65 and
 * free_thresh 0.196 read back as occupied, free and unknown.
 */
#ifndef HOUGHLOC_TOOLS_MAPGRID_H
#define HOUGHLOC_TOOLS_MAPGRID_H

#include <stddef.h>
#include <stdint.h>

#include "houghloc/map.h"

#define HL_MAPGRID_OCCUPIED 0
#define HL_MAPGRID_FREE 254
#define HL_MAPGRID_UNKNOWN 205
#define HL_MAPGRID_MARGIN 2                     /* unknown cells around the data */
#define HL_MAPGRID_MAX_CELLS (64u << 20)        /* larger grids are refused */
#define HL_MAPGRID_WHY_LEN 256

typedef struct hl_mapgrid {
    uint32_t width, height;     /* cells */
    double resolution_m;        /* cell side */
    double origin_x_m;          /* world position of the lower-left corner of cell (0, 0) */
    double origin_y_m;
    uint8_t *cells;             /* row-major, row 0 = lowest y (not the PGM's order) */
} hl_mapgrid_t;

/**
 * Builds the grid of @p n vectors at @p resolution_m. The grid spans every surface point
 * and every sensor position, with HL_MAPGRID_MARGIN unknown cells around them.
 * @param[out] g    allocated here (g->cells), freed by hl_mapgrid_free.
 * @param[out] why  on failure, one line (HL_MAPGRID_WHY_LEN bytes).
 * @return HL_OK; HL_ERR_EMPTY for n == 0; HL_ERR_ARG for a resolution that is not a
 *         positive finite number or NULL pointers; HL_ERR_CAPACITY when the grid would
 *         exceed HL_MAPGRID_MAX_CELLS cells; HL_ERR_NOMEM.
 */
hl_status_t hl_mapgrid_build(const hl_vector_t *v, size_t n, double resolution_m,
                             hl_mapgrid_t *g, char *why);

/** The cell's value; (i, j) must be inside the grid. */
uint8_t hl_mapgrid_at(const hl_mapgrid_t *g, uint32_t i, uint32_t j);

/**
 * The cell holding the world point (x_mm, y_mm).
 * @return false (i, j untouched) when the point is outside the grid.
 */
bool hl_mapgrid_cell(const hl_mapgrid_t *g, double x_mm, double y_mm, uint32_t *i,
                     uint32_t *j);

/**
 * Writes the PGM (binary P5, maxval 255, top row first) to @p path.
 * @return HL_OK, or HL_ERR_OS with a line naming the file in @p why.
 */
hl_status_t hl_mapgrid_write_pgm(const hl_mapgrid_t *g, const char *path, char *why);

/**
 * Writes the map_server YAML to @p path: image (@p image, a name relative to the YAML's
 * folder; double-quoted unless it is only letters, digits and "._-/+"), mode trinary,
 * resolution, origin [x, y, 0], negate 0, occupied_thresh 0.65, free_thresh 0.196.
 * @return HL_OK, or HL_ERR_OS with a line naming the file in @p why.
 */
hl_status_t hl_mapgrid_write_yaml(const hl_mapgrid_t *g, const char *path, const char *image,
                                  char *why);

/** Frees the cells. Accepts a grid that never built. */
void hl_mapgrid_free(hl_mapgrid_t *g);

#endif
