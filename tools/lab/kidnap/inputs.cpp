// inputs.cpp - the kidnap tools' configuration and logs (inputs.hpp).
#include "inputs.hpp"

namespace hlkid {

std::unique_ptr<hl_config_t> load_config(const std::string &file,
                                         const std::vector<std::string> &sets,
                                         std::string *why)
{
    std::vector<const char *> keys;
    for (const std::string &s : sets)
        keys.push_back(s.c_str());
    auto cfg = std::make_unique<hl_config_t>();
    char buf[HL_CONFIG_WHY_LEN];
    if (!hl_config_load(cfg.get(), file.c_str(), false, keys.data(),
                        static_cast<int>(keys.size()), buf)) {
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
