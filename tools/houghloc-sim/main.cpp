// main.cpp - houghloc-sim: a simulated ARCOS robot on TCP for houghlocd (README, section
// "Simulated robot"; docs/manual/arcos.md for the protocol subset).
//
// One thread, one poll loop: the listening socket, the client, a signalfd for SIGINT and
// SIGTERM, and the SIP clock. The live clock: robot time runs --speed times wall time, a
// SIP is due every 100 / K ms of wall time from the start. When the loop falls behind, no
// period is skipped: the SIPs go out back to back, each still 100 ms of robot time (robot
// time is what the SIPs say, and the daemon counts them), the sockets still served
// between them. The lockstep clock (--lockstep): a period runs only when the client has
// granted one (connection.hpp), at most one every 100 / K ms of wall time; a wait for a
// grant starts that pace over, so no burst follows it. Each SIP sent is matched by one
// GROUND_TRUTH message with the true pose.
#include <lcm/lcm.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>
#include <vector>

#include "houghloc/bus.h"
#include "houghloc/fixed.h"
#include "houghloc/slam.h"
#include "options.hpp"

using namespace hlsim;

namespace {

int64_t mono_ns()
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

struct Truth {
    lcm_t *lcm = nullptr;
    char channel[HL_BUS_CHANNEL_MAX] = "";
    std::vector<uint8_t> buf = std::vector<uint8_t>(HL_BUS_POSE_BYTES);

    void publish(const SimRobot &robot, uint64_t seq, Log &log)
    {
        if (!lcm)
            return;
        const Pose &p = robot.base().truth();
        hl_bus_pose_t g{};
        g.utime = robot.utime();
        g.scan_seq = static_cast<int32_t>(seq & 0x7FFFFFFF);
        g.pose = hl_pose_t{static_cast<hl_mm_t>(std::lround(p.x)),
                           static_cast<hl_mm_t>(std::lround(p.y)), hl_bam_from_rad(p.theta)};
        g.status = HL_BUS_POSE_ACCEPTED;
        int len = hl_bus_encode_pose(&g, buf.data(), buf.size());
        if (len < 0)
            log.once("truth-encode", "GROUND_TRUTH: the true pose does not encode (out of "
                     "range?): not published");
        else if (lcm_publish(lcm, channel, buf.data(), static_cast<unsigned>(len)) != 0)
            log.once("truth-publish", "GROUND_TRUTH: lcm_publish failed (logged once)");
    }
};

// Blocks SIGINT and SIGTERM and returns a signalfd for them (-1 on failure).
int signal_fd()
{
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    if (sigprocmask(SIG_BLOCK, &set, nullptr) != 0)
        return -1;
    signal(SIGPIPE, SIG_IGN);
    return signalfd(-1, &set, SFD_NONBLOCK | SFD_CLOEXEC);
}

void summary(const Server &server, const Connection &connection, const SimRobot &robot)
{
    const ServerCounts &c = server.counts();
    std::fprintf(stderr,
                 "houghloc-sim: summary: sips_sent=%llu commands=%llu bad_commands=%llu "
                 "client_garbage_bytes=%llu faults=%llu (drop %llu, garbage %llu, corrupt "
                 "%llu, stall %llu, teleport %llu, mute %llu) clients=%llu refused=%llu "
                 "muted_stops=%llu robot_time_s=%.1f collisions=%llu\n",
                 static_cast<unsigned long long>(c.sips),
                 static_cast<unsigned long long>(connection.commands()),
                 static_cast<unsigned long long>(connection.bad_commands()),
                 static_cast<unsigned long long>(connection.garbage_bytes()),
                 static_cast<unsigned long long>(c.faults()),
                 static_cast<unsigned long long>(c.drops),
                 static_cast<unsigned long long>(c.garbage),
                 static_cast<unsigned long long>(c.corrupt),
                 static_cast<unsigned long long>(c.stalls),
                 static_cast<unsigned long long>(c.teleports),
                 static_cast<unsigned long long>(c.mutes),
                 static_cast<unsigned long long>(c.clients),
                 static_cast<unsigned long long>(c.refused),
                 static_cast<unsigned long long>(connection.muted_stops()),
                 static_cast<double>(robot.utime()) / 1e6,
                 static_cast<unsigned long long>(robot.collisions()));
}

// The poll loop; returns when a signal arrives (0) or poll fails (1).
int run(Server &server, SimRobot &robot, Truth &truth, Log &log, int sigfd, double speed,
        bool lockstep)
{
    const int64_t period_ns = std::llround(1e8 / speed);   // 100 ms of robot time
    int64_t next_ns = mono_ns() + (lockstep ? 0 : period_ns);
    for (;;) {
        struct pollfd pfd[3];
        pfd[0] = {sigfd, POLLIN, 0};
        std::size_t n = 1 + server.pollfds(pfd + 1);
        // Live, a period is always due; lockstep, only once granted: until then the
        // loop sleeps until the client or a signal wakes it.
        struct timespec ts {}, *timeout = nullptr;
        if (server.may_step()) {
            int64_t wait = next_ns - mono_ns();
            if (wait < 0)
                wait = 0;
            ts = {static_cast<time_t>(wait / 1000000000), static_cast<long>(wait % 1000000000)};
            timeout = &ts;
        }
        int r = ppoll(pfd, n, timeout, nullptr);
        if (r < 0 && errno != EINTR) {
            log.line("poll: %s", std::strerror(errno));
            return 1;
        }
        if (r > 0 && (pfd[0].revents & POLLIN)) {
            struct signalfd_siginfo si;
            if (read(sigfd, &si, sizeof si) == static_cast<ssize_t>(sizeof si))
                log.line("%s: shutting down", strsignal(static_cast<int>(si.ssi_signo)));
            return 0;
        }
        if (r > 0)
            server.handle(pfd + 1, n - 1);
        const int64_t now = mono_ns();
        if (server.may_step() && now >= next_ns) {
            uint64_t seq = 0;
            // muted, the robot still moves and the lab still sees it: GROUND_TRUTH goes
            // on (its scan_seq the next SIP's)
            if (server.step(&seq) || server.period_muted())
                truth.publish(robot, seq, log);
            // Live: never skipped, behind, the next is due at once. Lockstep: a period
            // a whole period late waited for its grant; the pace starts over from now.
            if (lockstep && now - next_ns >= period_ns)
                next_ns = now;
            next_ns += period_ns;
        }
    }
}

}  // namespace

int main(int argc, char **argv)
{
    SimOptions o;
    std::string err;
    switch (parse_options(argc, argv, &o, &err)) {
    case ParseResult::Help:
        print_usage(stdout);
        return 0;
    case ParseResult::Version:
        std::printf("%s\n", version_line().c_str());
        return 0;
    case ParseResult::Error:
        std::fprintf(stderr, "houghloc-sim: %s\n", err.c_str());
        return 2;
    case ParseResult::Run:
        break;
    }
    World world;
    if (!World::load_or_lab(o.world, &world, &err)) {
        std::fprintf(stderr, "houghloc-sim: --world: %s\n", err.c_str());
        return 2;
    }
    Pose start;
    if (!start_pose(world, o, &start, &err) ||
        (o.teleport.has_to && !check_free_pose(world, o.teleport.to, "--teleport-to", &err))) {
        std::fprintf(stderr, "houghloc-sim: %s\n", err.c_str());
        return 2;
    }
    SimConfig cfg;
    sim_profile(o.profile, &cfg.profile);
    cfg.sonar.model = o.cone ? SonarParams::Model::Cone : SonarParams::Model::Physical;
    cfg.seed = o.seed;
    cfg.watchdog_us = std::llround(o.watchdog_s * 1e6);
    cfg.teleport = o.teleport;

    Log log;
    SimRobot robot(world, cfg, start, log);
    Connection connection(robot, log, o.lockstep);
    Server server(robot, connection, log, o.faults, o.seed);
    if (!server.listen(o.bind, o.port, &err) ||
        (!o.capture.empty() && !server.capture(o.capture, &err))) {
        std::fprintf(stderr, "houghloc-sim: %s\n", err.c_str());
        return 1;
    }
    Truth truth;
    if (o.truth) {
        hl_bus_channel(o.prefix.c_str(), HL_CHANNEL_GROUND_TRUTH, truth.channel);
        truth.lcm = lcm_create(o.lcm_url.empty() ? nullptr : o.lcm_url.c_str());
        if (!truth.lcm) {
            std::fprintf(stderr, "houghloc-sim: --lcm-url: cannot open LCM '%s'\n",
                         o.lcm_url.empty() ? "(default)" : o.lcm_url.c_str());
            return 1;
        }
    }
    int sigfd = signal_fd();
    if (sigfd < 0) {
        std::fprintf(stderr, "houghloc-sim: signalfd: %s\n", std::strerror(errno));
        return 1;
    }
    log.set_clock(robot.clock());
    log.line("listening on %s:%u (profile %s, speed %g, %s sonar, start (%.3f, %.3f) m "
             "%.1f deg, %s)", o.bind.c_str(), server.port(), o.profile.c_str(), o.speed,
             o.cone ? "cone" : "physical", start.x / 1000.0, start.y / 1000.0,
             rad2deg(start.theta), o.truth ? truth.channel : "no GROUND_TRUTH");
    if (o.lockstep)
        log.line("clock lockstep: one SIP period per credit from the client (OPEN, then "
                 "each STEP), at most %g times real time; no client, no robot time", o.speed);
    else
        log.line("clock live: robot time runs %g times real time", o.speed);
    int rc = run(server, robot, truth, log, sigfd, o.speed, o.lockstep);
    server.shutdown();
    summary(server, connection, robot);
    close(sigfd);
    if (truth.lcm)
        lcm_destroy(truth.lcm);
    return rc;
}
