// figures.hpp - the paper's figures for the experiments, drawn with render.hpp:
// Fig. 3 (known map), Figs. 4 and 5 (vote surface, a localization) and Fig. 7 (the
// online sequence, as frames and a contact sheet).
#ifndef HLEXP_FIGURES_HPP
#define HLEXP_FIGURES_HPP

#include <string>
#include <deque>
#include <vector>

#include "experiment.hpp"
#include "houghloc-internal/localize.h"
#include "render.hpp"

namespace hlexp {

void save_map_figure(const Context &ctx, const std::string &name,
                     const std::vector<hl_vector_t> &map, const std::vector<hl_pose_t> &where,
                     const std::string &title);

// Fig. 4 from the localizer's last vote surface; Fig. 5 the same with the map and the
// scan's star of readings drawn from the computed pose.
void save_localization_figures(const Context &ctx, hl_localizer_t *loc,
                               const std::vector<hl_vector_t> &map, const Sounding &test,
                               hl_pose_t found);

// Fig. 7: one frame every few stops into OUT/NAME/, and six of them on one sheet.
class Film {
public:
    Film(const Context &ctx, const std::string &name, bool enabled);
    void before_step(const hl_map_t *map);
    void after_step(size_t step, size_t steps, const hl_scan_t &scan, hl_pose_t pose,
                    const std::vector<hl_pose_t> &truth, const std::vector<hl_pose_t> &est,
                    const std::vector<hl_pose_t> &odo, uint32_t map_size);
    void finish();

private:
    std::string dir_, name_;
    bool enabled_;
    std::vector<hl_vector_t> map_before_;
    std::vector<hlfig::Frame> frames_;      // every frame drawn, for the sheet
    std::deque<hl_scan_t> scans_;           // frames point at these; a deque keeps them put
};

}  // namespace hlexp
#endif
