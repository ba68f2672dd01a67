// metrics.hpp - trajectory error metrics of houghloc-eval, computed as the evo package
// computes them (github.com/MichaelGrupp/evo, checked against evo 1.38.1):
//
//   ATE  `evo_ape tum GT EST -a`: the estimate is moved onto the ground truth by the
//        least-squares rigid motion (Umeyama, no scale), then each pose's position error
//        is |gt_i - est_i|; reported as RMSE, mean and maximum.
//   RPE  `evo_rpe tum GT EST -r trans_part --delta D --delta_unit m -a`: pose pairs (i, j)
//        chosen by distance travelled (pairs_by_path), and for each the translation part
//        of (gt_i^-1 gt_j)^-1 (est_i^-1 est_j); reported as RMSE and mean.
//
// Plain 2-D math on doubles (Eigen inside), no I/O and no LCM, so the unit tests link it
// alone.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace hleval {

// One pose of a trajectory.
struct Pose2 {
    double t = 0;       // time, seconds
    double x = 0, y = 0;  // position, metres
    double theta = 0;   // heading, radians, counter-clockwise from +x
};
using Trajectory = std::vector<Pose2>;

// A rigid motion of the plane: p -> R(angle) p + (tx, ty). (Plain numbers: Eigen stays
// inside metrics.cpp, which builds it with settings of its own.)
struct Rigid2 {
    double angle = 0;       // radians, (-pi, pi]
    double tx = 0, ty = 0;  // metres
};

// Summary of a list of errors; all NaN when n == 0.
struct Stats {
    std::size_t n = 0;
    double rmse = std::numeric_limits<double>::quiet_NaN();
    double mean = std::numeric_limits<double>::quiet_NaN();
    double max = std::numeric_limits<double>::quiet_NaN();
};
Stats stats_of(const std::vector<double> &errors);

// The rigid motion that best maps est's positions onto gt's (least squares, no scale;
// Eigen::umeyama). gt and est must be non-empty and of equal size (else
// std::invalid_argument). One pose gives a pure translation.
Rigid2 align_rigid(const Trajectory &gt, const Trajectory &est);

// traj moved by a: positions mapped, headings turned by a's angle.
Trajectory transformed(const Rigid2 &a, const Trajectory &traj);

// Position errors |gt_i - est_i|, pose by pose (equal sizes, else std::invalid_argument).
std::vector<double> position_errors(const Trajectory &gt, const Trajectory &est);

using IdPairs = std::vector<std::pair<std::size_t, std::size_t>>;

// Consecutive pairs by distance travelled, as evo's filters.filter_pairs_by_path with
// all_pairs false: the first pose opens the first segment; walking on, the path length
// since the segment's first pose is summed step by step, and the first pose where it
// reaches delta_m (>=) closes the segment and opens the next one, the sum starting again
// from 0. Pairs are the consecutive segment ends: (i0, i1), (i1, i2), ...; the tail
// shorter than delta_m gives no pair. delta_m must be > 0 (else std::invalid_argument).
IdPairs pairs_by_path(const Trajectory &poses, double delta_m);

// For each pair (i, j), |translation of (gt_i^-1 gt_j)^-1 (est_i^-1 est_j)|, which is
// |R(est_i)^T (est_j - est_i) - R(gt_i)^T (gt_j - gt_i)|: the error of the motion from
// i to j as seen from pose i. A rigid motion of either whole trajectory leaves it alone.
std::vector<double> rpe_translation_errors(const Trajectory &gt, const Trajectory &est,
                                           const IdPairs &pairs);

// The same errors' components along the true motion of each pair and across it
// (signed; a pair whose true motion is under 1 mm has no direction and is left out): where
// a sensor sees walls only across a corridor, its error stays along it.
struct SplitErrors {
    std::vector<double> along, across;
};
SplitErrors rpe_translation_split(const Trajectory &gt, const Trajectory &est,
                                  const IdPairs &pairs);

struct Scores {
    Rigid2 alignment;  // est -> gt
    Stats ate;         // position errors after the alignment
    Stats rpe;         // translation RPE over pairs_by_path(est, delta_m)
    Stats rpe_along, rpe_across;    // its split (rpe_translation_split)
};

// Both metrics, as evo computes them with -a. evo picks RPE pairs on the estimate (its
// default, pairs_from_reference false); so does this. gt and est: equal, non-zero size.
Scores score(const Trajectory &gt, const Trajectory &est, double delta_m = 1.0);

// One line of the TUM trajectory format, "t x y z qx qy qz qw" with z = 0 and the
// heading as a rotation about z, without the newline.
std::string tum_line(const Pose2 &p);

}  // namespace hleval
