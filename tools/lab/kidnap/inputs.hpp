// inputs.hpp - what the kidnap tools (hl-kidnap, hl-tour-study) read: the tracker's keys of
// a configuration file in houghlocd's form, set through the core's table (houghloc/params.h:
// every level, the studies' keys too), and the robot's scans of a log.
#ifndef HLKID_INPUTS_HPP
#define HLKID_INPUTS_HPP

#include <memory>
#include <string>
#include <vector>

#include "dataset.hpp"
#include "houghloc-internal/map.h"
#include "houghloc-internal/params.h"

namespace hlkid {

// For std::unique_ptr of the core's objects.
struct SlamDeleter {
    void operator()(hl_slam_t *s) const { hl_slam_destroy(s); }
};
struct MapDeleter {
    void operator()(hl_map_t *m) const { hl_map_destroy(m); }
};

// The tracker's parameters of the configuration @p file ([slam], [localize], [echo],
// [normals] and [reloc] keys), then the K=V keys of @p sets in order, slam.profile before
// the rest (as `houghlocd --config FILE --set K=V`). nullptr with a one-line reason in
// @p why on any bad key, value or file ("FILE:LINE: key 'x.y': ...").
std::unique_ptr<hl_params_t> load_config(const std::string &file,
                                         const std::vector<std::string> &sets,
                                         std::string *why);

// The SONAR scans of the log @p path with their ground truth (hlexp::read_soundings):
// a log's other scan channels (SONAR_TEST) are not the robot's tour.
bool load_soundings(const std::string &path, hlexp::Soundings *out, std::string *err);

}  // namespace hlkid
#endif
