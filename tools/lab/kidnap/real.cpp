// real.cpp - the kidnap experiment on a real building's log: leave one stretch out
// (kidnap.hpp). The paper's Table 1 left one position out of the known map; a robot
// driving through a building passes each place over several scans, so here every scan
// within the exclusion radius of the test scan's true position is left out of its map.
#include <memory>
#include <vector>

#include "experiment.hpp"
#include "stats.hpp"
#include "kidnap.hpp"

namespace hlkid {

namespace {

bool prepares(const hl_slam_params_t &p)
{
    return p.echo_bearings || p.fit_normals;
}

}  // namespace

TruthMapper::TruthMapper(const hl_slam_params_t &p, const hlexp::Soundings &log)
    : p_(p), log_(log), map_(nullptr)
{
    // Every scan as the slam puts it into its map: at its echo bearings and with its
    // surface normals when the parameters estimate them (the experiments' helper; the
    // slam's own is private).
    hlexp::Mode mode{};
    mode.slam = p;
    placed_.resize(prepares(p) ? log.size() : 0);
    for (size_t i = 0; i < placed_.size(); i++)
        placed_[i] = hlexp::as_localized(mode, log[i]->msg.scan);
    // The map as hl_slam_create makes it: capacity, culling seed, density bound, cull.
    hl_map_params_t mp;
    hl_slam_map_params(&p, &mp);
    map_ = hl_map_create_with(&mp);
    ok_ = map_ != nullptr;
    if (ok_)
        fresh_ = hl_map_rng(map_);
}

TruthMapper::~TruthMapper()
{
    hl_map_destroy(map_);
}

bool TruthMapper::make(const std::vector<hl_pose_t> &centres, double exclude_mm,
                       std::string *err)
{
    if (!ok_) {
        *err = "cannot create the map (out of memory?)";
        return false;
    }
    // Each map starts empty with a new map's generator, so it does not depend on the
    // maps before it.
    hl_map_restore(map_, nullptr, 0, 0, fresh_);
    for (size_t i = 0; i < log_.size(); i++) {
        const hl_scan_t &scan = prepares(p_) ? placed_[i] : log_[i]->msg.scan;
        bool far = true;
        for (const hl_pose_t &c : centres)
            far = far && hlexp::distance_mm(log_[i]->truth, c) > exclude_mm;
        if (far && hl_map_add_scan(map_, &scan, log_[i]->truth, nullptr) != HL_OK) {
            *err = "scan " + std::to_string(log_[i]->msg.seq) + ": cannot map it";
            return false;
        }
    }
    return true;
}

// The test scan @p t and the scans after it in the log, each the first at least kApartMm
// from the one before, @p count in all (fewer at the log's end).
static Group group_from(const hlexp::Soundings &log, size_t t, int count)
{
    Group g{ log[t].get() };
    for (size_t i = t + 1; i < log.size() && static_cast<int>(g.size()) < count; i++)
        if (hlexp::distance_mm(log[i]->truth, g.back()->truth) >= kApartMm)
            g.push_back(log[i].get());
    return g;
}

bool run_real(const hl_slam_params_t &p, const hlexp::Soundings &log, int trials,
              double exclude_mm, Scorer *scorer, std::string *err)
{
    const size_t n = log.size();
    if (trials < 1 || static_cast<size_t>(trials) > n) {
        *err = "wants " + std::to_string(trials) + " test scans of a log of " +
               std::to_string(n);
        return false;
    }
    TruthMapper mapper(p, log);
    std::unique_ptr<hl_slam_t, SlamDeleter> slam(hl_slam_create_with(&p));
    if (!slam) {
        *err = "cannot create the slam (out of memory?)";
        return false;
    }
    uint64_t most_cells = 0;
    double most_w = 0, most_h = 0;
    for (int k = 0; k < trials; k++) {
        // The middle scan of the k-th of `trials` equal stretches of the log.
        size_t t = (2 * static_cast<size_t>(k) + 1) * n / (2 * static_cast<size_t>(trials));
        Group group = group_from(log, t, p.reloc.scans);
        std::vector<hl_pose_t> places;
        for (const hlexp::Sounding *g : group)
            places.push_back(g->truth);
        if (!mapper.make(places, exclude_mm, err))
            return false;
        const hl_map_t *map = mapper.map();
        uint32_t count = hl_map_count(map);
        double w, h;
        uint64_t cells = coarse_cells_needed(p.reloc, hl_map_vectors(map), count, &w, &h);
        if (cells > most_cells) {
            most_cells = cells;
            most_w = w;
            most_h = h;
        }
        if (!restore_map(slam.get(), hl_map_vectors(map), count, err) ||
            !scorer->run(slam.get(), group, err))
            return false;
        scorer->progress(trials, 10);
    }
    std::fprintf(stderr,
                 "kidnap: %s: largest map: %.1f x %.1f m, %llu coarse cells "
                 "(reloc.coarse_max_cells %u)\n",
                 scorer->name().c_str(), most_w, most_h,
                 static_cast<unsigned long long>(most_cells), p.reloc.coarse_max_cells);
    return true;
}

}  // namespace hlkid
