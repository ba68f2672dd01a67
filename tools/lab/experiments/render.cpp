// render.cpp - cairo drawing of frames (see render.hpp).
//
// Drawing order, bottom to top: vote raster, floor tiles, world outline, test star, map
// vectors, paths, robots, then the text bands. The raster is opaque, so everything else
// must come after it; the map goes over the star because in the paper's Fig. 5 and
// Fig. 7 the short dark map vectors read on top of the long grey test vectors.
#include "render.hpp"
#include "render_cairo.hpp"
#include "render_geom.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>

#include <cairo.h>

#include "houghloc/fixed.h"

namespace hlfig {
namespace {

using namespace geom;



// ---- drawing ---------------------------------------------------------------------

void dot(cairo_t *cr, double x, double y, double r)
{
    cairo_new_sub_path(cr);
    cairo_arc(cr, x, y, r, 0, 2 * kPi);
}

// The value shown for cell (ix, iy): one slice, or the maximum over slices.
uint32_t vote_at(const hl_loc_surface_t &s, int slice, int32_t ix, int32_t iy)
{
    size_t plane = static_cast<size_t>(s.nx) * static_cast<size_t>(s.ny);
    size_t at = static_cast<size_t>(iy) * static_cast<size_t>(s.nx) + static_cast<size_t>(ix);
    if (slice >= 0)
        return s.cells[static_cast<size_t>(slice) * plane + at];
    uint32_t m = 0;
    for (int32_t it = 0; it < s.nt; it++)
        m = std::max(m, s.cells[static_cast<size_t>(it) * plane + at]);
    return m;
}

// The vote surface as an image, one pixel per cell, rows top down (y flipped).
// Grey = 1 - sqrt(v / max): the square root lifts weak votes into view, as the paper's
// Fig. 4 shows scattered faint votes next to the dark peak.
Surface vote_image(const hl_loc_surface_t &s, int slice)
{
    Surface img(cairo_image_surface_create(CAIRO_FORMAT_RGB24, s.nx, s.ny));
    if (cairo_surface_status(img.get()) != CAIRO_STATUS_SUCCESS)
        return nullptr;
    std::vector<uint32_t> v(static_cast<size_t>(s.nx) * static_cast<size_t>(s.ny));
    uint32_t vmax = 0;
    for (int32_t iy = 0; iy < s.ny; iy++)
        for (int32_t ix = 0; ix < s.nx; ix++) {
            uint32_t x = vote_at(s, slice, ix, iy);
            v[static_cast<size_t>(iy) * static_cast<size_t>(s.nx) + static_cast<size_t>(ix)] = x;
            vmax = std::max(vmax, x);
        }
    cairo_surface_flush(img.get());
    unsigned char *data = cairo_image_surface_get_data(img.get());
    int stride = cairo_image_surface_get_stride(img.get());
    for (int32_t iy = 0; iy < s.ny; iy++) {
        auto *row = reinterpret_cast<uint32_t *>(data + static_cast<size_t>(s.ny - 1 - iy) * stride);
        for (int32_t ix = 0; ix < s.nx; ix++) {
            uint32_t x = v[static_cast<size_t>(iy) * static_cast<size_t>(s.nx) + static_cast<size_t>(ix)];
            // An all-zero surface stays white rather than dividing by zero.
            double t = vmax ? std::sqrt(static_cast<double>(x) / vmax) : 0.0;
            auto g = static_cast<uint32_t>(std::lround(255.0 * (1.0 - t)));
            row[ix] = (g << 16) | (g << 8) | g;
        }
    }
    cairo_surface_mark_dirty(img.get());
    return img;
}

bool draw_votes(cairo_t *cr, const Layout &L, const hl_loc_surface_t &s, int slice,
                std::string *err)
{
    if (slice < -1 || slice >= s.nt) {
        set_err(err, "vote_slice " + std::to_string(slice) + " out of range -1.." +
                         std::to_string(s.nt - 1));
        return false;
    }
    if (s.nx > kMaxSurfacePx || s.ny > kMaxSurfacePx) {
        set_err(err, "vote surface too large to draw: " + std::to_string(s.nx) + " x " +
                         std::to_string(s.ny) + " cells");
        return false;
    }
    Surface img = vote_image(s, slice);
    if (!img) {
        set_err(err, "out of memory for the vote image");
        return false;
    }
    double cell_px = s.cell_mm * L.scale;
    cairo_save(cr);
    cairo_translate(cr, L.px(s.x0_mm), L.py(s.y0_mm + static_cast<double>(s.ny) * s.cell_mm));
    cairo_scale(cr, cell_px, cell_px);
    cairo_set_source_surface(cr, img.get(), 0, 0);
    cairo_pattern_t *pat = cairo_get_source(cr);
    cairo_pattern_set_extend(pat, CAIRO_EXTEND_PAD);
    // Big cells stay crisp squares; small ones are averaged rather than aliased.
    cairo_pattern_set_filter(pat, cell_px >= 3 ? CAIRO_FILTER_NEAREST : CAIRO_FILTER_GOOD);
    cairo_rectangle(cr, 0, 0, s.nx, s.ny);
    cairo_fill(cr);
    cairo_restore(cr);
    return true;
}

void draw_grid(cairo_t *cr, const Layout &L)
{
    long i0 = static_cast<long>(std::ceil(L.x0 / kTileMm));
    long i1 = static_cast<long>(std::floor(L.x1 / kTileMm));
    long j0 = static_cast<long>(std::ceil(L.y0 / kTileMm));
    long j1 = static_cast<long>(std::floor(L.y1 / kTileMm));
    if ((i1 - i0) + (j1 - j0) > kMaxGridLines)
        return;
    cairo_save(cr);
    grey(cr, 0.86);
    cairo_set_line_width(cr, 0.6);
    for (long i = i0; i <= i1; i++) {
        cairo_move_to(cr, L.px(i * kTileMm), L.py(L.y0));
        cairo_line_to(cr, L.px(i * kTileMm), L.py(L.y1));
    }
    for (long j = j0; j <= j1; j++) {
        cairo_move_to(cr, L.px(L.x0), L.py(j * kTileMm));
        cairo_line_to(cr, L.px(L.x1), L.py(j * kTileMm));
    }
    cairo_stroke(cr);
    cairo_restore(cr);
}

void draw_world(cairo_t *cr, const Layout &L, const std::vector<Segment> &world)
{
    cairo_save(cr);
    cairo_set_source_rgb(cr, 0.62, 0.66, 0.78);
    cairo_set_line_width(cr, 1.0);
    for (const Segment &s : world) {
        if (!std::isfinite(s.x1) || !std::isfinite(s.y1) || !std::isfinite(s.x2) ||
            !std::isfinite(s.y2))
            continue;
        cairo_move_to(cr, L.px(s.x1), L.py(s.y1));
        cairo_line_to(cr, L.px(s.x2), L.py(s.y2));
    }
    cairo_stroke(cr);
    cairo_restore(cr);
}

void draw_star(cairo_t *cr, const Layout &L, const hl_scan_t &scan, hl_pose_t pose)
{
    cairo_save(cr);
    grey(cr, 0.70);
    cairo_set_line_width(cr, 1.0);
    double ox = L.px(pose.x_mm), oy = L.py(pose.y_mm);
    for (uint32_t i = 0; i < scan_count(scan); i++) {
        const hl_reading_t &r = scan.readings[i];
        if (!r.valid)
            continue;
        Pt e = reading_end(pose, r);
        cairo_move_to(cr, ox, oy);
        cairo_line_to(cr, L.px(e.x), L.py(e.y));
    }
    cairo_stroke(cr);
    cairo_restore(cr);
}

// Fig. 3: each vector a thin line back to where the robot stood when it was sensed.
// Translucent, so where many soundings overlap the picture darkens like the paper's.
void draw_map_full(cairo_t *cr, const Layout &L, const std::vector<hl_vector_t> &map)
{
    cairo_save(cr);
    grey(cr, 0.15, 0.35);
    cairo_set_line_width(cr, 0.6);
    for (const hl_vector_t &v : map) {
        Pt o = sensor_of(v);
        cairo_move_to(cr, L.px(v.x_mm), L.py(v.y_mm));
        cairo_line_to(cr, L.px(o.x), L.py(o.y));
        cairo_stroke(cr);  // one at a time: a single path would not accumulate alpha
    }
    grey(cr, 0.0);
    for (const hl_vector_t &v : map)
        dot(cr, L.px(v.x_mm), L.py(v.y_mm), 1.0);
    cairo_fill(cr);
    cairo_restore(cr);
}

// Fig. 5 / Fig. 7: a dot on the surface and a short tick along the normal.
void draw_map_short(cairo_t *cr, const Layout &L, const std::vector<hl_vector_t> &map,
                    double tick_mm)
{
    cairo_save(cr);
    grey(cr, 0.1);
    cairo_set_line_width(cr, 1.0);
    for (const hl_vector_t &v : map) {
        Pt e = tick_end(v, tick_mm);
        cairo_move_to(cr, L.px(v.x_mm), L.py(v.y_mm));
        cairo_line_to(cr, L.px(e.x), L.py(e.y));
    }
    cairo_stroke(cr);
    for (const hl_vector_t &v : map)
        dot(cr, L.px(v.x_mm), L.py(v.y_mm), 1.4);
    cairo_fill(cr);
    cairo_restore(cr);
}

struct PathStyle {
    double r, g, b;
    double width_px;
    bool dashed;
};

void draw_path(cairo_t *cr, const Layout &L, const std::vector<hl_pose_t> &path,
               const PathStyle &ps)
{
    if (path.empty())
        return;
    cairo_save(cr);
    cairo_set_source_rgb(cr, ps.r, ps.g, ps.b);
    cairo_set_line_width(cr, ps.width_px);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    if (ps.dashed) {
        const double dash[] = {6.0, 4.0};
        cairo_set_dash(cr, dash, 2, 0);
    }
    cairo_move_to(cr, L.px(path[0].x_mm), L.py(path[0].y_mm));
    for (size_t i = 1; i < path.size(); i++)
        cairo_line_to(cr, L.px(path[i].x_mm), L.py(path[i].y_mm));
    cairo_stroke(cr);
    // Dots mark the stops, so a one-pose path still shows and the steps can be counted.
    for (const hl_pose_t &p : path)
        dot(cr, L.px(p.x_mm), L.py(p.y_mm), 0.5 * ps.width_px + 1.0);
    cairo_fill(cr);
    cairo_restore(cr);
}

void draw_robots(cairo_t *cr, const Layout &L, const Frame &f, const Style &st)
{
    double rad = std::max(4.0, st.robot_radius_mm * L.scale);
    cairo_save(cr);
    cairo_set_line_width(cr, 1.3);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 10);
    for (size_t i = 0; i < f.robot_positions.size(); i++) {
        const hl_pose_t &p = f.robot_positions[i];
        double x = L.px(p.x_mm), y = L.py(p.y_mm);
        Pt u = unit(p.theta);
        // Outline only: a filled disc would hide the vote peak under the robot.
        dot(cr, x, y, rad);
        cairo_set_source_rgb(cr, 0.55, 0.0, 0.55);
        cairo_stroke(cr);
        cairo_move_to(cr, x, y);
        cairo_line_to(cr, x + 1.6 * rad * u.x, y - 1.6 * rad * u.y);  // pixel y is down
        cairo_stroke(cr);
        if (i < f.position_labels.size() && !f.position_labels[i].empty()) {
            cairo_move_to(cr, x + rad + 2, y - rad);
            cairo_show_text(cr, f.position_labels[i].c_str());
        }
    }
    cairo_restore(cr);
}

// A bar of a round length near 1 m, right-aligned in the bottom band.
void draw_scale_bar(cairo_t *cr, const Layout &L)
{
    double len_mm = 1000;
    // Keep the bar legible: 1 m unless that is tiny or wider than a third of the picture.
    while (len_mm * L.scale < 20 && len_mm < 1e7)
        len_mm *= 10;
    while (len_mm * L.scale > L.width_px / 3.0 && len_mm > 1)
        len_mm /= 10;
    double len = len_mm * L.scale;
    double x1 = L.width_px - std::max(L.margin_px, 8);
    double x0 = x1 - len;
    double y = L.height_px - 6.0;
    cairo_save(cr);
    grey(cr, 0.0);
    cairo_set_line_width(cr, 2.0);
    cairo_move_to(cr, x0, y - 4);
    cairo_line_to(cr, x0, y);
    cairo_line_to(cr, x1, y);
    cairo_line_to(cr, x1, y - 4);
    cairo_stroke(cr);
    char label[32];
    if (len_mm >= 1000)
        std::snprintf(label, sizeof label, "%g m", len_mm / 1000);
    else
        std::snprintf(label, sizeof label, "%g mm", len_mm);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 11);
    cairo_text_extents_t te;
    cairo_text_extents(cr, label, &te);
    cairo_move_to(cr, x0 - te.x_advance - 6, y);
    cairo_show_text(cr, label);
    cairo_restore(cr);
}

void draw_text_bands(cairo_t *cr, const Layout &L, const Frame &f)
{
    cairo_save(cr);
    grey(cr, 0.0);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    if (!f.title.empty()) {
        cairo_set_font_size(cr, 15);
        cairo_move_to(cr, std::max(L.margin_px, 8), 19);
        cairo_show_text(cr, f.title.c_str());
    }
    if (!f.legend.empty()) {
        cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                               CAIRO_FONT_WEIGHT_NORMAL);
        cairo_set_font_size(cr, 12);
        cairo_move_to(cr, std::max(L.margin_px, 8), L.height_px - 7.0);
        cairo_show_text(cr, f.legend.c_str());
    }
    cairo_restore(cr);
    draw_scale_bar(cr, L);
}

}  // namespace

namespace geom {

// Draws one frame into a new image surface; nullptr and err on failure.
Surface render_surface(const Frame &f, const Style &st, const Layout &L, std::string *err)
{
    Surface surf(cairo_image_surface_create(CAIRO_FORMAT_RGB24, L.width_px, L.height_px));
    if (cairo_surface_status(surf.get()) != CAIRO_STATUS_SUCCESS) {
        set_err(err, "cannot create a " + std::to_string(L.width_px) + " x " +
                         std::to_string(L.height_px) + " image");
        return nullptr;
    }
    Context cr(cairo_create(surf.get()));
    cairo_t *c = cr.get();
    grey(c, 1.0);
    cairo_paint(c);

    // Data drawn past a fixed view must not spill into the text bands.
    cairo_save(c);
    cairo_rectangle(c, 0, L.top_px, L.width_px, L.height_px - L.top_px - kBottomBandPx);
    cairo_clip(c);
    if (has_votes(f.votes) && !draw_votes(c, L, *f.votes, f.vote_slice, err))
        return nullptr;
    if (st.grid_tiles)
        draw_grid(c, L);
    draw_world(c, L, f.world);
    if (f.scan)
        draw_star(c, L, *f.scan, f.scan_pose);
    if (f.map_full_length)
        draw_map_full(c, L, f.map);
    else
        draw_map_short(c, L, f.map, st.tick_mm);
    // Truth is wider and under the estimate, so a good estimate shows as a blue line
    // with a black edge instead of hiding the truth.
    draw_path(c, L, f.path_odometry, {0.85, 0.10, 0.10, 1.5, true});
    draw_path(c, L, f.path_truth, {0.0, 0.0, 0.0, 3.0, false});
    draw_path(c, L, f.path_estimate, {0.10, 0.30, 0.95, 1.3, false});
    draw_robots(c, L, f, st);
    cairo_restore(c);

    draw_text_bands(c, L, f);
    cairo_status_t cs = cairo_status(c);
    if (cs != CAIRO_STATUS_SUCCESS) {
        set_err(err, std::string("drawing failed: ") + cairo_status_to_string(cs));
        return nullptr;
    }
    cr.reset();
    cairo_surface_flush(surf.get());
    return surf;
}

}  // namespace geom
}  // namespace hlfig
