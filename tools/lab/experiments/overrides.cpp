// overrides.cpp - see overrides.hpp.
#include "overrides.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace hlexp {

namespace {

// The table's key for @p name: itself when it names a section ("localize.cell_mm"), else
// the one key of any section with that name ("cell_mm"); "" when none or several.
std::string key_for(const std::string &name)
{
    if (name.find('.') != std::string::npos)
        return name;
    std::string found;
    const hl_param_info_t *k;
    for (size_t i = 0; (k = hl_params_info(i)); i++) {
        const char *dot = std::strchr(k->key, '.');
        if (k->level != HL_PARAM_FIXED && dot && name == dot + 1) {
            if (!found.empty())
                return "";
            found = k->key;
        }
    }
    return found;
}

}  // namespace

bool apply_override(const std::string &setting, Mode *paper, Mode *improved, std::string *err)
{
    size_t dot = setting.find('.'), eq = setting.find('=');
    if (dot == std::string::npos || eq == std::string::npos || eq < dot) {
        *err = "--set wants MODE.NAME=VALUE, not '" + setting + "'";
        return false;
    }
    std::string mode = setting.substr(0, dot), name = setting.substr(dot + 1, eq - dot - 1);
    std::string value = setting.substr(eq + 1);
    Mode *m = mode == "paper" ? paper : mode == "improved" ? improved : nullptr;
    if (!m) {
        *err = "--set: unknown mode '" + mode + "' (paper or improved)";
        return false;
    }
    if (name == "table1_prior_sigma_mm") {      // Table 1's own, not the tracker's
        char *end = nullptr;
        errno = 0;
        double v = std::strtod(value.c_str(), &end);
        if (value.empty() || *end || errno || !std::isfinite(v) || v < 0 || v > 100000) {
            *err = "--set: table1_prior_sigma_mm must be a number in 0..100000, not '" + value +
                   "'";
            return false;
        }
        m->prior_sigma_mm = v;
        return true;
    }
    std::string key = key_for(name);
    if (key.empty()) {
        *err = "--set: unknown parameter '" + name + "'";
        return false;
    }
    if (hl_params_set(&m->params, key.c_str(), value.c_str()) != HL_OK ||
        hl_params_check(&m->params) != HL_OK) {
        *err = std::string("--set: ") + hl_params_error(&m->params);
        return false;
    }
    derive(m);
    return true;
}

}  // namespace hlexp
