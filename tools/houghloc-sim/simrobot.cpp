// simrobot.cpp - the simulated ARCOS robot: commands, sonar firing, watchdog, SIPs.
#include "simrobot.hpp"

#include <algorithm>
#include <cmath>

namespace hlsim {

namespace {

// Half the distance between the wheels: vel_left and vel_right are v -/+ w times this.
// (ARIA's Pioneer parameter files recover w from them with DiffConvFactor 0.0056.)
constexpr double kHalfTrackMm = 1.0 / 0.0056;
constexpr uint8_t kBatteryDeciVolts = 130;
constexpr int kUnitsPerTurn = 4096;   // HL_ARCOS_CONV_PIONEER
constexpr std::size_t kTransducersPerArray = 8;

int16_t angle_units(double rad)
{
    long long u = std::llround(rad * kUnitsPerTurn / (2.0 * kPi));
    u = ((u + kUnitsPerTurn / 2) % kUnitsPerTurn + kUnitsPerTurn) % kUnitsPerTurn -
        kUnitsPerTurn / 2;
    return static_cast<int16_t>(u);   // [-2048, 2048)
}

int16_t clamp16(double v)
{
    return static_cast<int16_t>(std::clamp(std::lround(v), -32767L, 32767L));
}

// x and y go out as the low 15 bits of the position in mm (arcos.h).
uint16_t wrap15(double mm)
{
    return static_cast<uint16_t>(std::llround(mm) & 0x7FFF);
}

}  // namespace

bool sim_profile(const std::string &name, SimProfile *out)
{
    if (name == "bonnie") {
        // The paper's robot: 16 transducers 22.5 degrees apart, 0 facing forward.
        out->name = name;
        out->bearings_deg.clear();
        for (int k = 0; k < 16; k++)
            out->bearings_deg.push_back(22.5 * k);
        return true;
    }
    if (name == "pioneer3") {
        // A Pioneer 3-DX's front and rear arrays, numbered as its SIPs number them.
        out->name = name;
        out->bearings_deg = {90, 50, 30, 10, -10, -30, -50, -90,
                             -90, -130, -150, -170, 170, 150, 130, 90};
        return true;
    }
    return false;
}

SimRobot::SimRobot(const World &world, const SimConfig &config, const Pose &start, Log &log)
    : world_(world), config_(config), log_(log), rng_(config.seed),
      base_(world, config.noise, rng_), teleport_(config.teleport, config.seed)
{
    base_.place(start);
    for (std::size_t t = 0; t < config_.profile.bearings_deg.size(); t++)
        polling_.push_back(static_cast<uint8_t>(t));
    rebuild_sequence();
}

void SimRobot::heard()
{
    watchdog_armed_ = true;
    last_heard_us_ = now_us_;
}

void SimRobot::connection_end()
{
    base_.halt();
    motors_ = false;
    arrays_ = 0;
    sonar_on_ = false;
    fired_.clear();
    watchdog_armed_ = false;
}

void SimRobot::stall_wheels()
{
    base_.set_wheels_stalled(true);
}

void SimRobot::rebuild_sequence()
{
    sequence_.clear();
    for (uint8_t t : polling_)
        if (arrays_ & (1u << (t / kTransducersPerArray)))
            sequence_.push_back(t);
    next_in_sequence_ = 0;
    sonar_on_ = !sequence_.empty();
}

// SONAR: bit 0 on or off; bits 1-3 the array (1..4), 0 for all of them.
void SimRobot::set_sonar(int32_t arg)
{
    bool was_on = sonar_on_;
    unsigned array = static_cast<unsigned>(arg >> 1) & 7u;
    unsigned mask = array == 0 ? 0xFu : 1u << (array - 1);
    arrays_ = (arg & 1) ? (arrays_ | mask) : (arrays_ & ~mask);
    rebuild_sequence();
    if (sonar_on_ && !was_on)
        next_fire_us_ = now_us_;   // the first transducer fires at once
    log_.line("sonar %s (SONAR %d)", sonar_on_ ? "on" : "off", static_cast<int>(arg));
}

// POLLING: the firing order, transducers numbered from 1; an empty string stops the sonar.
void SimRobot::set_polling(const hl_arcos_cmd_t &cmd)
{
    polling_.clear();
    std::size_t n = config_.profile.bearings_deg.size();
    for (std::size_t i = 0; i < cmd.str_len; i++) {
        std::size_t t = cmd.str[i] - 1u;
        if (t < n)
            polling_.push_back(static_cast<uint8_t>(t));
        else
            log_.once("polling-range", "POLLING names transducer %zu; the profile has %zu "
                      "(ignored)", t + 1, n);
    }
    rebuild_sequence();
}

bool SimRobot::motion_command(const hl_arcos_cmd_t &cmd)
{
    if (!motors_ && cmd.number != HL_ARCOS_STOP) {
        log_.once("motors-off", "a motion command while the motors are off: ignored "
                  "(send ENABLE 1)");
        return true;
    }
    const double a = cmd.arg;
    switch (cmd.number) {
    case HL_ARCOS_MOVE: base_.move(a); break;
    case HL_ARCOS_VEL: base_.vel(a); break;
    case HL_ARCOS_HEAD: base_.head(deg2rad(a)); break;
    case HL_ARCOS_DHEAD: base_.dhead(deg2rad(a)); break;
    case HL_ARCOS_RVEL: base_.rvel(deg2rad(a)); break;
    default: base_.stop(); break;
    }
    return true;
}

bool SimRobot::command(const hl_arcos_cmd_t &cmd)
{
    MotionLimits &lim = base_.limits;
    const int32_t a = cmd.arg;
    switch (cmd.number) {
    case HL_ARCOS_ENABLE:
        motors_ = a == 1;
        if (!motors_)
            base_.halt();
        log_.line("motors %s", motors_ ? "enabled" : "disabled");
        return true;
    case HL_ARCOS_SONAR:
        set_sonar(a);
        return true;
    case HL_ARCOS_POLLING:
        set_polling(cmd);
        return true;
    case HL_ARCOS_SONARCYCLE:
        cycle_us_ = static_cast<int64_t>(a) * 1000;
        next_fire_us_ = now_us_ + cycle_us_;
        return true;
    case HL_ARCOS_SETO:
        base_.reset_odometry();
        return true;
    case HL_ARCOS_SETV: lim.vmax = a; return true;
    case HL_ARCOS_SETRV: lim.rvmax = deg2rad(a); return true;
    case HL_ARCOS_SETA:
    case HL_ARCOS_SETRA: {
        // Positive sets the acceleration, negative the deceleration; 0 changes nothing.
        bool rot = cmd.number == HL_ARCOS_SETRA;
        double mag = rot ? deg2rad(std::abs(a)) : std::abs(a);
        if (a > 0)
            (rot ? lim.raccel : lim.accel) = mag;
        else if (a < 0)
            (rot ? lim.rdecel : lim.decel) = mag;
        else
            log_.once(rot ? "setra0" : "seta0", "%s 0 changes nothing", rot ? "SETRA" : "SETA");
        return true;
    }
    case HL_ARCOS_MOVE:
    case HL_ARCOS_VEL:
    case HL_ARCOS_HEAD:
    case HL_ARCOS_DHEAD:
    case HL_ARCOS_RVEL:
    case HL_ARCOS_STOP:
        return motion_command(cmd);
    default:
        log_.once("robot-cmd-" + std::to_string(cmd.number),
                  "command %u is not one the robot takes: ignored", cmd.number);
        return false;
    }
}

// Fires the next transducer of the sequence from the true pose along its true axis.
void SimRobot::fire()
{
    if (sequence_.empty())
        return;
    uint8_t t = sequence_[next_in_sequence_ % sequence_.size()];
    next_in_sequence_++;
    const Pose &p = base_.truth();
    double axis = wrap_pi(p.theta + deg2rad(config_.profile.bearings_deg[t]));
    SonarReading r = sonar_ping(world_, config_.sonar, p.pos(), axis, rng_);
    for (hl_arcos_sonar_t &s : fired_)
        if (s.transducer == t) {
            s.range = r.raw;   // only the newest reading of a transducer goes out
            return;
        }
    fired_.push_back(hl_arcos_sonar_t{t, r.raw});
}

void SimRobot::advance_to(int64_t t)
{
    for (;;) {
        // A teleport due now (or waiting for the base to stop) goes first, so a sonar
        // reading fired at the same moment sees the new pose.
        teleport_.tick(now_us_, world_, base_, log_);
        if (sonar_on_ && next_fire_us_ <= now_us_) {
            fire();
            next_fire_us_ += cycle_us_;
            continue;
        }
        if (now_us_ >= t)
            break;
        int64_t next = std::min(t, now_us_ + kSubstepUs);
        if (sonar_on_)
            next = std::min(next, next_fire_us_);
        next = std::min(next, teleport_.next_due_us(now_us_));
        base_.advance(static_cast<double>(next - now_us_) * 1e-6);
        now_us_ = next;
        if (base_.collisions() != collisions_logged_) {
            collisions_logged_ = base_.collisions();
            const Pose &p = base_.truth();
            log_.line("collision at (%.3f, %.3f) m, heading %.1f deg", p.x / 1000.0,
                      p.y / 1000.0, rad2deg(p.theta));
        }
    }
}

hl_arcos_sip_t SimRobot::step()
{
    if (watchdog_armed_ && config_.watchdog_us > 0 &&
        now_us_ - last_heard_us_ >= config_.watchdog_us) {
        watchdog_armed_ = false;
        log_.line("watchdog: no client packet for %.1f s of robot time: the robot stops",
                  static_cast<double>(now_us_ - last_heard_us_) / 1e6);
        base_.stop();
    }
    advance_to(now_us_ + kSipPeriodUs);
    return make_sip();
}

hl_arcos_sip_t SimRobot::make_sip()
{
    hl_arcos_sip_t s{};
    const Pose &o = base_.odom();
    s.type = base_.moving() ? HL_ARCOS_SIP_MOVING : HL_ARCOS_SIP_STOPPED;
    s.x = wrap15(o.x);
    s.y = wrap15(o.y);
    s.th = angle_units(o.theta);
    double v = base_.velocity(), w = base_.rot_velocity();
    s.vel_left = clamp16(v - w * kHalfTrackMm);
    s.vel_right = clamp16(v + w * kHalfTrackMm);
    s.battery = kBatteryDeciVolts;
    bool stalled = base_.take_stall();
    if (stalled && !stall_reported_)
        log_.line("stall: %s at true (%.0f, %.0f) mm; stall flags set while it pushes",
                  base_.wheels_stalled() ? "the wheels do not turn"
                                         : "a motion command pushes the robot against a wall",
                  base_.truth().x, base_.truth().y);
    stall_reported_ = stalled;   // once per stall
    s.stall_bumpers = stalled ? (HL_ARCOS_STALL_LEFT | HL_ARCOS_STALL_RIGHT) : 0;
    s.control = angle_units(base_.control_heading());
    std::size_t arrays = (config_.profile.bearings_deg.size() + kTransducersPerArray - 1) /
                         kTransducersPerArray;
    unsigned present = (1u << arrays) - 1u;
    s.flags = static_cast<uint16_t>((motors_ ? HL_ARCOS_FLAG_MOTORS : 0u) |
                                    (((arrays_ & present) << 1) & HL_ARCOS_FLAG_SONAR));
    std::size_t n = std::min<std::size_t>(fired_.size(), HL_ARCOS_SONAR_MAX);
    for (std::size_t i = 0; i < n; i++)
        s.sonar[i] = fired_[i];
    s.sonar_count = static_cast<uint8_t>(n);
    fired_.clear();
    return s;
}

}  // namespace hlsim
