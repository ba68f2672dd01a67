// figures.cpp - see figures.hpp.
#include "figures.hpp"

#include <sys/stat.h>

#include <cmath>
#include <cstdio>

namespace hlexp {

namespace {

const size_t FRAME_EVERY = 4;   // stops between film frames

void save(const hlfig::Frame &f, const std::string &path, const double *view = nullptr)
{
    std::string err;
    if (!hlfig::render_png(f, path, &err, hlfig::Style{}, view))
        progress("figures: %s", err.c_str());
    else
        progress("figures: wrote %s", path.c_str());
}

}  // namespace

void save_map_figure(const Context &ctx, const std::string &name,
                     const std::vector<hl_vector_t> &map, const std::vector<hl_pose_t> &where,
                     const std::string &title)
{
    hlfig::Frame f;
    f.map = map;
    f.map_full_length = true;
    f.robot_positions = where;
    f.title = title;
    save(f, ctx.out_dir + "/" + name);
}

void save_localization_figures(const Context &ctx, hl_localizer_t *loc,
                               const std::vector<hl_vector_t> &map, const Sounding &test,
                               hl_pose_t found)
{
    hl_loc_surface_t surface;
    hl_loc_get_surface(loc, &surface);
    hlfig::Frame votes;
    votes.votes = &surface;
    votes.title = "Vote surface (blurred), sounding " + std::to_string(test.msg.seq);
    save(votes, ctx.out_dir + "/fig4_votes.png");

    hlfig::Frame overlay;
    overlay.votes = &surface;
    overlay.map = map;
    overlay.scan = &test.msg.scan;
    overlay.scan_pose = found;
    overlay.robot_positions = { found };
    overlay.title = "Localization of sounding " + std::to_string(test.msg.seq) + ": error " +
                    std::to_string(static_cast<int>(std::hypot(found.x_mm - test.truth.x_mm,
                                                               found.y_mm - test.truth.y_mm))) +
                    " mm";
    save(overlay, ctx.out_dir + "/fig5_localization.png");
}

Film::Film(const Context &ctx, const std::string &name, bool enabled)
    : dir_(ctx.out_dir + "/" + name), name_(name), enabled_(enabled)
{
    if (enabled_)
        mkdir(dir_.c_str(), 0777);
}

void Film::before_step(const hl_map_t *map)
{
    if (!enabled_)
        return;
    const hl_vector_t *v = hl_map_vectors(map);
    map_before_.assign(v, v + hl_map_count(map));
}

void Film::after_step(size_t step, size_t steps, const hl_scan_t &scan, hl_pose_t pose,
                      const std::vector<hl_pose_t> &truth, const std::vector<hl_pose_t> &est,
                      const std::vector<hl_pose_t> &odo, uint32_t map_size)
{
    if (!enabled_ || (step % FRAME_EVERY != 0 && step + 1 != steps))
        return;
    scans_.push_back(scan);
    hlfig::Frame f;
    f.map = map_before_;
    f.scan = &scans_.back();
    f.scan_pose = pose;
    f.path_truth = truth;
    f.path_estimate = est;
    f.path_odometry = odo;
    f.title = "Online map-making, stop " + std::to_string(step + 1) + " of " +
              std::to_string(steps);
    f.legend = "map " + std::to_string(map_size) +
               " vectors; black: truth, blue: estimate, red: odometry";
    frames_.push_back(f);
}

void Film::finish()
{
    if (!enabled_ || frames_.empty())
        return;
    double view[4];
    hlfig::view_box(frames_, view);
    for (size_t i = 0; i < frames_.size(); i++) {
        char file[64];
        std::snprintf(file, sizeof file, "/frame_%03zu.png", i);
        std::string err;
        if (!hlfig::render_png(frames_[i], dir_ + file, &err, hlfig::Style{}, view))
            progress("figures: %s", err.c_str());
    }
    progress("figures: wrote %zu frames to %s/", frames_.size(), dir_.c_str());
    // six snapshots spread over the run, like the paper's Fig. 7
    std::vector<hlfig::Frame> pick;
    for (size_t k = 0; k < 6; k++)
        pick.push_back(frames_[k * (frames_.size() - 1) / 5]);
    std::string err;
    hlfig::Style small;
    small.width_px = 600;
    if (!hlfig::render_sheet(pick, 3, dir_ + ".png", &err, small, view))
        progress("figures: %s", err.c_str());
    else
        progress("figures: wrote %s.png", dir_.c_str());
}

}  // namespace hlexp
