// motion.hpp - the simulated robot's differential base: velocity and position commands
// with acceleration limits, exact odometry, a noisy true pose, and walls it cannot pass.
//
// The base keeps two poses, as tools/sim's Robot does: the odometry pose, which
// integrates the wheels' motion exactly and is what the SIPs report, and the true pose in
// the world, which the sonar and GROUND_TRUTH use. Each motion command draws one set of
// errors (a scale error forward, a lateral slip, a heading drift per metre, a turn scale
// error) with the sigmas of tools/sim's RobotParams, applied proportionally while the
// command runs, so a leg's true error has the distribution tools/sim's Robot gives it.
//
// Position commands (MOVE, HEAD, DHEAD) brake on the profile v = sqrt(2 * decel * left)
// and land on their target in odometry exactly: the last step is cut to what is left.
#ifndef HLSIMROBOT_MOTION_HPP
#define HLSIMROBOT_MOTION_HPP

#include "geom.hpp"
#include "rng.hpp"
#include "robot.hpp"
#include "world.hpp"

namespace hlsim {

/** The motion limits a client sets with SETV, SETA, SETRV and SETRA; Pioneer-like
 *  defaults. */
struct MotionLimits {
    double vmax = 400.0;            // SETV, mm/s
    double accel = 300.0;           // SETA +, mm/s^2
    double decel = 300.0;           // SETA -, mm/s^2
    double rvmax = deg2rad(60.0);   // SETRV, rad/s
    double raccel = deg2rad(100.0); // SETRA +, rad/s^2
    double rdecel = deg2rad(100.0); // SETRA -, rad/s^2
};

class Base {
public:
    /** Radius of the robot's body: its centre keeps this far from every surface. */
    static constexpr double kRadiusMm = 250.0;
    /** A contact ends with a step that leaves the body this far clear of every surface
     *  (a robot pushing a wall creeps the last fraction of a millimetre in steps that are
     *  taken between those refused: still the same contact). */
    static constexpr double kContactReleaseMm = 10.0;

    Base(const World &world, const RobotParams &noise, Rng &rng);

    /** Sets the robot down at @p truth (world frame), odometry at 0, 0, 0, at rest. */
    void place(const Pose &truth);
    /** SETO: odometry to 0, 0, 0; a running turn keeps the angle it has left. */
    void reset_odometry();
    /** The kidnapped robot (fault injection): the true pose jumps to @p truth; the
     *  odometry, the commands and the velocities stay as they were. */
    void teleport(const Pose &truth)
    {
        truth_ = truth;
        in_contact_ = false;
    }

    /* Commands, in the odometry frame. Translation (MOVE, VEL) and rotation (HEAD,
     * DHEAD, RVEL) are independent channels, as in ARCOS; a new command replaces the one
     * on its channel. */
    void move(double mm);            // drive this far along the heading, then stop
    void vel(double mm_s);           // translate at this velocity until told otherwise
    void head(double heading);       // turn to this odometry heading (rad), the short way
    void dhead(double dtheta);       // turn by this many radians
    void rvel(double rad_s);         // rotate at this rate until told otherwise
    void stop();                     // both channels to zero, braking at the decelerations
    void halt();                     // motors off: at rest at once, commands dropped

    /** From now on the wheels do not turn (fault injection): no motion, odometry
     *  frozen, stall flags while a command asks for motion. */
    void set_wheels_stalled(bool stalled) { wheels_stalled_ = stalled; }
    bool wheels_stalled() const { return wheels_stalled_; }

    /** Integrates @p dt seconds (the caller keeps steps short, ~10 ms). */
    void advance(double dt);

    MotionLimits limits;

    const Pose &odom() const { return odom_; }
    const Pose &truth() const { return truth_; }
    double velocity() const { return v_; }           // mm/s
    double rot_velocity() const { return w_; }       // rad/s
    /** Whether a command asks for motion or the base still moves. */
    bool moving() const;
    /** The heading setpoint: a running turn's target, else the heading. */
    double control_heading() const;
    /** Whether a command pushed against a wall or stalled wheels since the last call. */
    bool take_stall();
    /**
     * Collisions so far: contact episodes, each counted at its first refused step (the
     * first since the robot was set down or teleported, or since a step took it
     * kContactReleaseMm clear of every surface); a robot that keeps pushing, stands, or
     * turns in place against the wall is still in the same episode. Stalled wheels
     * (set_wheels_stalled) are no collision.
     */
    uint64_t collisions() const { return collisions_; }

private:
    enum class Mode { Idle, Velocity, Position };

    void draw_errors();
    double translation_wanted() const;
    double rotation_wanted() const;
    bool blocked(Vec2 from, Vec2 to) const;

    const World &world_;
    RobotParams noise_;
    Rng &rng_;
    Pose odom_, truth_;
    double v_ = 0.0, w_ = 0.0;
    Mode tmode_ = Mode::Idle, rmode_ = Mode::Idle;
    double vel_target_ = 0.0, move_left_ = 0.0;    // translation channel
    double rvel_target_ = 0.0, turn_left_ = 0.0;   // rotation channel
    double turn_target_ = 0.0;                     // odometry heading a turn ends at
    // This command's errors (see the top of the file).
    double fwd_err_ = 0.0, lat_err_ = 0.0, drift_rad_per_mm_ = 0.0, turn_err_ = 0.0;
    bool wheels_stalled_ = false;
    bool stalled_ = false;
    bool in_contact_ = false;      // a step was refused, and none has left the surface since
    uint64_t collisions_ = 0;
};

}  // namespace hlsim
#endif
