/*
 * mapgrid.c - occupancy grid from tangent vectors, ROS map_server files (mapgrid.h).
 */
#include "mapgrid.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/version.h"

/* Cells are on a global lattice of side res_mm with cell k covering [k res, (k+1) res);
 * the grid keeps the lattice index of its column 0 and row 0. */
static int64_t lattice(double mm, double res_mm)
{
    return (int64_t)floor(mm / res_mm);
}

static void grid_lattice0(const hl_mapgrid_t *g, int64_t *i0, int64_t *j0)
{
    double res_mm = g->resolution_m * 1000.0;
    *i0 = (int64_t)llround(g->origin_x_m * 1000.0 / res_mm);
    *j0 = (int64_t)llround(g->origin_y_m * 1000.0 / res_mm);
}

bool hl_mapgrid_cell(const hl_mapgrid_t *g, double x_mm, double y_mm, uint32_t *i, uint32_t *j)
{
    int64_t i0, j0;
    grid_lattice0(g, &i0, &j0);
    double res_mm = g->resolution_m * 1000.0;
    int64_t ci = lattice(x_mm, res_mm) - i0, cj = lattice(y_mm, res_mm) - j0;
    if (ci < 0 || cj < 0 || ci >= (int64_t)g->width || cj >= (int64_t)g->height)
        return false;
    *i = (uint32_t)ci;
    *j = (uint32_t)cj;
    return true;
}

uint8_t hl_mapgrid_at(const hl_mapgrid_t *g, uint32_t i, uint32_t j)
{
    return g->cells[(size_t)j * g->width + i];
}

static void set_cell(hl_mapgrid_t *g, uint32_t i, uint32_t j, uint8_t value)
{
    g->cells[(size_t)j * g->width + i] = value;
}

/* Marks free every cell of the Bresenham line from (i0, j0) to (i1, j1) but the last. */
static void trace_free(hl_mapgrid_t *g, int64_t i0, int64_t j0, int64_t i1, int64_t j1)
{
    int64_t di = i1 > i0 ? i1 - i0 : i0 - i1, dj = j1 > j0 ? j1 - j0 : j0 - j1;
    int64_t si = i0 < i1 ? 1 : -1, sj = j0 < j1 ? 1 : -1;
    int64_t err = di - dj;
    while (i0 != i1 || j0 != j1) {
        set_cell(g, (uint32_t)i0, (uint32_t)j0, HL_MAPGRID_FREE);
        int64_t e2 = 2 * err;
        if (e2 > -dj) {
            err -= dj;
            i0 += si;
        }
        if (e2 < di) {
            err += di;
            j0 += sj;
        }
    }
}

hl_status_t hl_mapgrid_build(const hl_vector_t *v, size_t n, double resolution_m,
                             hl_mapgrid_t *g, char *why)
{
    char dummy[HL_MAPGRID_WHY_LEN];
    why = why ? why : dummy;
    if (!g || (!v && n > 0) || !(resolution_m > 0) || !isfinite(resolution_m))
        return snprintf(why, HL_MAPGRID_WHY_LEN, "bad grid arguments"), HL_ERR_ARG;
    *g = (hl_mapgrid_t){ .resolution_m = resolution_m };
    if (n == 0)
        return snprintf(why, HL_MAPGRID_WHY_LEN, "the map holds no vector"), HL_ERR_EMPTY;
    double res_mm = resolution_m * 1000.0;
    int64_t imin = INT64_MAX, imax = INT64_MIN, jmin = INT64_MAX, jmax = INT64_MIN;
    for (size_t k = 0; k < n; k++) {
        hl_mm_t sx, sy;
        hl_vector_origin(&v[k], &sx, &sy);
        int64_t is[2] = { lattice(v[k].x_mm, res_mm), lattice(sx, res_mm) };
        int64_t js[2] = { lattice(v[k].y_mm, res_mm), lattice(sy, res_mm) };
        for (int e = 0; e < 2; e++) {
            imin = is[e] < imin ? is[e] : imin;
            imax = is[e] > imax ? is[e] : imax;
            jmin = js[e] < jmin ? js[e] : jmin;
            jmax = js[e] > jmax ? js[e] : jmax;
        }
    }
    imin -= HL_MAPGRID_MARGIN;
    jmin -= HL_MAPGRID_MARGIN;
    uint64_t w = (uint64_t)(imax + HL_MAPGRID_MARGIN - imin + 1);
    uint64_t h = (uint64_t)(jmax + HL_MAPGRID_MARGIN - jmin + 1);
    if (w * h > HL_MAPGRID_MAX_CELLS)
        return snprintf(why, HL_MAPGRID_WHY_LEN,
                        "the map spans %.1f x %.1f m: %llu x %llu cells at %g m, more than %u; "
                        "use a coarser --resolution",
                        (double)w * resolution_m, (double)h * resolution_m,
                        (unsigned long long)w, (unsigned long long)h, resolution_m,
                        HL_MAPGRID_MAX_CELLS),
               HL_ERR_CAPACITY;
    g->cells = malloc((size_t)(w * h));
    if (!g->cells)
        return snprintf(why, HL_MAPGRID_WHY_LEN, "out of memory"), HL_ERR_NOMEM;
    memset(g->cells, HL_MAPGRID_UNKNOWN, (size_t)(w * h));
    g->width = (uint32_t)w;
    g->height = (uint32_t)h;
    g->origin_x_m = (double)imin * resolution_m;
    g->origin_y_m = (double)jmin * resolution_m;

    for (size_t k = 0; k < n; k++) {
        hl_mm_t sx, sy;
        hl_vector_origin(&v[k], &sx, &sy);
        trace_free(g, lattice(sx, res_mm) - imin, lattice(sy, res_mm) - jmin,
                   lattice(v[k].x_mm, res_mm) - imin, lattice(v[k].y_mm, res_mm) - jmin);
    }
    for (size_t k = 0; k < n; k++)
        set_cell(g, (uint32_t)(lattice(v[k].x_mm, res_mm) - imin),
                 (uint32_t)(lattice(v[k].y_mm, res_mm) - jmin), HL_MAPGRID_OCCUPIED);
    return HL_OK;
}

static hl_status_t os_error(const char *path, const char *what, char *why)
{
    snprintf(why, HL_MAPGRID_WHY_LEN, "%s: %s: %s", path, what, strerror(errno));
    return HL_ERR_OS;
}

static hl_status_t close_checked(FILE *f, const char *path, char *why)
{
    bool bad = ferror(f) != 0;
    if (fclose(f) != 0 || bad)
        return os_error(path, "write error", why);
    return HL_OK;
}

hl_status_t hl_mapgrid_write_pgm(const hl_mapgrid_t *g, const char *path, char *why)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return os_error(path, "cannot create", why);
    fprintf(f, "P5\n# CREATOR: houghloc-map %s %.3f m/pix\n%u %u\n255\n", HL_VERSION,
            g->resolution_m, g->width, g->height);
    for (uint32_t r = 0; r < g->height; r++)    /* top row first: the largest y */
        fwrite(&g->cells[(size_t)(g->height - 1 - r) * g->width], 1, g->width, f);
    return close_checked(f, path, why);
}

/* Writes @p s as a YAML scalar: as it is when that is safe, else double-quoted. */
static void yaml_scalar(FILE *f, const char *s)
{
    bool plain = *s != '\0';
    for (const char *c = s; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') ||
              strchr("._-/+", *c)))
            plain = false;
    if (plain) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        if (*c == '"' || *c == '\\')
            fprintf(f, "\\%c", *c);
        else if (*c < 0x20 || *c == 0x7f)
            fprintf(f, "\\x%02x", *c);
        else
            fputc(*c, f);
    }
    fputc('"', f);
}

hl_status_t hl_mapgrid_write_yaml(const hl_mapgrid_t *g, const char *path, const char *image,
                                  char *why)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return os_error(path, "cannot create", why);
    fputs("image: ", f);
    yaml_scalar(f, image);
    fprintf(f,
            "\n"
            "mode: trinary\n"
            "resolution: %.6f\n"
            "origin: [%.6f, %.6f, 0.000000]\n"
            "negate: 0\n"
            "occupied_thresh: 0.65\n"
            "free_thresh: 0.196\n",
            g->resolution_m, g->origin_x_m, g->origin_y_m);
    return close_checked(f, path, why);
}

void hl_mapgrid_free(hl_mapgrid_t *g)
{
    if (!g)
        return;
    free(g->cells);
    g->cells = NULL;
    g->width = g->height = 0;
}
