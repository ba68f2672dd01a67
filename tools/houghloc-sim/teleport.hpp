// teleport.hpp - the kidnapped-robot fault: the true pose jumps elsewhere while the
// wheels do not turn, so the odometry the SIPs report goes on as if nothing happened and
// only the sonar readings and GROUND_TRUTH show the move.
//
// A teleport falls due at a robot time (--teleport-after, --teleport-every) but is
// carried out only while the base stands still (no command asks for motion, the wheels
// are stopped): a motion in progress is never cut in half, since a real robot is not
// picked up while it drives. Random destinations come from a generator of their own,
// seeded from --seed, so a run is reproducible and the motion and sonar noise stream is
// the one a run without teleports would draw.
#ifndef HLSIMROBOT_TELEPORT_HPP
#define HLSIMROBOT_TELEPORT_HPP

#include <cstdint>
#include <string>

#include "log.hpp"
#include "motion.hpp"
#include "rng.hpp"
#include "world.hpp"

namespace hlsim {

/** When and where to teleport. */
struct TeleportPlan {
    double after_s = -1.0;   // --teleport-after: once, at this robot time; < 0: never
    double every_s = -1.0;   // --teleport-every: at every multiple of this; <= 0: never
    bool has_to = false;     // --teleport-to given: always there; else a random free pose
    Pose to;                 // world frame, mm and radians
    bool enabled() const { return after_s >= 0.0 || every_s > 0.0; }
};

/** A random destination keeps at least this far from every surface... */
constexpr double kTeleportClearanceMm = 600.0;
/** ...and lands at least this far from where the robot was. */
constexpr double kTeleportMinJumpMm = 2000.0;
/** Random candidates tried before a teleport is given up (a world with no such place). */
constexpr int kTeleportMaxDraws = 20000;

/**
 * Whether the robot may stand at @p p (--start, --teleport-to): its centre at least its
 * radius from every surface (less 2 mm, for a pose read back from GROUND_TRUTH's whole
 * millimetres) and the world closed around it. @return false with one line in @p err,
 * starting with @p opt.
 */
bool check_free_pose(const World &w, const Pose &p, const std::string &opt, std::string *err);

/**
 * A random pose inside @p w's bounds, at least kTeleportClearanceMm from every surface,
 * closed in, at least kTeleportMinJumpMm from @p from, heading uniform. @return false
 * if kTeleportMaxDraws candidates gave none.
 */
bool random_free_pose(const World &w, const Pose &from, Rng &rng, Pose *out);

/** Runs a TeleportPlan against robot time. */
class Teleporter {
public:
    Teleporter(const TeleportPlan &plan, uint64_t seed);

    /** The next robot time (us) after @p now_us at which a teleport falls due, INT64_MAX
     *  if none: the caller ends its motion step there. */
    int64_t next_due_us(int64_t now_us) const;

    /** At robot time @p now_us: takes the teleports due and, while the base stands
     *  still, carries a pending one out (its true pose only), logging it. */
    void tick(int64_t now_us, const World &w, Base &base, Log &log);

    uint64_t count() const { return count_; }        // teleports carried out
    bool pending() const { return pending_; }        // one waits for the base to stop

private:
    void teleport(const World &w, Base &base, Log &log);

    TeleportPlan plan_;
    Rng rng_;
    int64_t after_us_ = -1, every_us_ = 0;
    bool after_done_ = false;
    int64_t next_every_us_ = 0;
    bool pending_ = false, wait_logged_ = false;
    const char *why_ = "";                           // the option that asked for it
    uint64_t count_ = 0;
};

}  // namespace hlsim
#endif
