// overrides.hpp - `--set MODE.NAME=VALUE`: change one parameter of a mode from the
// command line, for parameter studies without recompiling. NAME is a key of the core's
// table (houghloc/params.h: "localize.blur_sigma_mm", or its name alone when no other
// section has it, "blur_sigma_mm"), or table1_prior_sigma_mm (Mode::prior_sigma_mm).
#ifndef HLEXP_OVERRIDES_HPP
#define HLEXP_OVERRIDES_HPP

#include <string>

#include "experiment.hpp"

namespace hlexp {

// Applies "paper.NAME=VALUE" or "improved.NAME=VALUE" to the matching mode. Returns
// false with a one-line reason for an unknown mode or name or a bad value.
bool apply_override(const std::string &setting, Mode *paper, Mode *improved, std::string *err);

}  // namespace hlexp
#endif
