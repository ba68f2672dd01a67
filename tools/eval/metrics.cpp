// metrics.cpp - trajectory error metrics as evo computes them (metrics.hpp).
//
// Eigen is used here only, built without explicit vectorization: GCC 12 at -O2 reports
// false -Wstringop-overread (an SSE store "reading" 16 bytes of an 8-byte part of a
// 2-vector) inside Eigen::umeyama's inlined code, which -Werror would make fatal, and
// speed does not matter for a few thousand poses. The setting changes the alignment of
// Eigen's fixed-size types, so none of them appears in metrics.hpp.
#define EIGEN_DONT_VECTORIZE
#include "metrics.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace hleval {

namespace {

constexpr double kPi = 3.14159265358979323846;

void check_sizes(const Trajectory &gt, const Trajectory &est)
{
    if (gt.size() != est.size())
        throw std::invalid_argument("trajectories of different lengths");
    if (gt.empty())
        throw std::invalid_argument("empty trajectory");
}

Eigen::Vector2d pos(const Pose2 &p)
{
    return Eigen::Vector2d(p.x, p.y);
}

// R(theta)^T: world vectors into the frame of a pose with heading theta.
Eigen::Matrix2d to_frame(double theta)
{
    return Eigen::Rotation2Dd(theta).toRotationMatrix().transpose();
}

}  // namespace

Stats stats_of(const std::vector<double> &errors)
{
    Stats s;
    s.n = errors.size();
    if (s.n == 0)
        return s;
    double sum = 0, sq = 0, max = 0;
    for (double e : errors) {
        sum += e;
        sq += e * e;
        max = e > max ? e : max;
    }
    s.rmse = std::sqrt(sq / static_cast<double>(s.n));
    s.mean = sum / static_cast<double>(s.n);
    s.max = max;
    return s;
}

Rigid2 align_rigid(const Trajectory &gt, const Trajectory &est)
{
    check_sizes(gt, est);
    const Eigen::Index n = static_cast<Eigen::Index>(gt.size());
    Eigen::Matrix2Xd src(2, n), dst(2, n);
    for (Eigen::Index i = 0; i < n; i++) {
        src.col(i) = pos(est[static_cast<std::size_t>(i)]);
        dst.col(i) = pos(gt[static_cast<std::size_t>(i)]);
    }
    // Eigen's Umeyama keeps the result a proper rotation (it flips the smallest singular
    // direction when the best orthogonal map would be a reflection). evo works in 3-D on
    // z = 0 and flips its zero-variance z axis instead, so for an estimate that is a
    // mirror image of the truth the two differ; for any other they agree.
    Eigen::Matrix3d T = Eigen::umeyama(src, dst, false);
    Rigid2 a;
    a.angle = std::atan2(T(1, 0), T(0, 0));
    a.tx = T(0, 2);
    a.ty = T(1, 2);
    return a;
}

Trajectory transformed(const Rigid2 &a, const Trajectory &traj)
{
    Trajectory out = traj;
    const Eigen::Rotation2Dd R(a.angle);
    const Eigen::Vector2d t(a.tx, a.ty);
    for (Pose2 &p : out) {
        Eigen::Vector2d q = R * pos(p) + t;
        p.x = q.x();
        p.y = q.y();
        p.theta = std::remainder(p.theta + a.angle, 2 * kPi);
    }
    return out;
}

std::vector<double> position_errors(const Trajectory &gt, const Trajectory &est)
{
    if (gt.size() != est.size())
        throw std::invalid_argument("trajectories of different lengths");
    std::vector<double> e(gt.size());
    for (std::size_t i = 0; i < gt.size(); i++)
        e[i] = (pos(gt[i]) - pos(est[i])).norm();
    return e;
}

IdPairs pairs_by_path(const Trajectory &poses, double delta_m)
{
    if (!(delta_m > 0))
        throw std::invalid_argument("delta must be > 0");
    IdPairs pairs;
    if (poses.empty())
        return pairs;
    // evo: ids = [0]; path = 0; for each next pose: path += step; if path >= delta:
    // ids.append(i); path = 0. Then pairs of consecutive ids. The step is summed pose to
    // pose (not measured from the segment's start), so a segment's path is what the
    // robot travelled, and it ends at the first pose at or past delta.
    std::size_t open = 0;
    double path = 0;
    for (std::size_t i = 1; i < poses.size(); i++) {
        path += (pos(poses[i]) - pos(poses[i - 1])).norm();
        if (path >= delta_m) {
            pairs.emplace_back(open, i);
            open = i;
            path = 0;
        }
    }
    return pairs;
}

namespace {

// The motion from pose i to pose j as seen from pose i, true (q) and estimated (p).
struct PairMotion {
    Eigen::Vector2d q, p;
};

std::vector<PairMotion> pair_motions(const Trajectory &gt, const Trajectory &est,
                                     const IdPairs &pairs)
{
    if (gt.size() != est.size())
        throw std::invalid_argument("trajectories of different lengths");
    std::vector<PairMotion> m;
    m.reserve(pairs.size());
    for (const auto &[i, j] : pairs) {
        if (i >= gt.size() || j >= gt.size())
            throw std::invalid_argument("pair index out of range");
        m.push_back({ to_frame(gt[i].theta) * (pos(gt[j]) - pos(gt[i])),
                      to_frame(est[i].theta) * (pos(est[j]) - pos(est[i])) });
    }
    return m;
}

}  // namespace

std::vector<double> rpe_translation_errors(const Trajectory &gt, const Trajectory &est,
                                           const IdPairs &pairs)
{
    // E = Q_rel^-1 P_rel with Q_rel = gt_i^-1 gt_j, P_rel = est_i^-1 est_j; the
    // translation of E is R(Q_rel)^T (t(P_rel) - t(Q_rel)), whose norm is that of
    // t(P_rel) - t(Q_rel).
    std::vector<double> e;
    for (const PairMotion &m : pair_motions(gt, est, pairs))
        e.push_back((m.p - m.q).norm());
    return e;
}

SplitErrors rpe_translation_split(const Trajectory &gt, const Trajectory &est,
                                  const IdPairs &pairs)
{
    SplitErrors e;
    for (const PairMotion &m : pair_motions(gt, est, pairs)) {
        if (m.q.norm() < 1e-3)
            continue;
        Eigen::Vector2d u = m.q.normalized(), d = m.p - m.q;
        e.along.push_back(d.dot(u));
        e.across.push_back(u.x() * d.y() - u.y() * d.x());
    }
    return e;
}

Scores score(const Trajectory &gt, const Trajectory &est, double delta_m)
{
    check_sizes(gt, est);
    Scores s;
    s.alignment = align_rigid(gt, est);
    Trajectory aligned = transformed(s.alignment, est);
    s.ate = stats_of(position_errors(gt, aligned));
    IdPairs pairs = pairs_by_path(aligned, delta_m);
    s.rpe = stats_of(rpe_translation_errors(gt, aligned, pairs));
    SplitErrors split = rpe_translation_split(gt, aligned, pairs);
    s.rpe_along = stats_of(split.along);
    s.rpe_across = stats_of(split.across);
    return s;
}

std::string tum_line(const Pose2 &p)
{
    char buf[160];
    std::snprintf(buf, sizeof buf, "%.6f %.6f %.6f 0 0 0 %.9f %.9f", p.t, p.x, p.y,
                  std::sin(p.theta / 2), std::cos(p.theta / 2));
    return buf;
}

}  // namespace hleval
