// render_geom.hpp - what render.cpp (drawing) and render_geom.cpp (the view and its
// layout) share: the constants, points and boxes, where a reading or a vector ends.
#ifndef HLFIG_RENDER_GEOM_HPP
#define HLFIG_RENDER_GEOM_HPP

#include <algorithm>
#include <cmath>
#include <string>

#include "render.hpp"

namespace hlfig {
namespace geom {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTileMm = 609.6;        // two-foot floor tiles of the paper's lab
inline constexpr double kMinSideMm = 1000;      // smallest view side: keeps the scale finite
inline constexpr double kRobotPadMm = 150;      // view_box room around a robot position
inline constexpr double kMaxAspect = 4;         // taller views are widened to this
inline constexpr int kTitleBandPx = 26;
inline constexpr int kBottomBandPx = 24;        // legend and scale bar
inline constexpr int kMaxSurfacePx = 32767;     // cairo's image size limit
inline constexpr int kMaxGridLines = 400;       // beyond this the grid is noise: skip it

void set_err(std::string *err, const std::string &msg);

struct Box {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty = true;
    void add(double x, double y)
    {
        if (!std::isfinite(x) || !std::isfinite(y))
            return;
        if (empty) {
            x0 = x1 = x;
            y0 = y1 = y;
            empty = false;
            return;
        }
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
    }
};

struct Pt {
    double x, y;
};

/** Direction of a binary angle as a unit vector. */
Pt unit(hl_bam_t a);
/** End point of one reading of a scan taken at pose: the sensed surface point. */
Pt reading_end(hl_pose_t pose, const hl_reading_t &r);
Pt tick_end(const hl_vector_t &v, double tick_mm);
Pt sensor_of(const hl_vector_t &v);
uint32_t scan_count(const hl_scan_t &s);
/** A surface is drawable if its raster has cells; anything else is "no votes". */
bool has_votes(const hl_loc_surface_t *s);
/** The layout of frame @p f in the view @p view (x0, y0, x1, y1, mm) with style @p st. */
bool layout_from_view(const Frame &f, const Style &st, const double view[4], Layout *out,
                      std::string *err);

}  // namespace geom
}  // namespace hlfig
#endif
