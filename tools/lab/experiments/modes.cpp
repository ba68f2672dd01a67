// modes.cpp - the parameters of the "paper" and "improved" modes: the core's presets.
#include "experiment.hpp"

#include <cstdio>
#include <cstdlib>

namespace hlexp {

namespace {

// Sets @p key of @p m's parameters; the table's own values, which cannot fail.
void set(Mode *m, const char *key, const char *value)
{
    if (hl_params_set(&m->params, key, value) != HL_OK) {
        std::fprintf(stderr, "hl-experiments: %s\n", hl_params_error(&m->params));
        std::abort();
    }
}

Mode with(const char *name, const char *profile)
{
    Mode m;
    m.name = name;
    hl_params_default(&m.params);
    set(&m, "slam.profile", profile);
    // The experiments measure the tracker alone: no LOST state, whose global searches
    // would answer in the tracker's place (the paper's profile has none either).
    set(&m, "slam.lost_after", "0");
    set(&m, "slam.search_every", "0");
    // Global (x, y, theta) searches over the whole lab: Table 1's, and the paper's tour.
    set(&m, "localize.max_cells", "4194304");
    return m;
}

}  // namespace

void derive(Mode *m)
{
    m->slam = *hl_params_slam(&m->params);
    m->loc = m->slam.loc;
    m->interpolate = m->slam.interpolate;
}

Mode paper_mode()
{
    Mode m = with("paper", "paper");
    m.prior_sigma_mm = 0;
    derive(&m);
    return m;
}

Mode improved_mode()
{
    Mode m = with("improved", "sonar-stops");   // guarded, +-1 m window, prior, interpolation
    m.prior_sigma_mm = 150;
    derive(&m);
    return m;
}

hl_scan_t as_localized(const Mode &m, const hl_scan_t &scan)
{
    hl_scan_t echoed, fitted;
    return *hl_slam_prepare(&m.slam, &scan, &echoed, &fitted);
}

}  // namespace hlexp
