// inputs.cpp - the kidnap tools' configuration and logs (inputs.hpp).
#include "inputs.hpp"

namespace hlkid {

std::unique_ptr<hl_slam_params_t> load_config(const std::string &file,
                                         const std::vector<std::string> &sets,
                                         std::string *why)
{
    std::vector<const char *> keys;
    for (const std::string &s : sets)
        keys.push_back(s.c_str());
    auto cfg = std::make_unique<hl_slam_params_t>();
    char buf[HL_DAEMON_CONFIG_WHY_LEN];
    if (!hl_daemon_config_slam(file.c_str(), keys.data(), static_cast<int>(keys.size()),
                               cfg.get(), buf)) {
        *why = buf;
        return nullptr;
    }
    return cfg;
}

bool load_soundings(const std::string &path, hlexp::Soundings *out, std::string *err)
{
    if (!hlexp::read_soundings(path, out, err))
        return false;
    hlexp::Soundings keep;
    for (auto &s : *out)
        if (s->channel == "SONAR")
            keep.push_back(std::move(s));
    out->swap(keep);
    return true;
}

}  // namespace hlkid
