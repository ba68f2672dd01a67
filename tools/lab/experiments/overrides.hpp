// overrides.hpp - `--set MODE.NAME=VALUE`: change one parameter of a mode from the
// command line, for parameter studies without recompiling.
#ifndef HLEXP_OVERRIDES_HPP
#define HLEXP_OVERRIDES_HPP

#include <string>

#include "experiment.hpp"

namespace hlexp {

// Applies "paper.NAME=VALUE" or "improved.NAME=VALUE" to the matching mode. Returns
// false with a one-line reason for an unknown mode or name or a bad value.
bool apply_override(const std::string &setting, Mode *paper, Mode *improved, std::string *err);

// The names --set accepts, for --help.
const char *override_names();

}  // namespace hlexp
#endif
