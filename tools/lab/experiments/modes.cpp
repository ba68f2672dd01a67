// modes.cpp - the parameters of the "paper" and "improved" modes.
#include "experiment.hpp"

namespace hlexp {

Mode paper_mode()
{
    Mode m;
    m.name = "paper";
    hl_loc_params_default(&m.loc);
    m.loc.cell_mm = 47;             // the coarser raster of Table 1
    m.loc.blur_sigma_mm = 50;       // the paper gives no sigma; about one coarse cell
    m.loc.normal_gate = hl_bam_from_deg(30.0);
    m.loc.theta_step = hl_bam_from_deg(1.1);
    m.loc.theta_half_steps = 8;
    m.loc.max_cells = 1u << 22;     // global (x, y, theta) searches over the whole lab
    m.loc.group_mm = 0;             // every pair votes alone
    m.interpolate = false;
    m.prior_sigma_mm = 0;
    hl_slam_params_default(&m.slam);
    m.slam.loc = m.loc;
    m.slam.guarded = false;         // every localization extends the map
    m.slam.use_prior = false;
    m.slam.interpolate = false;
    m.slam.window_mm = 0;           // global search over the map
    m.slam.echo_bearings = false;   // readings on their beam axes
    m.slam.refine = false;          // the best cell is the answer
    return m;
}

Mode improved_mode()
{
    Mode m;
    m.name = "improved";
    hl_loc_params_default(&m.loc);
    m.loc.max_cells = 1u << 22;
    m.interpolate = true;
    m.prior_sigma_mm = 150;
    hl_slam_params_default(&m.slam);    // guarded, +-1 m window, prior, interpolation
    m.slam.loc = m.loc;
    return m;
}

hl_scan_t as_localized(const Mode &m, const hl_scan_t &scan)
{
    hl_scan_t echoed, fitted;
    return *hl_slam_prepare(&m.slam, &scan, &echoed, &fitted);
}

}  // namespace hlexp
