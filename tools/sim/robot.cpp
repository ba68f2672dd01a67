// robot.cpp - sounding procedure and noisy motion.
#include "robot.hpp"

#include <cmath>

#include "houghloc/fixed.h"

namespace hlsim {

namespace {
int64_t seconds_to_us(double s)
{
    return static_cast<int64_t>(std::llround(s * 1e6));
}
}  // namespace

Robot::Robot(const World &world, const SonarParams &sonar, const RobotParams &params,
             Rng &rng, int64_t start_utime)
    : world_(world), sonar_(sonar), params_(params), rng_(rng), utime_(start_utime)
{
}

void Robot::place(const Pose &truth, const Pose &odom)
{
    truth_ = truth;
    odom_ = odom;
}

// Emits odometry samples at the report period while moving from @p from to @p to,
// then one "stopped" sample; advances the clock by the motion's duration. The true pose
// of each sample runs the same way from @p truth_from to the (already moved) truth_.
void Robot::report_motion(const Pose &from, const Pose &to, const Pose &truth_from,
                          double seconds, double speed)
{
    int64_t start = utime_;
    int64_t dur = seconds_to_us(seconds);
    int64_t period = seconds_to_us(params_.odometry_period_s);
    double dth = wrap_pi(to.theta - from.theta);
    double true_dth = wrap_pi(truth_.theta - truth_from.theta);
    for (int64_t t = period; t < dur; t += period) {
        double f = static_cast<double>(t) / static_cast<double>(dur);
        OdoSample s;
        s.utime = start + t;
        s.odom = {from.x + f * (to.x - from.x), from.y + f * (to.y - from.y),
                  wrap_pi(from.theta + f * dth)};
        s.velocity_mm_s = speed;
        s.stopped = false;
        s.truth = {truth_from.x + f * (truth_.x - truth_from.x),
                   truth_from.y + f * (truth_.y - truth_from.y),
                   wrap_pi(truth_from.theta + f * true_dth)};
        odo_.push_back(s);
    }
    utime_ = start + dur;
    OdoSample s;
    s.utime = utime_;
    s.odom = to;
    s.velocity_mm_s = 0.0;
    s.stopped = true;
    s.truth = truth_;
    odo_.push_back(s);
}

void Robot::turn(double dtheta)
{
    Pose from = odom_, truth_from = truth_;
    odom_.theta = wrap_pi(odom_.theta + dtheta);
    double err = rng_.normal(0.0, params_.odo_turn_frac * std::fabs(dtheta));
    truth_.theta = wrap_pi(truth_.theta + dtheta + err);
    report_motion(from, odom_, truth_from, std::fabs(rad2deg(dtheta)) / params_.turn_rate_deg_s,
                  0.0);
}

void Robot::drive(double dist_mm)
{
    Pose from = odom_, truth_from = truth_;
    odom_.x += dist_mm * std::cos(odom_.theta);
    odom_.y += dist_mm * std::sin(odom_.theta);
    double d = std::fabs(dist_mm);
    double fwd = dist_mm + rng_.normal(0.0, params_.odo_dist_frac * d);
    double lat = rng_.normal(0.0, params_.odo_dist_frac * d);
    double dth = rng_.normal(0.0, deg2rad(params_.odo_heading_deg_per_m) * d / 1000.0);
    // Half the heading error acts during the leg, half shows at its end.
    double mid = truth_.theta + dth / 2.0;
    truth_.x += fwd * std::cos(mid) - lat * std::sin(mid);
    truth_.y += fwd * std::sin(mid) + lat * std::cos(mid);
    truth_.theta = wrap_pi(truth_.theta + dth);
    double speed = dist_mm < 0.0 ? -params_.speed_mm_s : params_.speed_mm_s;
    report_motion(from, odom_, truth_from, d / params_.speed_mm_s, speed);
}

void Robot::go_to(Vec2 target)
{
    Vec2 to = target - odom_.pos();
    if (to.norm() < 1.0)
        return;
    double bearing = std::atan2(to.y, to.x);
    double dth = wrap_pi(bearing - odom_.theta);
    if (std::fabs(dth) > 1e-9)
        turn(dth);
    drive(to.norm());
}

void Robot::steer_to(Vec2 target)
{
    Vec2 to = target - truth_.pos();
    if (to.norm() < 1.0)
        return;
    double dth = wrap_pi(std::atan2(to.y, to.x) - truth_.theta);
    if (std::fabs(dth) > 1e-9)
        turn(dth);
    drive(to.norm());
}

void Robot::move(double dx, double dy)
{
    double c = std::cos(odom_.theta), s = std::sin(odom_.theta);
    go_to({odom_.x + c * dx - s * dy, odom_.y + s * dx + c * dy});
}

void Robot::turn_to(double heading)
{
    double dth = wrap_pi(heading - odom_.theta);
    if (std::fabs(dth) > 1e-12)
        turn(dth);
}

void Robot::wait(double seconds)
{
    utime_ += seconds_to_us(seconds);
}

Sounding Robot::sound()
{
    const RobotParams &p = params_;
    // The body rotates by one step between rounds of pings; each step errs a little,
    // and the errors accumulate over the sounding.
    std::vector<double> body(static_cast<std::size_t>(p.rotation_steps));
    double heading = truth_.theta;
    for (int s = 0; s < p.rotation_steps; s++) {
        if (s > 0)
            heading += deg2rad(p.rotation_step_deg) + rng_.normal(0.0, deg2rad(p.rotation_sigma_deg));
        body[static_cast<std::size_t>(s)] = heading;
    }
    Sounding out;
    out.readings.reserve(static_cast<std::size_t>(p.transducers * p.rotation_steps));
    for (int t = 0; t < p.transducers; t++) {
        for (int s = 0; s < p.rotation_steps; s++) {
            RingReading r;
            r.transducer = t;
            r.step = s;
            double nominal_deg = t * p.transducer_spacing_deg + s * p.rotation_step_deg;
            r.bearing_bam = hl_bam_from_deg(nominal_deg);
            r.true_axis = wrap_pi(body[static_cast<std::size_t>(s)] +
                                  deg2rad(t * p.transducer_spacing_deg));
            r.sonar = sonar_ping(world_, sonar_, truth_.pos(), r.true_axis, rng_);
            out.readings.push_back(r);
        }
    }
    // The body turns back to where it started (its encoders are good over a few
    // degrees); the true heading is unchanged by a sounding.
    utime_ += seconds_to_us(p.rotation_steps * p.step_time_s +
                            (p.rotation_steps - 1) * p.rotation_step_deg / p.turn_rate_deg_s);
    out.utime = utime_;
    out.odom = odom_;
    out.truth = truth_;
    return out;
}

std::vector<OdoSample> Robot::take_odometry()
{
    std::vector<OdoSample> out;
    out.swap(odo_);
    return out;
}

}  // namespace hlsim
