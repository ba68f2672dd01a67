// pose_graph.hpp - a 2-D pose graph and its least-squares solution (Gauss-Newton, dense):
// what a tour's stops would be if every match between two of them had to hold at once.
// For hl-tour-study's study of loop closure (docs/kidnap.md, "Tenth session"); doubles,
// tools only.
#ifndef HLKID_POSE_GRAPH_HPP
#define HLKID_POSE_GRAPH_HPP

#include <vector>

namespace hlkid {

struct Pose2 {
    double x = 0, y = 0, theta = 0;     // mm, mm, radians
};

// Pose @p b in the frame of @p a, and its inverse.
Pose2 between(const Pose2 &a, const Pose2 &b);
Pose2 compose(const Pose2 &a, const Pose2 &rel);

// A measurement of stop `to` in the frame of stop `from`, with its standard deviations.
struct Edge {
    int from = 0, to = 0;
    Pose2 rel;
    double sigma_mm = 50, sigma_rad = 0.03;
    bool loop = false;          // a closure (may be dropped as an outlier), not a step
};

// Moves @p poses (stop 0 held fixed) to the least-squares fit of @p edges, by
// @p iterations Gauss-Newton steps. Edges whose normalized error exceeds @p gate (in
// standard deviations, after a first solution) are dropped and the fit solved again;
// returns how many loop edges were kept.
int solve_pose_graph(std::vector<Pose2> *poses, std::vector<Edge> *edges, int iterations,
                     double gate);

}  // namespace hlkid
#endif
