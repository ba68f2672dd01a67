// hl-kidnap - one row of the kidnap experiment (make kidnap, tools/lab/kidnap/kidnap.mk): how
// often hl_slam_relocalize finds a robot set down anywhere in a known map, heading
// unknown, from one scan, and how long it takes.
//
// The parameters are the core's table (houghloc/params.h), read from --config (and --set)
// in houghlocd's form: a file of the daemon's tracker keys gives what houghlocd would do
// with it, and the global search's study keys (the table's level "study", which
// houghlocd does not offer) are set here too.
#include <getopt.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "inputs.hpp"
#include "kidnap.hpp"

namespace {

void usage(FILE *to)
{
    std::fprintf(to,
        "usage: hl-kidnap --config FILE [--set K=V]... --world NAME --input INPUT --trials N\n"
        "                 (--sim-world FILE (--map MAP... | --truth-map TOUR...) --test-log LOG\n"
        "                  [--seed S]\n"
        "                  | --log IMPORT [--exclude-m M]) [--detail FILE]\n"
        "       hl-kidnap --header\n"
        "Relocalizes N robots, heading unknown, each from its first reloc.scans scans at\n"
        "least %.1f m apart, with hl_slam_relocalize_scans, and prints one row:\n"
        "  %s\n"
        "(a success is found, not ambiguous, within %.1f m and %.0f degrees of the truth;\n"
        "times are the call alone). Progress on stderr.\n"
        "  --config FILE     the tracker's keys in houghlocd's form, the studies' too\n"
        "                    (/dev/null: the defaults)\n"
        "  --set K=V         a key, after the file (repeatable)\n"
        "  --world, --input  the row's first two cells\n"
        "A simulated world: the map is the daemon's map file MAP of its tour of the world\n"
        "FILE ('lab': the built-in lab); N soundings at random free poses, drawn with seed S\n"
        "(default 1), each followed by the robot's next soundings, are written to LOG first. --truth-map TOUR: the map is made instead of\n"
        "the tour log TOUR's scans at their true poses (a drift-free tour), as the slam does.\n"
        "Several maps (--map or --truth-map again, one kind): the same N soundings in each,\n"
        "one row of them all (N times the maps trials), a line for each map on stderr.\n"
        "A real building: every scan of the imported log IMPORT (houghloc-import-carmen with\n"
        "--truth) more than M metres (default 2) from all of a trial's scans' true positions\n"
        "makes its map, at its true pose; N test scans spread evenly over the log, each with\n"
        "the log's next scans apart.\n"
        "  --detail FILE     one line per trial (the answer, the runner-up, the errors)\n"
        "  --alone-first     as the tracker searches a lost scan: the test scan alone first,\n"
        "                    the scans together only when that answer is ambiguous\n"
        "Exit status: 0 done; 1 an error (one line on stderr); 2 bad usage.\n",
        hlkid::kApartMm / 1000.0, hlkid::kHeader, hlkid::kSuccessMm / 1000.0,
        hlkid::kSuccessDeg);
}

struct Options {
    std::string config, world, input, sim_world, test_log, log, detail;
    bool alone_first = false;
    std::vector<std::string> sets, maps, truth_maps;
    long trials = 0;
    unsigned long long seed = 1;
    double exclude_m = 2.0;
};

bool number(const char *s, double lo, double hi, double *out)
{
    char *end = nullptr;
    errno = 0;
    double v = std::strtod(s, &end);
    if (*s == '\0' || *end != '\0' || errno == ERANGE || !(v >= lo && v <= hi))
        return false;
    *out = v;
    return true;
}

// A bad option value: one line, exit status 2.
int bad(const char *option, const char *wants, const char *got)
{
    std::fprintf(stderr, "hl-kidnap: %s wants %s, got '%s'\n", option, wants, got);
    return 2;
}

// Parses argv into @p o; returns -1 to go on, else the exit status.
int parse(int argc, char **argv, Options *o)
{
    enum { WORLD = 256, INPUT, SIM_WORLD, MAP, TRUTH_MAP, TEST_LOG, LOG, SEED, EXCLUDE, DETAIL, HEADER,
           ALONE_FIRST };
    static const struct option longs[] = {
        { "config", required_argument, nullptr, 'c' },
        { "set", required_argument, nullptr, 's' },
        { "trials", required_argument, nullptr, 'n' },
        { "world", required_argument, nullptr, WORLD },
        { "input", required_argument, nullptr, INPUT },
        { "sim-world", required_argument, nullptr, SIM_WORLD },
        { "map", required_argument, nullptr, MAP },
        { "truth-map", required_argument, nullptr, TRUTH_MAP },
        { "test-log", required_argument, nullptr, TEST_LOG },
        { "log", required_argument, nullptr, LOG },
        { "seed", required_argument, nullptr, SEED },
        { "exclude-m", required_argument, nullptr, EXCLUDE },
        { "detail", required_argument, nullptr, DETAIL },
        { "header", no_argument, nullptr, HEADER },
        { "alone-first", no_argument, nullptr, ALONE_FIRST },
        { "help", no_argument, nullptr, 'h' },
        { nullptr, 0, nullptr, 0 },
    };
    double v;
    for (int c; (c = getopt_long(argc, argv, "c:s:n:h", longs, nullptr)) != -1;) {
        switch (c) {
        case 'c': o->config = optarg; break;
        case 's': o->sets.push_back(optarg); break;
        case 'n':
            if (!number(optarg, 1, 100000, &v) || v != static_cast<long>(v))
                return bad("--trials", "1..100000", optarg);
            o->trials = static_cast<long>(v);
            break;
        case WORLD: o->world = optarg; break;
        case INPUT: o->input = optarg; break;
        case SIM_WORLD: o->sim_world = optarg; break;
        case MAP: o->maps.push_back(optarg); break;
        case TRUTH_MAP: o->truth_maps.push_back(optarg); break;
        case TEST_LOG: o->test_log = optarg; break;
        case LOG: o->log = optarg; break;
        case SEED:
            if (!number(optarg, 0, 1e15, &v) || v != static_cast<double>(static_cast<long long>(v)))
                return bad("--seed", "a whole number", optarg);
            o->seed = static_cast<unsigned long long>(v);
            break;
        case EXCLUDE:
            if (!number(optarg, 0, 1000, &v))
                return bad("--exclude-m", "metres in 0..1000", optarg);
            o->exclude_m = v;
            break;
        case DETAIL: o->detail = optarg; break;
        case ALONE_FIRST: o->alone_first = true; break;
        case HEADER: std::printf("%s\n", hlkid::kHeader); return 0;
        case 'h': usage(stdout); return 0;
        default: usage(stderr); return 2;
        }
    }
    bool sim = !o->sim_world.empty(), real = !o->log.empty();
    const char *missing = optind < argc ? "no operands" :
                          o->config.empty() ? "--config" : o->world.empty() ? "--world" :
                          o->input.empty() ? "--input" : o->trials == 0 ? "--trials" :
                          sim == real ? "one of --sim-world and --log" :
                          sim && o->maps.empty() == o->truth_maps.empty() ?
                              "one of --map and --truth-map" :
                          sim && o->test_log.empty() ? "--test-log" : nullptr;
    if (missing) {
        std::fprintf(stderr, "hl-kidnap: wants %s (--help)\n", missing);
        return 2;
    }
    return -1;
}


// The map of the tour log @p path's scans at their true poses, into @p slam.
bool truth_map(const hl_slam_params_t &p, const std::string &path, hl_slam_t *slam,
               std::string *err)
{
    hlexp::Soundings tour;
    if (!hlkid::load_soundings(path, &tour, err))
        return false;
    hlkid::TruthMapper mapper(p, tour);
    if (!mapper.make({}, -1.0, err))
        return false;
    return hlkid::restore_map(slam, hl_map_vectors(mapper.map()), hl_map_count(mapper.map()),
                              err);
}

// The trials of the soundings @p tests in one map of a simulated world: the daemon's map
// file @p path, or (@p truth) the tour log @p path mapped at its true poses. @p index of
// @p count maps, for the trials' map column and the lines on stderr.
bool run_sim_map(const hl_slam_params_t &p, const std::string &what, const std::string &path,
                 bool truth, int index, int count, const hlexp::Soundings &tests,
                 hlkid::Scorer *scorer)
{
    std::string err;
    std::unique_ptr<hl_slam_t, hlkid::SlamDeleter> slam(hl_slam_create_with(&p));
    if (!slam) {
        std::fprintf(stderr, "hl-kidnap: %s: cannot create the slam\n", what.c_str());
        return false;
    }
    if (!(truth ? truth_map(p, path, slam.get(), &err)
                : hlkid::load_daemon_map(slam.get(), path, &err))) {
        std::fprintf(stderr, "hl-kidnap: %s: %s\n", what.c_str(), err.c_str());
        return false;
    }
    double w, h;
    uint32_t n = hl_map_count(hl_slam_map(slam.get()));
    unsigned long long cells = hlkid::coarse_cells_needed(
        p.reloc, hl_map_vectors(hl_slam_map(slam.get())), n, &w, &h);
    std::fprintf(stderr,
                 "kidnap: %s: map %d of %d (%s): %u vectors over %.1f x %.1f m (%llu coarse "
                 "cells), %zu test soundings\n",
                 what.c_str(), index, count, path.c_str(), n, w, h, cells, tests.size());
    scorer->set_map(index, count);
    const size_t per = p.reloc.scans, trials = tests.size() / per;
    for (size_t k = 0; k < trials; k++) {
        hlkid::Group group;
        for (size_t i = 0; i < per; i++)
            group.push_back(tests[k * per + i].get());
        if (!scorer->run(slam.get(), group, &err)) {
            std::fprintf(stderr, "hl-kidnap: %s: %s\n", what.c_str(), err.c_str());
            return false;
        }
        scorer->progress(static_cast<int>(trials), 20);
    }
    return true;
}

int run(const Options &o)
{
    std::string why;
    std::unique_ptr<hl_params_t> cfg = hlkid::load_config(o.config, o.sets, &why);
    if (!cfg) {
        std::fprintf(stderr, "hl-kidnap: %s\n", why.c_str());
        return 1;
    }
    const hl_slam_params_t &p = *hl_params_slam(cfg.get());
    const std::string what = o.world + " " + o.input;
    hlkid::Scorer scorer(o.world, o.input, p.reloc, o.alone_first);
    std::string err;
    hlexp::Soundings tests;
    if (!o.sim_world.empty()) {
        const std::string world = o.sim_world == "lab" ? "" : o.sim_world;
        if (!hlkid::write_sim_tests(world, static_cast<int>(o.trials), p.reloc.scans, o.seed,
                                    o.test_log, &err) ||
            !hlkid::load_soundings(o.test_log, &tests, &err)) {
            std::fprintf(stderr, "hl-kidnap: %s: %s\n", what.c_str(), err.c_str());
            return 1;
        }
        const bool truth = o.maps.empty();
        const std::vector<std::string> &maps = truth ? o.truth_maps : o.maps;
        // Every map readable before the first trial: a run of several maps takes minutes.
        for (const std::string &m : maps)
            if (FILE *f = std::fopen(m.c_str(), "rb"))
                std::fclose(f);
            else {
                std::fprintf(stderr, "hl-kidnap: %s: %s: cannot open: %s\n", what.c_str(),
                             m.c_str(), std::strerror(errno));
                return 1;
            }
        for (size_t i = 0; i < maps.size(); i++)
            if (!run_sim_map(p, what, maps[i], truth, static_cast<int>(i) + 1,
                             static_cast<int>(maps.size()), tests, &scorer))
                return 1;
    } else {
        if (!hlkid::load_soundings(o.log, &tests, &err) ||
            !hlkid::run_real(p, tests, static_cast<int>(o.trials), 1000.0 * o.exclude_m,
                             &scorer, &err)) {
            std::fprintf(stderr, "hl-kidnap: %s: %s\n", what.c_str(), err.c_str());
            return 1;
        }
    }
    if (!o.detail.empty() && !scorer.write_detail(o.detail, &err)) {
        std::fprintf(stderr, "hl-kidnap: %s\n", err.c_str());
        return 1;
    }
    scorer.write_row(stdout);
    return std::fflush(stdout) == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    int st = parse(argc, argv, &o);
    return st >= 0 ? st : run(o);
}
