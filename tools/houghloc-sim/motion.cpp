// motion.cpp - the differential base: velocity profiles, odometry, true pose, walls.
#include "motion.hpp"

#include <algorithm>
#include <cmath>

namespace hlsim {

namespace {

// Moves @p cur toward @p want by at most the acceleration (when speeding up) or the
// deceleration (when slowing down or reversing) times @p dt.
double ramp(double cur, double want, double acc, double dec, double dt)
{
    double diff = want - cur;
    bool faster = (cur >= 0.0 && diff > 0.0) || (cur <= 0.0 && diff < 0.0);
    double lim = (faster ? acc : dec) * dt;
    if (diff > lim)
        return cur + lim;
    if (diff < -lim)
        return cur - lim;
    return want;
}

// The speed that still stops within @p left at deceleration @p dec, capped at @p vmax,
// signed like @p left.
double braking_speed(double left, double vmax, double dec)
{
    double s = std::min(vmax, std::sqrt(2.0 * dec * std::fabs(left)));
    return left < 0.0 ? -s : s;
}

// Whether a step of @p step reaches or passes what is @p left in the same direction.
bool reaches(double step, double left)
{
    return left == 0.0 || (step * left > 0.0 && std::fabs(step) >= std::fabs(left));
}

}  // namespace

Base::Base(const World &world, const RobotParams &noise, Rng &rng)
    : world_(world), noise_(noise), rng_(rng)
{
}

void Base::place(const Pose &truth)
{
    halt();
    truth_ = truth;
    odom_ = Pose{};
    in_contact_ = false;
}

void Base::reset_odometry()
{
    odom_ = Pose{};
    if (rmode_ == Mode::Position)
        turn_target_ = turn_left_;
}

void Base::draw_errors()
{
    fwd_err_ = rng_.normal(0.0, noise_.odo_dist_frac);
    lat_err_ = rng_.normal(0.0, noise_.odo_dist_frac);
    drift_rad_per_mm_ = rng_.normal(0.0, deg2rad(noise_.odo_heading_deg_per_m) / 1000.0);
    turn_err_ = rng_.normal(0.0, noise_.odo_turn_frac);
}

void Base::move(double mm)
{
    draw_errors();
    tmode_ = Mode::Position;
    move_left_ = mm;
}

void Base::vel(double mm_s)
{
    draw_errors();
    tmode_ = Mode::Velocity;
    vel_target_ = mm_s;
}

void Base::head(double heading)
{
    draw_errors();
    rmode_ = Mode::Position;
    turn_left_ = wrap_pi(heading - odom_.theta);
    turn_target_ = odom_.theta + turn_left_;
}

void Base::dhead(double dtheta)
{
    draw_errors();
    rmode_ = Mode::Position;
    turn_left_ = dtheta;
    turn_target_ = odom_.theta + dtheta;
}

void Base::rvel(double rad_s)
{
    draw_errors();
    rmode_ = Mode::Velocity;
    rvel_target_ = rad_s;
}

void Base::stop()
{
    tmode_ = rmode_ = Mode::Velocity;
    vel_target_ = rvel_target_ = 0.0;
}

void Base::halt()
{
    tmode_ = rmode_ = Mode::Idle;
    vel_target_ = rvel_target_ = move_left_ = turn_left_ = 0.0;
    v_ = w_ = 0.0;
}

double Base::translation_wanted() const
{
    switch (tmode_) {
    case Mode::Velocity:
        return std::clamp(vel_target_, -limits.vmax, limits.vmax);
    case Mode::Position:
        return braking_speed(move_left_, limits.vmax, limits.decel);
    case Mode::Idle:
        break;
    }
    return 0.0;
}

double Base::rotation_wanted() const
{
    switch (rmode_) {
    case Mode::Velocity:
        return std::clamp(rvel_target_, -limits.rvmax, limits.rvmax);
    case Mode::Position:
        return braking_speed(turn_left_, limits.rvmax, limits.rdecel);
    case Mode::Idle:
        break;
    }
    return 0.0;
}

bool Base::moving() const
{
    bool translating = (tmode_ == Mode::Position && move_left_ != 0.0) ||
                       (tmode_ == Mode::Velocity && vel_target_ != 0.0);
    bool rotating = (rmode_ == Mode::Position && turn_left_ != 0.0) ||
                    (rmode_ == Mode::Velocity && rvel_target_ != 0.0);
    return translating || rotating || v_ != 0.0 || w_ != 0.0;
}

double Base::control_heading() const
{
    return rmode_ == Mode::Position ? wrap_pi(turn_target_) : odom_.theta;
}

bool Base::take_stall()
{
    bool s = stalled_;
    stalled_ = false;
    return s;
}

// A step is refused when it ends closer to a surface than the body's radius and closer
// than it started (so a robot that ended up too close can still back away).
bool Base::blocked(Vec2 from, Vec2 to) const
{
    double c1 = world_.clearance(to);
    return c1 < kRadiusMm && c1 < world_.clearance(from);
}

void Base::advance(double dt)
{
    if (wheels_stalled_) {
        if (moving())
            stalled_ = true;
        v_ = w_ = 0.0;
        return;
    }
    w_ = ramp(w_, rotation_wanted(), limits.raccel, limits.rdecel, dt);
    double dth = w_ * dt;
    bool turn_done = rmode_ == Mode::Position && reaches(dth, turn_left_);
    if (turn_done)
        dth = turn_left_;

    v_ = ramp(v_, translation_wanted(), limits.accel, limits.decel, dt);
    double ds = v_ * dt;
    bool move_done = tmode_ == Mode::Position && reaches(ds, move_left_);
    if (move_done)
        ds = move_left_;

    // The true motion: this command's errors, proportional to the odometry's motion;
    // half the heading change acts along the step.
    double dth_true = dth * (1.0 + turn_err_) + std::fabs(ds) * drift_rad_per_mm_;
    double mid = truth_.theta + dth_true / 2.0;
    double fwd = ds * (1.0 + fwd_err_), lat = ds * lat_err_;
    Vec2 to = truth_.pos() + Vec2{fwd * std::cos(mid) - lat * std::sin(mid),
                                  fwd * std::sin(mid) + lat * std::cos(mid)};
    if (ds != 0.0 && blocked(truth_.pos(), to)) {
        // The wheels stop against the wall: neither pose moves; a turn in place still can.
        if (!in_contact_)
            collisions_++;   // the rising edge: a new contact episode
        in_contact_ = true;
        stalled_ = true;
        v_ = 0.0;
        ds = 0.0;
        move_done = false;
        dth_true = dth * (1.0 + turn_err_);
        to = truth_.pos();
    } else if (in_contact_ && ds != 0.0 &&
               world_.clearance(to) >= kRadiusMm + kContactReleaseMm) {
        in_contact_ = false;   // a step away from the surface: the contact has ended
    }

    double mid_odom = odom_.theta + dth / 2.0;
    odom_.x += ds * std::cos(mid_odom);
    odom_.y += ds * std::sin(mid_odom);
    odom_.theta = wrap_pi(turn_done ? turn_target_ : odom_.theta + dth);
    truth_ = Pose{to.x, to.y, wrap_pi(truth_.theta + dth_true)};

    if (turn_done) {
        rmode_ = Mode::Idle;
        turn_left_ = w_ = 0.0;
    } else if (rmode_ == Mode::Position) {
        turn_left_ -= dth;
    }
    if (move_done) {
        tmode_ = Mode::Idle;
        move_left_ = v_ = 0.0;
    } else if (tmode_ == Mode::Position) {
        move_left_ -= ds;
    }
}

}  // namespace hlsim
