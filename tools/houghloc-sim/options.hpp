// options.hpp - houghloc-sim's command line, parsed strictly: every number must be all
// digits (and a sign, point or exponent where it may have one), finite and in range.
#ifndef HLSIMROBOT_OPTIONS_HPP
#define HLSIMROBOT_OPTIONS_HPP

#include <cstdint>
#include <cstdio>
#include <string>

#include "server.hpp"

namespace hlsim {

struct SimOptions {
    std::string bind = "127.0.0.1";
    int port = 8101;                 // 0: any free port (logged)
    double speed = 1.0;              // robot time per wall time, 0.1 .. 100 (live), the
                                     // most it may be with --lockstep, 0.1 .. 1000
    bool lockstep = false;           // --lockstep: a SIP period per client credit
    uint64_t seed = 1;
    std::string world;               // empty: the built-in lab
    std::string profile = "bonnie";
    bool cone = false;               // --sonar-model cone
    bool has_start = false;
    double start_x_m = 0.0, start_y_m = 0.0, start_deg = 0.0;
    std::string lcm_url;             // empty: liblcm's default ($LCM_DEFAULT_URL)
    std::string prefix;              // channel prefix
    bool truth = true;               // publish GROUND_TRUTH
    double watchdog_s = 2.0;         // robot time without a client packet; 0: none
    std::string capture;             // --capture: the first client's bytes go here too
    Faults faults;
    TeleportPlan teleport;           // --teleport-after, --teleport-every, --teleport-to
};

enum class ParseResult { Run, Help, Version, Error };

/** Parses argv. On Error, @p err holds one line naming the option. */
ParseResult parse_options(int argc, char **argv, SimOptions *o, std::string *err);

/**
 * The true start pose: --start, else the world's `start` line, else its tour start
 * (snapped to its tile grid, where hl-sim-logs starts its tour) with heading 0. Checked
 * to be free space as --start is. @return false with one line in @p err.
 */
bool start_pose(const World &w, const SimOptions &o, Pose *out, std::string *err);

/** The --help text. */
void print_usage(FILE *f);
/** The --version line, "houghloc-sim <version>" as every houghloc program prints it. */
std::string version_line();

/** A strict decimal number: no spaces, no hex, no inf or nan, all of @p s used. */
bool parse_number(const char *s, double *out);
/** A strict unsigned integer: digits only, at most @p max. */
bool parse_count(const char *s, uint64_t max, uint64_t *out);

}  // namespace hlsim
#endif
