// render_geom.cpp - the view of a figure and its layout on the page (see render.hpp), and
// the geometry render.cpp draws with (render_geom.hpp).
#include "render_geom.hpp"

#include <algorithm>
#include <cmath>

namespace hlfig {
namespace geom {

void set_err(std::string *err, const std::string &msg)
{
    if (err)
        *err = msg;
}

Pt unit(hl_bam_t a)
{
    double r = hl_bam_to_rad(a);
    return {std::cos(r), std::sin(r)};
}

Pt reading_end(hl_pose_t pose, const hl_reading_t &r)
{
    Pt u = unit(static_cast<hl_bam_t>(pose.theta + r.bearing));
    return {pose.x_mm + u.x * r.range_mm, pose.y_mm + u.y * r.range_mm};
}

Pt tick_end(const hl_vector_t &v, double tick_mm)
{
    Pt u = unit(v.normal);
    return {v.x_mm + u.x * tick_mm, v.y_mm + u.y * tick_mm};
}

Pt sensor_of(const hl_vector_t &v)
{
    hl_mm_t x, y;
    hl_vector_origin(&v, &x, &y);
    return {static_cast<double>(x), static_cast<double>(y)};
}

uint32_t scan_count(const hl_scan_t &s)
{
    return std::min<uint32_t>(s.count, HL_SCAN_MAX_READINGS);
}

bool has_votes(const hl_loc_surface_t *s)
{
    return s && s->cells && s->nx > 0 && s->ny > 0 && s->nt > 0 && s->cell_mm > 0;
}

}  // namespace geom

namespace {

using namespace geom;

void add_frame(const Frame &f, Box *b)
{
    for (const hl_vector_t &v : f.map) {
        b->add(v.x_mm, v.y_mm);
        Pt e = f.map_full_length ? sensor_of(v) : tick_end(v, Style{}.tick_mm);
        b->add(e.x, e.y);
    }
    for (const hl_pose_t &p : f.robot_positions) {
        b->add(p.x_mm - kRobotPadMm, p.y_mm - kRobotPadMm);
        b->add(p.x_mm + kRobotPadMm, p.y_mm + kRobotPadMm);
    }
    if (has_votes(f.votes)) {
        const hl_loc_surface_t &s = *f.votes;
        b->add(s.x0_mm, s.y0_mm);
        b->add(s.x0_mm + static_cast<double>(s.nx) * s.cell_mm,
               s.y0_mm + static_cast<double>(s.ny) * s.cell_mm);
    }
    if (f.scan) {
        b->add(f.scan_pose.x_mm, f.scan_pose.y_mm);
        for (uint32_t i = 0; i < scan_count(*f.scan); i++) {
            const hl_reading_t &r = f.scan->readings[i];
            if (r.valid) {
                Pt e = reading_end(f.scan_pose, r);
                b->add(e.x, e.y);
            }
        }
    }
    for (const auto *path : {&f.path_truth, &f.path_estimate, &f.path_odometry})
        for (const hl_pose_t &p : *path)
            b->add(p.x_mm, p.y_mm);
    for (const Segment &s : f.world) {
        b->add(s.x1, s.y1);
        b->add(s.x2, s.y2);
    }
}

// Widens [lo, hi] about its centre to at least `side`.
void widen(double *lo, double *hi, double side)
{
    if (*hi - *lo >= side)
        return;
    double c = 0.5 * (*lo + *hi);
    *lo = c - 0.5 * side;
    *hi = c + 0.5 * side;
}

// The view of a bounding box: a 1 m box at the origin if empty, each side >= 1 m.
void box_to_view(Box b, double view[4])
{
    if (b.empty) {
        b.x0 = b.y0 = -0.5 * kMinSideMm;
        b.x1 = b.y1 = 0.5 * kMinSideMm;
    }
    widen(&b.x0, &b.x1, kMinSideMm);
    widen(&b.y0, &b.y1, kMinSideMm);
    view[0] = b.x0;
    view[1] = b.y0;
    view[2] = b.x1;
    view[3] = b.y1;
}

bool check_style(const Style &st, std::string *err)
{
    if (st.margin_px < 0 || st.margin_px > st.width_px / 4 || st.width_px < 2 * st.margin_px + 64 ||
        st.width_px > kMaxSurfacePx) {
        set_err(err, "bad style: width_px " + std::to_string(st.width_px) + ", margin_px " +
                         std::to_string(st.margin_px));
        return false;
    }
    if (!(st.tick_mm >= 0) || !(st.robot_radius_mm >= 0)) {
        set_err(err, "bad style: tick_mm and robot_radius_mm must be >= 0");
        return false;
    }
    return true;
}

}  // namespace

namespace geom {

bool layout_from_view(const Frame &f, const Style &st, const double view[4], Layout *out,
                      std::string *err)
{
    if (!check_style(st, err))
        return false;
    for (int i = 0; i < 4; i++) {
        if (!std::isfinite(view[i])) {
            set_err(err, "view box is not finite");
            return false;
        }
    }
    if (!(view[2] > view[0] && view[3] > view[1])) {
        set_err(err, "view box is empty: x1 <= x0 or y1 <= y0");
        return false;
    }
    Layout L;
    L.x0 = view[0];
    L.y0 = view[1];
    L.x1 = view[2];
    L.y1 = view[3];
    // A very tall view would make a picture many widths high: widen it instead.
    widen(&L.x0, &L.x1, (L.y1 - L.y0) / kMaxAspect);
    L.margin_px = st.margin_px;
    L.top_px = f.title.empty() ? 0 : kTitleBandPx;
    L.width_px = st.width_px;
    L.scale = (st.width_px - 2.0 * st.margin_px) / (L.x1 - L.x0);
    double h = L.top_px + 2.0 * st.margin_px + (L.y1 - L.y0) * L.scale + kBottomBandPx;
    if (!(h <= kMaxSurfacePx)) {
        set_err(err, "picture too tall: " + std::to_string(std::lround(h)) + " px");
        return false;
    }
    L.height_px = static_cast<int>(std::ceil(h - 1e-6));  // 924.0000001 is 924
    *out = L;
    return true;
}

}  // namespace geom

void view_box(const std::vector<Frame> &frames, double view_mm[4])
{
    Box b;
    for (const Frame &f : frames)
        add_frame(f, &b);
    box_to_view(b, view_mm);
}

bool layout_for(const Frame &f, const Style &st, const double *view_mm, Layout *out,
                std::string *err)
{
    double view[4];
    if (view_mm) {
        std::copy(view_mm, view_mm + 4, view);
    } else {
        Box b;
        add_frame(f, &b);
        box_to_view(b, view);
    }
    return layout_from_view(f, st, view, out, err);
}

// The public entry points only add the no-throw guarantee: std::vector and std::string
// may throw bad_alloc, which becomes an ordinary failure.

}  // namespace hlfig
