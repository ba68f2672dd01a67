// options.cpp - houghloc-sim's command line.
#include "options.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "houghloc/bus.h"
#include "houghloc/version.h"
#include "simrobot.hpp"
#include "tour.hpp"
#include "world.hpp"

namespace hlsim {

namespace {

constexpr double kMaxSeconds = 1e7;   // fault times: about four months of robot time
constexpr double kMaxSpeedLive = 100.0;       // --speed without --lockstep
constexpr double kMaxSpeedLockstep = 1000.0;  // --speed with it: a cap, not a promise

}  // namespace

void print_usage(FILE *f)
{
    std::fprintf(f,
        "usage: houghloc-sim [options]\n"
        "A simulated Pioneer-style robot for houghlocd: the server side of the ARCOS\n"
        "subset (docs/manual/arcos.md) over TCP, one client at a time. Motion commands move a\n"
        "noisy true pose in the world; SIPs (one per 100 ms of robot time) report the\n"
        "drifting odometry and sonar readings; the true pose goes out on LCM.\n"
        "  --port N            TCP port, 0..65535 (default 8101; 0: any free port, logged)\n"
        "  --bind ADDR         IPv4 address to listen on (default 127.0.0.1)\n"
        "  --speed K           robot time runs K times wall time, 0.1..100 (default 1);\n"
        "                      with --lockstep at most K times, 0.1..1000\n"
        "  --lockstep          the lockstep clock: robot time advances one SIP period\n"
        "                      (100 ms) per credit from the client, OPEN's and then one\n"
        "                      per STEP (command 250), so a run does not depend on how\n"
        "                      fast the machine or the client is; none without a client\n"
        "  --seed N            motion and sonar noise seed (default 1)\n"
        "  --world FILE        world file (default: the built-in lab)\n"
        "  --profile P         bonnie (16 transducers 22.5 deg apart, default) or pioneer3\n"
        "  --sonar-model M     physical (default) or cone, as hl-sim-logs\n"
        "  --start X,Y,DEG     true start pose, metres and degrees (default: the world's\n"
        "                      start line, else its tour start, heading 0)\n"
        "  --lcm-url URL       LCM network for GROUND_TRUTH (default: liblcm's,\n"
        "                      $LCM_DEFAULT_URL)\n"
        "  --prefix P          channel prefix: P + GROUND_TRUTH (default none)\n"
        "  --no-truth          publish nothing on LCM\n"
        "  --watchdog S        the robot stops after S s of robot time without a client\n"
        "                      packet, 0..60; 0: never (default 2, as ARCOS)\n"
        "  --capture FILE      write every byte sent to the first client to FILE, as sent\n"
        "                      (houghlocd replays it with robot.link = file:FILE)\n"
        "Fault injection (each logged when it happens and counted in the summary):\n"
        "  --drop-after S      close the client's connection at S s of robot time, once\n"
        "  --drop-every S      close each client's connection S s of robot time after it\n"
        "                      connected, 0.1..1e7 (a drop every S s while one reconnects)\n"
        "  --garbage-every N   every Nth SIP is preceded by 1..64 random bytes\n"
        "  --corrupt-every N   every Nth SIP has a wrong checksum\n"
        "  --stall-after S     from S s of robot time on the wheels do not turn\n"
        "  --mute-after S      from S s of robot time on no SIP goes out, to this client\n"
        "                      or the next, while commands are still read and obeyed (a\n"
        "                      one-way link loss); STOPs sent meanwhile are logged and\n"
        "                      counted (muted_stops in the summary)\n"
        "  --teleport-after S  kidnapped robot: at S s of robot time, once, 0..1e7, the\n"
        "                      true pose jumps; the wheels do not turn, so the odometry\n"
        "                      does not (due while the base moves, it waits until the\n"
        "                      base stands still)\n"
        "  --teleport-every S  the same every S s of robot time, 0.1..1e7\n"
        "  --teleport-to X,Y,DEG  where to, metres and degrees, checked as --start\n"
        "                      (default: a random pose 0.6 m clear of the walls, 2 m or\n"
        "                      more away, any heading, drawn from --seed)\n"
        "  --help              this text\n"
        "  --version           the version\n"
        "Log lines go to stderr; SIGINT or SIGTERM ends it with a summary line, exit 0.\n"
        "Exit status: 0 done, 1 runtime failure (port in use, LCM), 2 bad option.\n");
}

std::string version_line()
{
    return std::string("houghloc-sim ") + HL_VERSION;
}

bool parse_number(const char *s, double *out)
{
    if (!s || !*s)
        return false;
    for (const char *p = s; *p; p++)
        if (!std::strchr("0123456789+-.eE", *p))
            return false;   // no spaces, hex, inf or nan
    char *end = nullptr;
    errno = 0;
    double v = std::strtod(s, &end);
    if (*end != '\0' || errno == ERANGE || !std::isfinite(v))
        return false;
    *out = v;
    return true;
}

bool parse_count(const char *s, uint64_t max, uint64_t *out)
{
    if (!s || *s < '0' || *s > '9')
        return false;
    uint64_t v = 0;
    for (const char *p = s; *p; p++) {
        if (*p < '0' || *p > '9')
            return false;
        uint64_t d = static_cast<uint64_t>(*p - '0');
        if (v > (max - d) / 10)
            return false;
        v = v * 10 + d;
    }
    *out = v;
    return true;
}

namespace {

// "X,Y,DEG" in metres and degrees (--start, --teleport-to).
bool parse_pose(const char *s, double v[3])
{
    std::string text = s;
    std::size_t pos = 0;
    for (int k = 0; k < 3; k++) {
        std::size_t comma = k < 2 ? text.find(',', pos) : text.size();
        if (comma == std::string::npos)
            return false;
        if (!parse_number(text.substr(pos, comma - pos).c_str(), &v[k]))
            return false;
        pos = comma + 1;
    }
    const double lim_m = kWorldCoordMax / 1000.0;
    return std::fabs(v[0]) <= lim_m && std::fabs(v[1]) <= lim_m && std::fabs(v[2]) <= 360.0;
}

bool bad(std::string *err, const std::string &opt, const char *want, const char *got)
{
    *err = opt + " wants " + want + ", got '" + got + "'";
    return false;
}

// One option with its value; false with *err set if the value is bad.
bool take(const std::string &a, const char *v, SimOptions *o, std::string *err)
{
    double d = 0.0;
    uint64_t n = 0;
    if (a == "--port") {
        if (!parse_count(v, 65535, &n))
            return bad(err, a, "a port number 0..65535", v);
        o->port = static_cast<int>(n);
    } else if (a == "--bind") {
        struct in_addr ia;
        if (inet_pton(AF_INET, v, &ia) != 1)
            return bad(err, a, "an IPv4 address such as 127.0.0.1", v);
        o->bind = v;
    } else if (a == "--speed") {
        if (!parse_number(v, &d) || d < 0.1 || d > kMaxSpeedLockstep)
            return bad(err, a, "a number from 0.1 to 100 (to 1000 with --lockstep)", v);
        o->speed = d;   // above 100 only with --lockstep: parse_options checks it at the end
    } else if (a == "--seed") {
        if (!parse_count(v, UINT64_MAX, &n))
            return bad(err, a, "a non-negative integer", v);
        o->seed = n;
    } else if (a == "--world") {
        if (!*v)
            return bad(err, a, "a file name", v);
        o->world = v;
    } else if (a == "--profile") {
        SimProfile p;
        if (!sim_profile(v, &p))
            return bad(err, a, "bonnie or pioneer3", v);
        o->profile = v;
    } else if (a == "--sonar-model") {
        if (std::strcmp(v, "physical") != 0 && std::strcmp(v, "cone") != 0)
            return bad(err, a, "physical or cone", v);
        o->cone = std::strcmp(v, "cone") == 0;
    } else if (a == "--start" || a == "--teleport-to") {
        double p[3];
        if (!parse_pose(v, p))
            return bad(err, a, "X,Y,DEG (metres, metres, degrees within +-360)", v);
        if (a == "--start") {
            o->has_start = true;
            o->start_x_m = p[0];
            o->start_y_m = p[1];
            o->start_deg = p[2];
        } else {
            o->teleport.has_to = true;
            o->teleport.to = Pose{p[0] * 1000.0, p[1] * 1000.0, wrap_pi(deg2rad(p[2]))};
        }
    } else if (a == "--lcm-url") {
        if (!*v)
            return bad(err, a, "an LCM URL", v);
        o->lcm_url = v;
    } else if (a == "--capture") {
        if (!*v)
            return bad(err, a, "a file name", v);
        o->capture = v;
    } else if (a == "--prefix") {
        char ch[HL_BUS_CHANNEL_MAX];
        if (!hl_bus_channel(v, HL_CHANNEL_GROUND_TRUTH, ch))
            return bad(err, a, "up to 32 of A-Z a-z 0-9 _ - . /", v);
        o->prefix = v;
    } else if (a == "--watchdog") {
        if (!parse_number(v, &d) || d < 0.0 || d > 60.0)
            return bad(err, a, "seconds of robot time, 0..60", v);
        o->watchdog_s = d;
    } else if (a == "--drop-after" || a == "--stall-after" || a == "--teleport-after" ||
               a == "--mute-after") {
        if (!parse_number(v, &d) || d < 0.0 || d > kMaxSeconds)
            return bad(err, a, "seconds of robot time, 0..1e7", v);
        (a == "--drop-after"    ? o->faults.drop_after_s
         : a == "--stall-after" ? o->faults.stall_after_s
         : a == "--mute-after"  ? o->faults.mute_after_s
                                : o->teleport.after_s) = d;
    } else if (a == "--drop-every" || a == "--teleport-every") {
        if (!parse_number(v, &d) || d < 0.1 || d > kMaxSeconds)
            return bad(err, a, "seconds of robot time, 0.1..1e7", v);
        (a == "--drop-every" ? o->faults.drop_every_s : o->teleport.every_s) = d;
    } else if (a == "--garbage-every" || a == "--corrupt-every") {
        if (!parse_count(v, 1000000000, &n) || n < 1)
            return bad(err, a, "a SIP count 1..1000000000", v);
        (a == "--garbage-every" ? o->faults.garbage_every : o->faults.corrupt_every) = n;
    } else {
        *err = "unknown option '" + a + "' (--help)";   // parse_options lists them all
        return false;
    }
    return true;
}

}  // namespace

ParseResult parse_options(int argc, char **argv, SimOptions *o, std::string *err)
{
    for (int i = 1; i < argc; i++) {
        std::string a = argv[i];
        if (a == "--help" || a == "-h")
            return ParseResult::Help;
        if (a == "--version")
            return ParseResult::Version;
        if (a == "--no-truth") {
            o->truth = false;
            continue;
        }
        if (a == "--lockstep") {
            o->lockstep = true;
            continue;
        }
        static const char *const with_value[] = {
            "--port", "--bind", "--speed", "--seed", "--world", "--profile",
            "--sonar-model", "--start", "--lcm-url", "--prefix", "--drop-after",
            "--drop-every", "--stall-after", "--garbage-every", "--corrupt-every",
            "--watchdog", "--teleport-after", "--teleport-every", "--teleport-to",
            "--capture", "--mute-after"};
        bool known = false;
        for (const char *name : with_value)
            known = known || a == name;
        if (!known) {
            *err = "unknown option '" + a + "' (--help)";
            return ParseResult::Error;
        }
        if (i + 1 >= argc) {
            *err = a + " needs a value (--help)";
            return ParseResult::Error;
        }
        if (!take(a, argv[++i], o, err))
            return ParseResult::Error;
    }
    if (!o->lockstep && o->speed > kMaxSpeedLive) {
        char v[32];
        std::snprintf(v, sizeof v, "%g", o->speed);
        *err = std::string("--speed wants a number from 0.1 to 100 without --lockstep, got '") +
               v + "'";
        return ParseResult::Error;
    }
    if (o->teleport.has_to && !o->teleport.enabled()) {
        *err = "--teleport-to needs --teleport-after or --teleport-every (--help)";
        return ParseResult::Error;
    }
    return ParseResult::Run;
}

bool start_pose(const World &w, const SimOptions &o, Pose *out, std::string *err)
{
    const char *what = "--start";
    if (o.has_start) {
        *out = Pose{o.start_x_m * 1000.0, o.start_y_m * 1000.0, wrap_pi(deg2rad(o.start_deg))};
    } else if (w.has_start) {
        *out = w.start;
        what = "the world's start";
    } else if (w.has_tour) {
        std::vector<TourStop> stops = tour_order(w, w.tour_start, w.tile_mm, kTourClearanceMm);
        Vec2 p = stops.empty() ? w.tour_start : stops[0].at;
        *out = Pose{p.x, p.y, 0.0};
        what = "the world's tour start";
    } else {
        *err = "--start: the world declares no start and no tour start; give --start X,Y,DEG";
        return false;
    }
    // A robot stopped against a wall stands at its radius; GROUND_TRUTH's whole
    // millimetres may put it a hair inside: check_free_pose lets it restart there.
    if (check_free_pose(w, *out, what, err))
        return true;
    if (!o.has_start)
        *err += "; give --start X,Y,DEG";
    return false;
}

}  // namespace hlsim
