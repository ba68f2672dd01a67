// inputs.cpp - the kidnap tools' configuration and logs (inputs.hpp).
#include "inputs.hpp"

#include <fstream>
#include <sstream>
#include <utility>

namespace hlkid {

namespace {

std::string trim(const std::string &s)
{
    size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
    return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

bool is_preset(const std::string &key)
{
    const hl_param_info_t *k;
    for (size_t i = 0; (k = hl_params_info(i)); i++)
        if (key == k->key)
            return k->type == HL_PARAM_PRESET;
    return false;
}

// One "section.key" = value, with where it came from for the message.
struct Setting {
    std::string where, key, value;
};

// The keys of the INI text @p text ("[section]" lines, "key = value" lines, ';' and '#'
// comments), as houghlocd reads its file. false with why on a line that is neither.
bool read_ini(const std::string &file, const std::string &text, std::vector<Setting> *out,
              std::string *why)
{
    std::istringstream in(text);
    std::string line, section;
    for (int n = 1; std::getline(in, line); n++) {
        std::string where = file + ":" + std::to_string(n);
        size_t c = line.find_first_of(";#");
        if (c != std::string::npos && (c == 0 || line[c - 1] == ' ' || line[c - 1] == '\t'))
            line.erase(c);
        line = trim(line);
        if (line.empty())
            continue;
        if (line.front() == '[' && line.back() == ']') {
            section = trim(line.substr(1, line.size() - 2));
            continue;
        }
        size_t eq = line.find('=');
        if (eq == std::string::npos || section.empty()) {
            *why = where + ": not a 'key = value' line in a [section]";
            return false;
        }
        out->push_back({ where, section + "." + trim(line.substr(0, eq)),
                         trim(line.substr(eq + 1)) });
    }
    return true;
}

}  // namespace

std::unique_ptr<hl_params_t> load_config(const std::string &file,
                                         const std::vector<std::string> &sets,
                                         std::string *why)
{
    std::ifstream f(file);
    if (!f) {
        *why = file + ": cannot open";
        return nullptr;
    }
    std::stringstream text;
    text << f.rdbuf();
    std::vector<Setting> all;
    if (!read_ini(file, text.str(), &all, why))
        return nullptr;
    for (const std::string &s : sets) {
        size_t eq = s.find('=');
        if (eq == std::string::npos) {
            *why = "--set " + s + ": expected SECTION.KEY=VALUE";
            return nullptr;
        }
        all.push_back({ "--set " + s, s.substr(0, eq), s.substr(eq + 1) });
    }
    auto p = std::make_unique<hl_params_t>();
    hl_params_default(p.get());
    // The presets first (slam.profile), then every other key, as houghlocd applies them.
    for (bool presets : { true, false })
        for (const Setting &s : all)
            if (is_preset(s.key) == presets &&
                hl_params_set(p.get(), s.key.c_str(), s.value.c_str()) != HL_OK) {
                *why = s.where + ": " + hl_params_error(p.get());
                return nullptr;
            }
    if (hl_params_check(p.get()) != HL_OK) {
        *why = file + ": " + hl_params_error(p.get());
        return nullptr;
    }
    return p;
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
