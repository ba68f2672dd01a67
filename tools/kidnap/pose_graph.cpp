// pose_graph.cpp - a 2-D pose graph by Gauss-Newton (pose_graph.hpp).
#include "pose_graph.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace hlkid {
namespace {

double wrap(double a)
{
    return std::atan2(std::sin(a), std::cos(a));
}

// The edge's error and its Jacobians in the two poses it joins.
Eigen::Vector3d residual(const Pose2 &a, const Pose2 &b, const Edge &e, Eigen::Matrix3d *ja,
                         Eigen::Matrix3d *jb)
{
    double c = std::cos(a.theta), s = std::sin(a.theta);
    double dx = b.x - a.x, dy = b.y - a.y;
    Eigen::Vector3d r(c * dx + s * dy - e.rel.x, -s * dx + c * dy - e.rel.y,
                      wrap(b.theta - a.theta - e.rel.theta));
    *ja << -c, -s, -s * dx + c * dy,
            s, -c, -c * dx - s * dy,
            0, 0, -1;
    *jb << c, s, 0,
           -s, c, 0,
           0, 0, 1;
    return r;
}

Eigen::Matrix3d information(const Edge &e)
{
    Eigen::Vector3d w(1 / (e.sigma_mm * e.sigma_mm), 1 / (e.sigma_mm * e.sigma_mm),
                      1 / (e.sigma_rad * e.sigma_rad));
    return w.asDiagonal();
}

void gauss_newton(std::vector<Pose2> *poses, const std::vector<Edge> &edges, int iterations)
{
    const int n = static_cast<int>(poses->size());
    for (int it = 0; it < iterations; it++) {
        Eigen::MatrixXd h = Eigen::MatrixXd::Zero(3 * n, 3 * n);
        Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * n);
        for (const Edge &e : edges) {
            Eigen::Matrix3d ja, jb, w = information(e);
            Eigen::Vector3d r = residual((*poses)[e.from], (*poses)[e.to], e, &ja, &jb);
            int i = 3 * e.from, j = 3 * e.to;
            h.block<3, 3>(i, i) += ja.transpose() * w * ja;
            h.block<3, 3>(i, j) += ja.transpose() * w * jb;
            h.block<3, 3>(j, i) += jb.transpose() * w * ja;
            h.block<3, 3>(j, j) += jb.transpose() * w * jb;
            g.segment<3>(i) += ja.transpose() * w * r;
            g.segment<3>(j) += jb.transpose() * w * r;
        }
        h.block<3, 3>(0, 0) += Eigen::Matrix3d::Identity() * 1e12;    // stop 0 is held
        Eigen::VectorXd d = h.ldlt().solve(-g);
        for (int k = 0; k < n; k++) {
            (*poses)[k].x += d(3 * k);
            (*poses)[k].y += d(3 * k + 1);
            (*poses)[k].theta = wrap((*poses)[k].theta + d(3 * k + 2));
        }
        if (d.cwiseAbs().maxCoeff() < 1e-3)
            break;
    }
}

}  // namespace

Pose2 between(const Pose2 &a, const Pose2 &b)
{
    double c = std::cos(a.theta), s = std::sin(a.theta);
    double dx = b.x - a.x, dy = b.y - a.y;
    return Pose2{ c * dx + s * dy, -s * dx + c * dy, wrap(b.theta - a.theta) };
}

Pose2 compose(const Pose2 &a, const Pose2 &rel)
{
    double c = std::cos(a.theta), s = std::sin(a.theta);
    return Pose2{ a.x + c * rel.x - s * rel.y, a.y + s * rel.x + c * rel.y,
                  wrap(a.theta + rel.theta) };
}

int solve_pose_graph(std::vector<Pose2> *poses, std::vector<Edge> *edges, int iterations,
                     double gate)
{
    gauss_newton(poses, *edges, iterations);
    std::vector<Edge> kept;
    for (const Edge &e : *edges) {
        Eigen::Matrix3d ja, jb;
        Eigen::Vector3d r = residual((*poses)[e.from], (*poses)[e.to], e, &ja, &jb);
        double chi = std::sqrt(r.dot(information(e) * r) / 3.0);
        if (!e.loop || chi <= gate)
            kept.push_back(e);
    }
    *edges = kept;
    gauss_newton(poses, *edges, iterations);
    int loops = 0;
    for (const Edge &e : *edges)
        loops += e.loop;
    return loops;
}

}  // namespace hlkid
