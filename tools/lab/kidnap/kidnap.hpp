// kidnap.hpp - the kidnap experiment (make kidnap, tools/lab/kidnap/kidnap.mk): a robot set
// down somewhere in a known map with no idea of its pose, its first scans there (the test
// scan and the next ones, the robot driven at least kApartMm between them: reloc.scans of
// them), and the global search of hl_slam_relocalize_scans. What the two kinds of world
// share: the trials, their scoring, and the row of the table.
#ifndef HLKID_KIDNAP_HPP
#define HLKID_KIDNAP_HPP

#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "dataset.hpp"
#include "inputs.hpp"
#include "houghloc-internal/map.h"
#include "houghloc-internal/slam_search.h"
#include "houghloc-internal/slam_params.h"

namespace hlkid {

// A found answer counts as a success within both (inclusive); farther off it is wrong.
constexpr double kSuccessMm = 500.0;
constexpr double kSuccessDeg = 5.0;
constexpr double kNearMm = 5000.0;
// A trial's scans are taken at least this far apart (the tracker keeps its lost scans
// 0.5 m or 30 degrees apart, slam_lost.c).
constexpr double kApartMm = 500.0;
// The grid of Trial::truth_score around the true pose.
constexpr int kTruthNearMm = 300, kTruthStepMm = 100, kTruthNearDeg = 6, kTruthStepDeg = 3;

// The table's columns, in order (kidnap.tsv's header).
extern const char *const kHeader;

enum class Outcome { Success, Ambiguous, Wrong };

// A trial's scans, the test scan first: what the robot saw at the place and from the
// next places it drove to.
using Group = std::vector<const hlexp::Sounding *>;

struct Trial {
    int32_t seq = 0;            // the test scan's seq in its log
    int scans = 1;              // scans searched together
    hl_pose_t truth{};
    hl_status_t status = HL_OK;
    hl_reloc_result_t result{};
    uint32_t map_vectors = 0;
    uint32_t near_vectors = 0;  // map vectors within kNearMm of the true position: how
                                // much the map knows of the place (for the detail file)
    double ms = 0.0;            // the search calls alone (CLOCK_MONOTONIC)
    uint32_t truth_score = 0;   // hl_slam_judge's best within kTruthNearMm, kTruthNearDeg
                                // of the truth: what the map lets the search find there
    uint32_t truth_scans_score = 0; // ... summed over the trial's scans, each near its own
                                    // truth (compares with result.score)
    uint32_t answer_climbed = 0;    // ... and near the answer (both climbed alike), so
                                    // that the two compare as places, not as poses
    double error_mm = 0.0, error_deg = 0.0;     // of result.pose, when it has one
    Outcome outcome = Outcome::Ambiguous;
    int map = 1;                // which of the row's maps (1..), for the detail file
};

// Runs the trials one by one and keeps what the row and the detail file need.
class Scorer {
public:
    // @p alone_first: as the tracker searches a lost scan (slam_lost.c), the test scan
    // alone first, the scans together only when that answer is ambiguous.
    Scorer(std::string world, std::string input, const hl_reloc_params_t &reloc,
           bool alone_first = false)
        : world_(std::move(world)), input_(std::move(input)), reloc_(reloc),
          alone_first_(alone_first) {}

    // Relocalizes the scans of @p group (as the sensor gave them, with their odometry) in
    // @p slam's map and scores the answer against the test scan's truth. HL_OK with
    // `found` is a success or wrong; HL_OK without it and HL_ERR_EMPTY (no answer) are
    // ambiguous. Any other status means the experiment is set up wrong (a map too big for
    // the configured search): false, with one line.
    bool run(hl_slam_t *slam, const Group &group, std::string *err);

    // The trials that follow are in map @p index of @p count (1 of 1 until called).
    void set_map(int index, int count)
    {
        map_ = index;
        maps_ = count;
        map_first_ = trials_.size();
    }
    const std::vector<Trial> &trials() const { return trials_; }
    std::string name() const { return world_ + " " + input_; }
    // The row: world input trials success_pct ambiguous_pct wrong_pct median_ms p90_ms.
    void write_row(FILE *out) const;
    // One line per trial (seq, truth, answer, runner-up, errors, time), for tuning.
    bool write_detail(const std::string &path, std::string *err) const;
    // One progress line every @p every trials of the current map and at its @p total.
    void progress(int total, int every) const;

private:
    std::string world_, input_;
    hl_reloc_params_t reloc_;   // the search's parameters, for the reason of a failure
    bool alone_first_;
    std::vector<Trial> trials_;
    int map_ = 1, maps_ = 1;
    size_t map_first_ = 0;      // the current map's first trial: its trials are the rest
};

// The coarse raster one candidate heading of the global search needs over the bounding
// box of @p map (as the localizer places it), for the progress lines and the error.
uint64_t coarse_cells_needed(const hl_reloc_params_t &p, const hl_vector_t *map, uint32_t n,
                             double *width_m, double *height_m);

// Puts @p n vectors into @p slam's map (hl_slam_restore, the state of a started slam).
bool restore_map(hl_slam_t *slam, const hl_vector_t *v, uint32_t n, std::string *err);

// ---- simulated worlds (sim.cpp) -------------------------------------------------------

// Writes @p trials tests of @p scans soundings each in the simulated world @p world_path
// ("" = the built-in lab) to the LCM log @p log_path: the first at a random pose drawn
// with @p seed, free and in the toured space, uniformly random heading; the robot then
// drives kApartMm to 2 kApartMm to a free place in a random direction (or, boxed in,
// turns 45 degrees) and sounds again, its odometry erring as the tour's. Each a full
// sounding of the tour's robot and sonar.
bool write_sim_tests(const std::string &world_path, int trials, int scans, uint64_t seed,
                     const std::string &log_path, std::string *err);

// Loads the vectors of the daemon's map file @p path into @p slam.
bool load_daemon_map(hl_slam_t *slam, const std::string &path, std::string *err);

// ---- real buildings (real.cpp) --------------------------------------------------------

// Maps made from a log's scans at their true poses (no localization: what a drift-free
// robot would map), as the slam of @p p makes its map: capacity, culling seed, density
// bound, echo bearings. Each make() starts from an empty map and a new map's culling
// generator, so a map does not depend on those made before it.
class TruthMapper {
public:
    TruthMapper(const hl_slam_params_t &p, const hlexp::Soundings &log);
    ~TruthMapper();
    TruthMapper(const TruthMapper &) = delete;
    TruthMapper &operator=(const TruthMapper &) = delete;
    // Every scan of the log, in log order, but those within @p exclude_mm of any of
    // @p centres (a negative @p exclude_mm leaves none out).
    bool make(const std::vector<hl_pose_t> &centres, double exclude_mm, std::string *err);
    const hl_map_t *map() const { return map_; }

private:
    const hl_slam_params_t &p_;
    const hlexp::Soundings &log_;
    hl_map_t *map_;
    bool ok_ = false;
    hl_rng_t fresh_{};              // a new map's culling generator
    std::vector<hl_scan_t> placed_; // the scans at their echo bearings, when estimated
};

// For @p trials test scans spread evenly over @p log, each with the next scans of the log
// each at least kApartMm from the one before (up to reloc.scans in all): a map of every
// other scan more than @p exclude_mm from all of their true positions, at its true pose,
// in log order, made as the slam of @p p makes its map; then the trial.
bool run_real(const hl_slam_params_t &p, const hlexp::Soundings &log, int trials,
              double exclude_mm, Scorer *scorer, std::string *err);

}  // namespace hlkid
#endif
