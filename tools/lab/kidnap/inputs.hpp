// inputs.hpp - what the kidnap tools (hl-kidnap, hl-tour-study) read: the slam parameters
// of houghlocd's configuration, through the daemon's own loader
// (houghloc-internal/daemon_config.h), and the robot's scans of a log.
#ifndef HLKID_INPUTS_HPP
#define HLKID_INPUTS_HPP

#include <memory>
#include <string>
#include <vector>

#include "dataset.hpp"
#include "houghloc-internal/daemon_config.h"
#include "houghloc/map.h"
#include "houghloc/slam.h"

namespace hlkid {

// For std::unique_ptr of the core's objects.
struct SlamDeleter {
    void operator()(hl_slam_t *s) const { hl_slam_destroy(s); }
};
struct MapDeleter {
    void operator()(hl_map_t *m) const { hl_map_destroy(m); }
};

// The slam parameters of houghlocd's configuration from @p file, then the K=V keys of
// @p sets in order (as `houghlocd --config FILE --set K=V`). nullptr with the loader's
// one-line reason in @p why on any bad key, value or file.
std::unique_ptr<hl_slam_params_t> load_config(const std::string &file,
                                         const std::vector<std::string> &sets,
                                         std::string *why);

// The SONAR scans of the log @p path with their ground truth (hlexp::read_soundings):
// a log's other scan channels (SONAR_TEST) are not the robot's tour.
bool load_soundings(const std::string &path, hlexp::Soundings *out, std::string *err);

}  // namespace hlkid
#endif
