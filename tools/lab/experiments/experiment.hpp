// experiment.hpp - what the three experiments of the paper share: the two modes, the
// run context, and one result row type per experiment.
#ifndef HLEXP_EXPERIMENT_HPP
#define HLEXP_EXPERIMENT_HPP

#include <string>
#include <vector>

#include "dataset.hpp"
#include "houghloc-internal/params.h"

namespace hlexp {

// "paper": the paper's method and parameters (slam.profile = paper); "improved": ours
// (the defaults). Each field says which experiment it affects.
struct Mode {
    std::string name;
    hl_params_t params;         // the tracker's settings (houghloc/params.h); the fields
                                // below but prior_sigma_mm follow from them (derive)
    hl_loc_params_t loc;        // all experiments (cell_mm is set per Table 1 row)
    bool interpolate;           // sub-cell interpolation of the peak
    double prior_sigma_mm;      // Table 1: 0 = global search with no prior (the paper);
                                // > 0 = a prior estimate, the measured position plus a
                                // seeded Gaussian error of this sigma per axis (what
                                // odometry over a short hop gives), searched in the
                                // slam window with the odometry prior
    hl_slam_params_t slam;      // orientation baseline and combined tour; its
                                // echo_bearings and echo apply to every experiment
};

Mode paper_mode();
Mode improved_mode();
// Sets loc, interpolate and slam from m->params (after a change to them).
void derive(Mode *m);

// The scan as the mode's localizer sees it: at the readings' echo bearings when the mode
// estimates them (houghloc/echo.h), else unchanged.
hl_scan_t as_localized(const Mode &m, const hl_scan_t &scan);

struct Context {
    std::string out_dir;        // results and figures go here
    bool figures = true;
    int reps = 8;               // Table 1: random map subsets per setting
};

struct Table1Row {
    std::string mode;
    bool prior;                 // the improved mode's prior estimate (Mode::prior_sigma_mm)
    int fraction16;             // map fraction, in sixteenths
    int raster_mm;
    int trials, wild;
    double tame_mean_mm, tame_sigma_mm;
};

struct OrientationRow {
    std::string mode;
    int trials;
    double mean_deg, sigma_deg, max_abs_deg;
};

struct CombinedRow {
    std::string mode;           // paper, improved, odometry
    int stops, accepted, rejected;
    int wild_accepted;          // accepted into the map with error > 500 mm
    double rmse_mm, max_mm, final_mm;
};

std::vector<Table1Row> run_table1(const Soundings &lab, const Mode &m, const Context &ctx);
OrientationRow run_orientation(const Soundings &log, const Mode &m, const Context &ctx);
std::vector<CombinedRow> run_combined(const Soundings &tour, const Mode &m, const Context &ctx,
                                      bool with_odometry_row);

// Progress on stderr: one line per step, prefixed with the experiment's name.
void progress(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

}  // namespace hlexp
#endif
