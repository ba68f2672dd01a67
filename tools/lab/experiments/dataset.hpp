// dataset.hpp - reads a recorded run (an LCM event log, as lcm-logger writes them) into
// soundings paired with their ground truth. Every message goes through the validating
// decoders of houghloc/bus.h.
#ifndef HLEXP_DATASET_HPP
#define HLEXP_DATASET_HPP

#include <memory>
#include <string>
#include <vector>

#include "houghloc/bus.h"

namespace hlexp {

struct Sounding {
    std::string channel;            // SONAR, SONAR_TEST, ...
    hl_bus_scan_t msg;              // scan, its odometry pose, seq, utime
    hl_pose_t truth{};              // from GROUND_TRUTH with the same scan_seq
    bool has_truth = false;
};

using Soundings = std::vector<std::unique_ptr<Sounding>>;

// Reads every scan on a channel whose name starts with "SONAR" and the GROUND_TRUTH poses.
// Returns false with a one-line reason (naming the file and event) on any bad event, a
// truncated log, a scan whose seq does not increase on the previous scan's (on any of
// those channels), or a scan without ground truth (the experiments score against it).
bool read_soundings(const std::string &path, Soundings *out, std::string *err);

// The soundings on exactly @p channel, in log order.
std::vector<const Sounding *> on_channel(const Soundings &all, const std::string &channel);

}  // namespace hlexp
#endif
