// robot.hpp - the simulated robot: a ring of transducers, the rotating sounding, and
// noisy dead reckoning (paper, sections 3 and 6).
//
// The robot keeps two poses: the true one, which the sonar physics uses, and the
// odometry one, which is what the robot believes and reports. Motion commands are given
// in the odometry frame and executed exactly there; the true motion differs by noise
// proportional to the distance and the turn, so the two drift apart as on a real base.
#ifndef HLSIM_ROBOT_HPP
#define HLSIM_ROBOT_HPP

#include <cstdint>
#include <vector>

#include "rng.hpp"
#include "sonar.hpp"
#include "world.hpp"

namespace hlsim {

struct RobotParams {
    int transducers = 16;                // evenly spaced ring, transducer 0 faces forward
    double transducer_spacing_deg = 22.5;
    int rotation_steps = 8;              // body positions per sounding
    double rotation_step_deg = 2.8125;   // 22.5 / 8: the ring becomes 128 readings
    double rotation_sigma_deg = 0.3;     // error of each body rotation step
    double odo_dist_frac = 0.05;         // true forward and lateral error sigma per mm driven
    double odo_heading_deg_per_m = 2.0;  // true heading error sigma per metre driven
    double odo_turn_frac = 0.02;         // true heading error sigma per radian turned
    double speed_mm_s = 300.0;           // driving speed
    double turn_rate_deg_s = 45.0;       // turning speed
    double step_time_s = 0.25;           // one body rotation step plus 16 pings
    double odometry_period_s = 0.1;      // ODOMETRY sample interval while moving
};

/** One reading of a sounding. */
struct RingReading {
    int transducer = 0;       // 0..transducers-1
    int step = 0;             // 0..rotation_steps-1
    uint16_t bearing_bam = 0; // nominal bearing in the robot frame, as recorded
    double true_axis = 0.0;   // world direction the transducer really faced (radians)
    SonarReading sonar;
};

/** A complete sounding: readings ordered by nominal bearing. */
struct Sounding {
    int64_t utime = 0;        // when it completed
    Pose odom;                // odometry pose (the bearings are relative to its heading)
    Pose truth;               // true pose
    std::vector<RingReading> readings;
};

/** An odometry report, as the base sends it while moving and once when it stops; with
 *  the true pose at that instant, for the sensors that sample while the robot moves
 *  (the continuous sonar ring, the laser). */
struct OdoSample {
    int64_t utime = 0;
    Pose odom;
    double velocity_mm_s = 0.0;
    bool stopped = true;
    Pose truth;
};

class Robot {
public:
    Robot(const World &world, const SonarParams &sonar, const RobotParams &params, Rng &rng,
          int64_t start_utime);

    /** Sets the robot down: true pose and what its odometry says (no motion noise). */
    void place(const Pose &truth, const Pose &odom);
    /** Turns in place by @p dtheta radians (odometry exact, truth noisy). */
    void turn(double dtheta);
    /** Drives straight ahead by @p dist_mm (odometry exact, truth noisy). */
    void drive(double dist_mm);
    /** Turns to face @p target (odometry frame) and drives there. */
    void go_to(Vec2 target);
    /**
     * Turns and drives by the amounts that would take the true pose to the world point
     * @p target, as a robot that localizes before each move does (the data sets assume
     * a perfect localizer steering). The truth still errs by this move's noise; the
     * odometry integrates the commands, so it drifts from the truth move by move.
     */
    void steer_to(Vec2 target);
    /** Moves by (dx forward, dy left) in the robot frame: go_to the odometry point. */
    void move(double dx, double dy);
    /** Turns to the odometry heading @p heading (radians), the short way. */
    void turn_to(double heading);
    /** Lets simulated time pass without motion. */
    void wait(double seconds);

    /** Takes one sounding: every transducer at every body rotation step, then returns. */
    Sounding sound();

    /** The odometry reports since the last call. */
    std::vector<OdoSample> take_odometry();

    const Pose &truth() const { return truth_; }
    const Pose &odom() const { return odom_; }
    int64_t utime() const { return utime_; }
    const RobotParams &params() const { return params_; }

private:
    void report_motion(const Pose &from, const Pose &to, const Pose &truth_from,
                       double seconds, double speed);

    const World &world_;
    SonarParams sonar_;
    RobotParams params_;
    Rng &rng_;
    int64_t utime_;
    Pose truth_, odom_;
    std::vector<OdoSample> odo_;
};

}  // namespace hlsim
#endif
