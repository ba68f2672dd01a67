// teleport.cpp - the kidnapped-robot fault: schedule, destinations, the jump itself.
#include "teleport.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace hlsim {

namespace {

constexpr uint64_t kTeleportSeedMix = 0x6b69646e61707065ULL;   // "kidnappe"

std::string where(const Pose &p)
{
    char b[96];
    std::snprintf(b, sizeof b, "(%.3f, %.3f) m %.1f deg", p.x / 1000.0, p.y / 1000.0,
                  rad2deg(p.theta));
    return b;
}

}  // namespace

bool check_free_pose(const World &w, const Pose &p, const std::string &opt, std::string *err)
{
    char at[96];
    std::snprintf(at, sizeof at, "(%.3f, %.3f) m", p.x / 1000.0, p.y / 1000.0);
    double c = w.clearance(p.pos());
    if (c < Base::kRadiusMm - 2.0) {
        *err = opt + ": " + at + " is not in free space: " +
               std::to_string(static_cast<long>(c)) + " mm from a surface, the robot's " +
               "radius is 250 mm";
        return false;
    }
    std::string why;
    if (!w.enclosed(p.pos(), &why)) {
        *err = opt + ": " + at + " is not in free space: " + why;
        return false;
    }
    return true;
}

bool random_free_pose(const World &w, const Pose &from, Rng &rng, Pose *out)
{
    Vec2 lo, hi;
    if (!w.bounds(&lo, &hi))
        return false;
    std::string why;
    for (int k = 0; k < kTeleportMaxDraws; k++) {
        Vec2 c{rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y)};
        // The cheap tests first: enclosed() casts 360 rays.
        if ((c - from.pos()).norm() < kTeleportMinJumpMm ||
            w.clearance(c) < kTeleportClearanceMm || !w.enclosed(c, &why))
            continue;
        *out = Pose{c.x, c.y, rng.uniform(-kPi, kPi)};
        return true;
    }
    return false;
}

Teleporter::Teleporter(const TeleportPlan &plan, uint64_t seed)
    : plan_(plan), rng_(seed ^ kTeleportSeedMix)
{
    if (plan.after_s >= 0.0)
        after_us_ = std::llround(plan.after_s * 1e6);
    if (plan.every_s > 0.0)
        every_us_ = next_every_us_ = std::llround(plan.every_s * 1e6);
}

int64_t Teleporter::next_due_us(int64_t now_us) const
{
    int64_t due = std::numeric_limits<int64_t>::max();
    if (!after_done_ && after_us_ > now_us)
        due = after_us_;
    if (every_us_ > 0 && next_every_us_ > now_us && next_every_us_ < due)
        due = next_every_us_;
    return due;
}

void Teleporter::tick(int64_t now_us, const World &w, Base &base, Log &log)
{
    if (!after_done_ && after_us_ >= 0 && now_us >= after_us_) {
        after_done_ = true;
        pending_ = true;
        why_ = "--teleport-after";
    }
    if (every_us_ > 0 && now_us >= next_every_us_) {
        // Periods that pass while a teleport waits for the base fold into that one.
        while (next_every_us_ <= now_us)
            next_every_us_ += every_us_;
        if (!pending_)
            why_ = "--teleport-every";
        pending_ = true;
    }
    if (!pending_)
        return;
    if (base.moving()) {
        if (!wait_logged_)
            log.line("fault: a teleport is due (%s) while the base moves: it waits until "
                     "the base stands still", why_);
        wait_logged_ = true;
        return;
    }
    pending_ = wait_logged_ = false;
    teleport(w, base, log);
}

void Teleporter::teleport(const World &w, Base &base, Log &log)
{
    const Pose from = base.truth();
    Pose to = plan_.to;
    if (!plan_.has_to && !random_free_pose(w, from, rng_, &to)) {
        log.line("fault: teleport (%s) skipped: no pose %.1f m clear of the walls and %.0f m "
                 "away in %d draws", why_, kTeleportClearanceMm / 1000.0,
                 kTeleportMinJumpMm / 1000.0, kTeleportMaxDraws);
        return;
    }
    base.teleport(to);
    count_++;
    log.line("fault: teleported (%s): true pose from %s to %s; odometry unchanged", why_,
             where(from).c_str(), where(to).c_str());
}

}  // namespace hlsim
