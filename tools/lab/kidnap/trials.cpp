// trials.cpp - one kidnap trial, its score, and the row of the table (kidnap.hpp).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>

#include "stats.hpp"
#include "kidnap.hpp"

namespace hlkid {

const char *const kHeader =
    "world\tinput\ttrials\tsuccess_pct\tambiguous_pct\twrong_pct\tmedian_ms\tp90_ms";

namespace {

double now_ms()
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) / 1e6;
}

// The median (the mean of the middle two for an even count) and the nearest-rank
// percentile: the smallest time at least @p q of the trials took no longer than.
double median(std::vector<double> v)
{
    if (v.empty())
        return 0.0;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2.0;
}

double nearest_rank(std::vector<double> v, double q)
{
    if (v.empty())
        return 0.0;
    std::sort(v.begin(), v.end());
    size_t k = static_cast<size_t>(std::ceil(q * static_cast<double>(v.size())));
    return v[k > 0 ? k - 1 : 0];
}

const char *outcome_name(Outcome o)
{
    return o == Outcome::Success ? "success" : o == Outcome::Wrong ? "wrong" : "ambiguous";
}

double pct(int k, size_t n)
{
    return n ? 100.0 * k / static_cast<double>(n) : 0.0;
}

}  // namespace

uint64_t coarse_cells_needed(const hl_reloc_params_t &p, const hl_vector_t *map, uint32_t n,
                             double *width_m, double *height_m)
{
    *width_m = *height_m = 0.0;
    if (n == 0)
        return 0;
    int32_t x0 = map[0].x_mm, x1 = x0, y0 = map[0].y_mm, y1 = y0;
    for (uint32_t i = 1; i < n; i++) {
        x0 = std::min(x0, map[i].x_mm);
        x1 = std::max(x1, map[i].x_mm);
        y0 = std::min(y0, map[i].y_mm);
        y1 = std::max(y1, map[i].y_mm);
    }
    *width_m = (x1 - x0) / 1000.0;
    *height_m = (y1 - y0) / 1000.0;
    uint64_t nx = static_cast<uint64_t>((x1 - x0) / p.coarse_cell_mm + 1);
    uint64_t ny = static_cast<uint64_t>((y1 - y0) / p.coarse_cell_mm + 1);
    return nx * ny * (2u * p.coarse_half_steps + 1u);
}

bool restore_map(hl_slam_t *slam, const hl_vector_t *v, uint32_t n, std::string *err)
{
    hl_slam_state_t st;
    hl_slam_get_state(slam, &st);
    st.started = true;      // a map and no pose: what a kidnapped robot has
    hl_status_t s = hl_slam_restore(slam, &st, v, n);
    if (s != HL_OK) {
        *err = std::string("cannot restore the map (") + std::to_string(n) + " vectors): " +
               hl_status_str(s);
        return false;
    }
    return true;
}

// Climbs hl_slam_judge's score of @p scan from @p from (scored @p score): each step tries
// the pose turned by +-step and moved by +-step along x and y, takes the best that scores
// higher, and halves the steps when none does (2 degrees and 50 mm down to an eighth),
// staying within kTruthNearMm and kTruthNearDeg of @p centre. The search's poses and the
// grid below are good to a step; a laser's far readings need a tenth of a degree.
static uint32_t climb(hl_slam_t *slam, const hl_scan_t &scan, hl_pose_t centre,
                      hl_pose_t from, uint32_t score)
{
    const hl_bam_t near_theta = hl_bam_from_deg(kTruthNearDeg);
    hl_pose_t at = from;
    int32_t dt = hl_bam_from_deg(2.0), dxy = 50;
    for (int level = 0; level < 4; level++, dt /= 2, dxy /= 2)
        for (int step = 0; step < 40; step++) {
            hl_pose_t next[6] = { at, at, at, at, at, at };
            next[0].theta = static_cast<hl_bam_t>(at.theta + dt);
            next[1].theta = static_cast<hl_bam_t>(at.theta - dt);
            next[2].x_mm += dxy;
            next[3].x_mm -= dxy;
            next[4].y_mm += dxy;
            next[5].y_mm -= dxy;
            uint32_t scores[6];
            hl_slam_judge_poses(slam, &scan, next, 6, scores);
            int best = -1;
            for (int k = 0; k < 6; k++) {
                int32_t turn = hl_bam_diff(next[k].theta, centre.theta);
                bool inside = std::abs(next[k].x_mm - centre.x_mm) <= kTruthNearMm &&
                              std::abs(next[k].y_mm - centre.y_mm) <= kTruthNearMm &&
                              std::abs(turn) <= near_theta;
                if (inside && scores[k] > score) {
                    score = scores[k];
                    best = k;
                }
            }
            if (best < 0)
                break;
            at = next[best];
        }
    return score;
}

// The best judge of @p scan around @p truth: the best of a grid, climbed. The map drifts
// from the world a little, and the ground truth is good to a few cm and a fraction of a
// degree, so the truth itself may score less than the place does a little away.
static uint32_t truth_score(hl_slam_t *slam, const hl_scan_t &scan, hl_pose_t truth)
{
    std::vector<hl_pose_t> grid;
    for (int dx = -kTruthNearMm; dx <= kTruthNearMm; dx += kTruthStepMm)
        for (int dy = -kTruthNearMm; dy <= kTruthNearMm; dy += kTruthStepMm)
            for (int dd = -kTruthNearDeg; dd <= kTruthNearDeg; dd += kTruthStepDeg)
                grid.push_back({ truth.x_mm + dx, truth.y_mm + dy,
                                 static_cast<hl_bam_t>(truth.theta + hl_bam_from_deg(dd)) });
    std::vector<uint32_t> scores(grid.size());
    hl_slam_judge_poses(slam, &scan, grid.data(), static_cast<uint32_t>(grid.size()),
                        scores.data());
    size_t best = static_cast<size_t>(std::max_element(scores.begin(), scores.end()) -
                                      scores.begin());
    return climb(slam, scan, truth, grid[best], scores[best]);
}

bool Scorer::run(hl_slam_t *slam, const Group &group, std::string *err)
{
    const hlexp::Sounding &test = *group.front();
    Trial t;
    t.map = map_;
    t.seq = test.msg.seq;
    t.truth = test.truth;
    t.scans = static_cast<int>(group.size());
    t.map_vectors = hl_map_count(hl_slam_map(slam));
    const hl_vector_t *v = hl_map_vectors(hl_slam_map(slam));
    for (uint32_t i = 0; i < t.map_vectors; i++)
        t.near_vectors += std::hypot(static_cast<double>(v[i].x_mm) - t.truth.x_mm,
                                     static_cast<double>(v[i].y_mm) - t.truth.y_mm) <= kNearMm;
    std::vector<const hl_scan_t *> scans;
    std::vector<hl_pose_t> odometry;
    for (const hlexp::Sounding *g : group) {
        scans.push_back(&g->msg.scan);
        odometry.push_back(g->msg.odometry);
    }
    double t0 = now_ms();
    t.status = HL_ERR_EMPTY;
    if (alone_first_)
        t.status = hl_slam_relocalize(slam, scans[0], &t.result);
    if (!(t.status == HL_OK && t.result.found) && (!alone_first_ || scans.size() > 1))
        t.status = hl_slam_relocalize_scans(slam, scans.data(), odometry.data(),
                                            static_cast<uint32_t>(scans.size()), &t.result);
    t.ms = now_ms() - t0;
    if (t.status != HL_OK && t.status != HL_ERR_EMPTY) {
        *err = "scan " + std::to_string(t.seq) + ": hl_slam_relocalize_scans: " +
               hl_status_str(t.status);
        double w, h;
        uint64_t cells = coarse_cells_needed(reloc_, v, t.map_vectors, &w, &h);
        if (t.status == HL_ERR_CAPACITY && cells > reloc_.coarse_max_cells) {
            char buf[240];
            std::snprintf(buf, sizeof buf,
                          " (the map of %u vectors spans %.1f x %.1f m: %llu coarse cells, "
                          "reloc.coarse_max_cells is %u)",
                          t.map_vectors, w, h, static_cast<unsigned long long>(cells),
                          reloc_.coarse_max_cells);
            *err += buf;
        }
        return false;
    }
    t.truth_score = truth_score(slam, test.msg.scan, t.truth);
    t.truth_scans_score = t.truth_score;
    for (size_t k = 1; k < group.size(); k++)
        t.truth_scans_score += truth_score(slam, group[k]->msg.scan, group[k]->truth);
    if (t.status == HL_OK) {
        t.answer_climbed = climb(slam, test.msg.scan, t.result.pose, t.result.pose,
                                 hl_slam_judge(slam, &test.msg.scan, t.result.pose));
        t.error_mm = hlexp::distance_mm(t.result.pose, t.truth);
        int32_t d = hl_bam_diff(t.result.pose.theta, t.truth.theta);
        t.error_deg = std::fabs(d * (360.0 / 65536.0));
    }
    if (t.status == HL_OK && t.result.found)
        t.outcome = t.error_mm <= kSuccessMm && t.error_deg <= kSuccessDeg ? Outcome::Success
                                                                           : Outcome::Wrong;
    else
        t.outcome = Outcome::Ambiguous;     // not found, or no answer at all
    trials_.push_back(t);
    return true;
}

void Scorer::write_row(FILE *out) const
{
    int ok = 0, amb = 0, wrong = 0;
    std::vector<double> ms;
    for (const Trial &t : trials_) {
        ok += t.outcome == Outcome::Success;
        amb += t.outcome == Outcome::Ambiguous;
        wrong += t.outcome == Outcome::Wrong;
        ms.push_back(t.ms);
    }
    size_t n = trials_.size();
    std::fprintf(out, "%s\t%s\t%zu\t%.1f\t%.1f\t%.1f\t%.2f\t%.2f\n", world_.c_str(),
                 input_.c_str(), n, pct(ok, n), pct(amb, n), pct(wrong, n), median(ms),
                 nearest_rank(ms, 0.9));
}

void Scorer::progress(int total, int every) const
{
    size_t n = trials_.size() - map_first_;
    if (n == 0 || (n % static_cast<size_t>(every) != 0 && n != static_cast<size_t>(total)))
        return;
    int ok = 0, amb = 0;
    std::vector<double> ms;
    for (size_t i = map_first_; i < trials_.size(); i++) {
        const Trial &t = trials_[i];
        ok += t.outcome == Outcome::Success;
        amb += t.outcome == Outcome::Ambiguous;
        ms.push_back(t.ms);
    }
    std::string which = maps_ > 1 ? " map " + std::to_string(map_) + "/" +
                                        std::to_string(maps_) + ":" : "";
    std::fprintf(stderr,
                 "kidnap: %s %s:%s %zu/%d trials: success %.1f %%, ambiguous %.1f %%, wrong "
                 "%.1f %%, median %.1f ms\n",
                 world_.c_str(), input_.c_str(), which.c_str(), n, total, pct(ok, n),
                 pct(amb, n), pct(static_cast<int>(n) - ok - amb, n), median(ms));
}

bool Scorer::write_detail(const std::string &path, std::string *err) const
{
    FILE *f = std::fopen(path.c_str(), "w");
    if (!f) {
        *err = path + ": " + std::strerror(errno);
        return false;
    }
    std::fprintf(f, "seq\toutcome\tstatus\ttrue_x_mm\ttrue_y_mm\ttrue_deg\tx_mm\ty_mm\tdeg\t"
                    "error_mm\terror_deg\texplained_pct\tscore\trunner_up_score\t"
                    "runner_x_mm\trunner_y_mm\trunner_deg\tmap_vectors\tnear_vectors\tms\t"
                    "truth_score\tedge\trunner_edge\tmap\tanswer_climbed\tscans\ttruth_scans_score\n");
    for (const Trial &t : trials_) {
        const hl_reloc_result_t &r = t.result;
        std::fprintf(f, "%d\t%s\t%s\t%d\t%d\t%.1f\t%d\t%d\t%.1f\t%.0f\t%.1f\t%.1f\t%u\t%u\t"
                        "%d\t%d\t%.1f\t%u\t%u\t%.2f\t%u\t%u\t%u\t%d\t%u\t%d\t%u\n",
                     t.seq, outcome_name(t.outcome), hl_status_str(t.status), t.truth.x_mm,
                     t.truth.y_mm, hl_bam_to_deg(t.truth.theta), r.pose.x_mm, r.pose.y_mm,
                     hl_bam_to_deg(r.pose.theta), t.error_mm, t.error_deg, r.explained_pct,
                     r.score, r.runner_up_score, r.runner_up.x_mm, r.runner_up.y_mm,
                     hl_bam_to_deg(r.runner_up.theta), t.map_vectors, t.near_vectors, t.ms,
                     t.truth_score, r.edge, r.runner_edge, t.map, t.answer_climbed, t.scans, t.truth_scans_score);
    }
    if (std::fclose(f) != 0) {
        *err = path + ": write failed";
        return false;
    }
    return true;
}

}  // namespace hlkid
