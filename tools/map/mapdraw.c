/*
 * mapdraw.c - the PNG picture of a map (mapdraw.h).
 */
#include "mapdraw.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>

#define MARGIN_PX 40.0
#define LEGEND_PX 24.0          /* one legend line */
#define STROKE_HALF_MM 60.0     /* half a vector's stroke along the surface */
#define TICK_MM 100.0           /* a normal's tick */

/* The world-to-picture mapping: px = x0 + (x - xmin) s, py = y0 + (ymax - y) s. */
typedef struct view {
    double xmin, ymax, s;       /* mm, mm, px per mm */
    double x0, y0;              /* px */
    int width, height;
} view_t;

static double px(const view_t *w, double x_mm)
{
    return w->x0 + (x_mm - w->xmin) * w->s;
}

static double py(const view_t *w, double y_mm)
{
    return w->y0 + (w->ymax - y_mm) * w->s;
}

static void grow(double b[4], double x, double y)
{
    b[0] = x < b[0] ? x : b[0];
    b[1] = y < b[1] ? y : b[1];
    b[2] = x > b[2] ? x : b[2];
    b[3] = y > b[3] ? y : b[3];
}

static view_t make_view(const hl_vector_t *v, size_t n, const hl_mapdraw_path_t *paths,
                        size_t npaths, int size_px, size_t legend_lines)
{
    double b[4] = { INFINITY, INFINITY, -INFINITY, -INFINITY };
    for (size_t k = 0; k < n; k++)
        grow(b, v[k].x_mm, v[k].y_mm);
    for (size_t p = 0; p < npaths; p++)
        for (size_t k = 0; k < paths[p].n; k++)
            grow(b, paths[p].poses[k].x_mm, paths[p].poses[k].y_mm);
    /* At least 1 m across, so a single point still gets a sensible scale. */
    double span_x = fmax(b[2] - b[0], 1000.0), span_y = fmax(b[3] - b[1], 1000.0);
    view_t w;
    w.s = size_px / fmax(span_x, span_y);
    w.xmin = (b[0] + b[2]) / 2 - span_x / 2;
    w.ymax = (b[1] + b[3]) / 2 + span_y / 2;
    w.x0 = MARGIN_PX;
    w.y0 = MARGIN_PX + LEGEND_PX * (double)legend_lines;
    w.width = (int)ceil(span_x * w.s + 2 * MARGIN_PX);
    w.height = (int)ceil(span_y * w.s + 2 * MARGIN_PX + LEGEND_PX * (double)legend_lines);
    return w;
}

static void draw_grid(cairo_t *cr, const view_t *w)
{
    double xmax = w->xmin + (w->width - 2 * MARGIN_PX) / w->s;
    double ymin = w->ymax - (w->height - w->y0 - MARGIN_PX) / w->s;
    double step = (xmax - w->xmin) > 100000 || (w->ymax - ymin) > 100000 ? 10000 : 1000;
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_set_line_width(cr, 1);
    for (double x = ceil(w->xmin / step) * step; x <= xmax; x += step) {
        cairo_move_to(cr, px(w, x), py(w, w->ymax));
        cairo_line_to(cr, px(w, x), py(w, ymin));
    }
    for (double y = ceil(ymin / step) * step; y <= w->ymax; y += step) {
        cairo_move_to(cr, px(w, w->xmin), py(w, y));
        cairo_line_to(cr, px(w, xmax), py(w, y));
    }
    cairo_stroke(cr);
}

static void draw_vectors(cairo_t *cr, const view_t *w, const hl_vector_t *v, size_t n,
                         bool normals)
{
    double half = fmax(STROKE_HALF_MM * w->s, 1.5);     /* px */
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    if (normals) {
        double tick = fmax(TICK_MM * w->s, 3.0);
        cairo_set_source_rgb(cr, 0.85, 0.35, 0.2);
        cairo_set_line_width(cr, 1);
        for (size_t k = 0; k < n; k++) {
            double a = hl_bam_to_rad(v[k].normal), x = px(w, v[k].x_mm), y = py(w, v[k].y_mm);
            cairo_move_to(cr, x, y);
            cairo_line_to(cr, x + tick * cos(a), y - tick * sin(a));
        }
        cairo_stroke(cr);
    }
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_set_line_width(cr, 1.6);
    for (size_t k = 0; k < n; k++) {
        /* Along the surface: the normal turned a quarter turn. */
        double a = hl_bam_to_rad(v[k].normal), x = px(w, v[k].x_mm), y = py(w, v[k].y_mm);
        double dx = -sin(a) * half, dy = -cos(a) * half;    /* picture y points down */
        cairo_move_to(cr, x - dx, y - dy);
        cairo_line_to(cr, x + dx, y + dy);
    }
    cairo_stroke(cr);
}

static void draw_path(cairo_t *cr, const view_t *w, const hl_mapdraw_path_t *p)
{
    if (p->n == 0)
        return;
    cairo_set_source_rgb(cr, p->rgb[0], p->rgb[1], p->rgb[2]);
    cairo_set_line_width(cr, 1.5);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (size_t k = 0; k < p->n; k++)
        cairo_line_to(cr, px(w, p->poses[k].x_mm), py(w, p->poses[k].y_mm));
    cairo_stroke(cr);
    for (size_t k = 0; k < p->n; k++) {   /* a dot at each pose, a ring at the start */
        cairo_arc(cr, px(w, p->poses[k].x_mm), py(w, p->poses[k].y_mm), k == 0 ? 5 : 1.8, 0,
                  2 * 3.14159265358979323846);
        if (k == 0) {
            cairo_stroke(cr);
        } else {
            cairo_fill(cr);
        }
    }
}

static void draw_legend(cairo_t *cr, const view_t *w, size_t n,
                        const hl_mapdraw_path_t *paths, size_t npaths)
{
    char text[160];
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 14);
    double y = MARGIN_PX * 0.6;
    /* The scale bar: 1 m. */
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 2);
    cairo_move_to(cr, MARGIN_PX, y);
    cairo_line_to(cr, MARGIN_PX + 1000 * w->s, y);
    cairo_stroke(cr);
    snprintf(text, sizeof text, "1 m    %zu vectors", n);
    cairo_move_to(cr, MARGIN_PX + 1000 * w->s + 8, y + 5);
    cairo_show_text(cr, text);
    for (size_t p = 0; p < npaths; p++) {
        y += LEGEND_PX;
        cairo_set_source_rgb(cr, paths[p].rgb[0], paths[p].rgb[1], paths[p].rgb[2]);
        cairo_move_to(cr, MARGIN_PX, y);
        cairo_line_to(cr, MARGIN_PX + 30, y);
        cairo_stroke(cr);
        snprintf(text, sizeof text, "%s (%zu poses)", paths[p].label, paths[p].n);
        cairo_move_to(cr, MARGIN_PX + 38, y + 5);
        cairo_show_text(cr, text);
    }
}

hl_status_t hl_mapdraw_png(const char *path, const hl_vector_t *v, size_t n,
                           const hl_mapdraw_path_t *paths, size_t npaths,
                           const hl_mapdraw_opts_t *opts, char *why)
{
    if (opts->size_px < HL_MAPDRAW_MIN_PX || opts->size_px > HL_MAPDRAW_MAX_PX) {
        snprintf(why, HL_MAPDRAW_WHY_LEN, "picture size %d px out of %d..%d", opts->size_px,
                 HL_MAPDRAW_MIN_PX, HL_MAPDRAW_MAX_PX);
        return HL_ERR_ARG;
    }
    size_t points = n;
    for (size_t p = 0; p < npaths; p++)
        points += paths[p].n;
    if (points == 0) {
        snprintf(why, HL_MAPDRAW_WHY_LEN, "%s: nothing to draw", path);
        return HL_ERR_ARG;
    }
    view_t w = make_view(v, n, paths, npaths, opts->size_px, npaths);
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w.width, w.height);
    cairo_t *cr = cairo_create(sf);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    draw_grid(cr, &w);
    draw_vectors(cr, &w, v, n, opts->normals);
    for (size_t p = 0; p < npaths; p++)
        draw_path(cr, &w, &paths[p]);
    draw_legend(cr, &w, n, paths, npaths);
    cairo_status_t st = cairo_status(cr);
    if (st == CAIRO_STATUS_SUCCESS)
        st = cairo_surface_write_to_png(sf, path);
    cairo_destroy(cr);
    cairo_surface_destroy(sf);
    /* Frees cairo's font caches (no cairo object is alive now), so that a run under
     * LeakSanitizer reports only our own leaks. */
    cairo_debug_reset_static_data();
    if (st != CAIRO_STATUS_SUCCESS) {
        snprintf(why, HL_MAPDRAW_WHY_LEN, "%s: cannot write the picture: %s", path,
                 cairo_status_to_string(st));
        return HL_ERR_OS;
    }
    return HL_OK;
}
