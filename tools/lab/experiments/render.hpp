// render.hpp - pictures for the experiments: maps of tangent vectors, vote surfaces,
// scans and paths, drawn with cairo into PNG files in the style of the paper's figures
// (Fig. 3 the known map, Fig. 4 the votes, Fig. 5 a localization, Fig. 7 online mapping).
//
// World coordinates are millimetres with y up (the map frame); pictures flip y. Nothing
// here throws: every entry point reports failure as false plus a one-line message.
#ifndef HOUGHLOC_TOOLS_EXPERIMENTS_RENDER_HPP
#define HOUGHLOC_TOOLS_EXPERIMENTS_RENDER_HPP

#include <string>
#include <vector>

#include "houghloc-internal/localize.h"
#include "houghloc-internal/map.h"
#include "houghloc/scan.h"

namespace hlfig {

struct Style {
    int width_px = 900;         // picture width (each tile's width in a sheet), >= 2 margins + 64
    int margin_px = 30;         // white border around the drawing, 0..width_px/4
    bool grid_tiles = true;     // the lab's 609.6 mm (two-foot) floor tiles in light grey
    double tick_mm = 120;       // length of a short map vector (Fig. 5 / Fig. 7 style)
    double robot_radius_mm = 150;  // robot circle (drawn at least 4 px)
};

struct Segment {
    double x1, y1, x2, y2;      // mm
};

// What one picture shows; every member is optional.
struct Frame {
    // Map vectors: a dot at the surface point and a short tick along the normal,
    // or, with map_full_length, a thin line back to the sensor position (Fig. 3).
    std::vector<hl_vector_t> map;
    bool map_full_length = false;
    // Small circles with a heading tick; labels (if any) beside them, same order.
    std::vector<hl_pose_t> robot_positions;
    std::vector<std::string> position_labels;
    // Blurred vote surface as grey levels under everything (darker = more votes, Fig. 4).
    // vote_slice -1 shows the maximum over the heading slices. The surface is only read
    // while rendering.
    const hl_loc_surface_t *votes = nullptr;
    int vote_slice = -1;
    // The "star" of test vectors: light grey lines from scan_pose to each valid reading.
    const hl_scan_t *scan = nullptr;
    hl_pose_t scan_pose{};
    // Polylines: truth black, estimate blue, odometry red dashed.
    std::vector<hl_pose_t> path_truth, path_estimate, path_odometry;
    std::vector<Segment> world;  // faint outline of the world
    std::string title;           // top line
    std::string legend;          // bottom line
};

// Where a picture puts the world: a point (x, y) in mm lands at pixel (px(x), py(y)).
// Rows from the top: title band (top_px, 0 without a title), margin, the view
// (view height * scale), margin, a bottom band with the legend and the scale bar.
struct Layout {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the view in mm, after widening
    double scale = 1;                         // pixels per mm
    int width_px = 0, height_px = 0;
    int top_px = 0, margin_px = 0;
    double px(double x_mm) const { return margin_px + (x_mm - x0) * scale; }
    double py(double y_mm) const { return top_px + margin_px + (y1 - y_mm) * scale; }
};

// The layout render_png would use. False (and err) on a bad style or view.
bool layout_for(const Frame &f, const Style &st, const double *view_mm, Layout *out,
                std::string *err);

// Renders one frame to a PNG file. The view is view_mm (x0, y0, x1, y1 in mm) if given,
// else view_box({f}); the picture is st.width_px wide and as tall as the view's aspect
// needs (a view taller than 4:1 is widened), plus bands for the title and legend.
bool render_png(const Frame &f, const std::string &path, std::string *err,
                const Style &st = {}, const double *view_mm = nullptr);

// Renders every frame with one common view (view_mm, or view_box(frames)) so the tiles
// compare directly, and tiles them row by row, `columns` per row, into one PNG. Each
// tile is st.width_px wide; rows take the height of their tallest tile.
bool render_sheet(const std::vector<Frame> &frames, int columns, const std::string &path,
                  std::string *err, const Style &st = {}, const double *view_mm = nullptr);

// The bounding box (x0, y0, x1, y1 in mm) of everything the frames draw: map vectors
// (and their sensor positions when drawn full length), robots, vote rasters, scan star
// ends, paths and world segments. An empty set gives a 1 m box around the origin; a box
// narrower than 1 m on a side is widened to 1 m about its centre.
void view_box(const std::vector<Frame> &frames, double view_mm[4]);

}  // namespace hlfig
#endif
