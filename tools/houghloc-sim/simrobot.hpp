// simrobot.hpp - the simulated ARCOS robot, pure: commands in, robot time advanced in
// SIP periods, SIPs out (no sockets, no clock, no global state).
//
// It is the server side of the ARCOS subset of include/robot/houghloc/arcos.h, less the
// connection (connection.hpp): motion commands drive a Base (motion.hpp), the sonar ring
// fires one transducer per sonar cycle from the true pose into the world (tools/sim's
// sonar_ping), and every 100 ms of robot time it reports a standard SIP with the
// odometry and the readings fired since the previous one. A watchdog stops the robot
// after 2 s of robot time without a client packet (SimConfig::watchdog_us). The
// kidnapped-robot fault (SimConfig::teleport, teleport.hpp) moves the true pose alone.
#ifndef HLSIMROBOT_SIMROBOT_HPP
#define HLSIMROBOT_SIMROBOT_HPP

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "houghloc/arcos.h"
#include "log.hpp"
#include "motion.hpp"
#include "sonar.hpp"
#include "teleport.hpp"

namespace hlsim {

/** A robot profile: its name (the SYNC2 subclass) and its transducers' bearings,
 *  degrees counter-clockwise from forward. Every transducer sits at the robot's centre. */
struct SimProfile {
    std::string name;
    std::vector<double> bearings_deg;
};

/** The profile called @p name ("bonnie" or "pioneer3"); false if there is none. */
bool sim_profile(const std::string &name, SimProfile *out);

struct SimConfig {
    SimProfile profile;
    SonarParams sonar;
    RobotParams noise;   // odo_dist_frac, odo_heading_deg_per_m, odo_turn_frac
    uint64_t seed = 1;
    int64_t watchdog_us = 2000000;   // ARCOS's default watchdog, robot time; 0: none
    TeleportPlan teleport;           // the kidnapped-robot fault (teleport.hpp); default none
};

class SimRobot {
public:
    static constexpr int64_t kSipPeriodUs = 100000;   // one standard SIP per 100 ms
    static constexpr int64_t kSubstepUs = 10000;      // motion integration step
    static constexpr int64_t kSonarCycleUs = 40000;   // default sonar cycle

    /** @p world and @p log must outlive the robot. */
    SimRobot(const World &world, const SimConfig &config, const Pose &start, Log &log);

    /**
     * Carries out one command of the subset that acts on the robot (everything but
     * SYNCn/PULSE/OPEN/CLOSE, which are the connection's). @return false, with one log
     * line per kind, for a command the robot does not take (unsupported, or a motion
     * command while the motors are off); the caller counts those.
     */
    bool command(const hl_arcos_cmd_t &cmd);

    /** A client packet arrived: the watchdog starts over (and is armed). */
    void heard();
    /** The client is gone (CLOSE, disconnect): the robot stops at once, motors and
     *  sonar off, the watchdog disarmed. Pose and odometry are kept. */
    void connection_end();
    /** Fault injection: the wheels stop turning for good. */
    void stall_wheels();

    /** Advances robot time by one SIP period and returns the SIP for its end. */
    hl_arcos_sip_t step();

    int64_t utime() const { return now_us_; }
    const int64_t *clock() const { return &now_us_; }
    const Base &base() const { return base_; }
    bool motors_on() const { return motors_; }
    bool sonar_on() const { return sonar_on_; }
    int64_t sonar_cycle_us() const { return cycle_us_; }
    const SimProfile &profile() const { return config_.profile; }
    uint64_t teleports() const { return teleport_.count(); }
    /** Collisions so far (Base::collisions), each logged once as it happens. */
    uint64_t collisions() const { return base_.collisions(); }
    bool teleport_pending() const { return teleport_.pending(); }

private:
    void set_sonar(int32_t arg);
    void set_polling(const hl_arcos_cmd_t &cmd);
    void rebuild_sequence();
    bool motion_command(const hl_arcos_cmd_t &cmd);
    void fire();
    void advance_to(int64_t t);
    hl_arcos_sip_t make_sip();

    const World &world_;
    SimConfig config_;
    Log &log_;
    Rng rng_;
    Base base_;
    int64_t now_us_ = 0;
    bool motors_ = false;
    // Sonar: the firing order (polling order filtered by the enabled arrays), where it
    // is, and the readings fired since the last SIP (the newest per transducer).
    bool sonar_on_ = false;
    unsigned arrays_ = 0;              // bit k: array k + 1 (transducers 8k .. 8k + 7) on
    std::vector<uint8_t> polling_;     // the POLLING order, transducers from 0
    std::vector<uint8_t> sequence_;
    std::size_t next_in_sequence_ = 0;
    int64_t cycle_us_ = kSonarCycleUs;
    int64_t next_fire_us_ = 0;
    std::vector<hl_arcos_sonar_t> fired_;
    bool stall_reported_ = false;      // this stall is logged
    uint64_t collisions_logged_ = 0;
    Teleporter teleport_;
    // Watchdog.
    bool watchdog_armed_ = false;
    int64_t last_heard_us_ = 0;
};

}  // namespace hlsim
#endif
