// hl-experiments - reruns the paper's three experiments on the simulated data sets, in
// "paper" and "improved" modes, and writes results.md, table1.tsv, orientation.tsv,
// combined.tsv, limits.tsv (what the simulated sonar allows) and the figures into one
// folder.
#include <getopt.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <set>
#include <string>

#include "world.hpp"
#include "experiment.hpp"
#include "limits.hpp"
#include "overrides.hpp"
#include "report.hpp"

namespace {

void usage(FILE *to)
{
    std::fprintf(to,
        "usage: hl-experiments [options]\n"
        "Reruns the paper's experiments (Table 1, orientation, combined map-making) on the\n"
        "simulated logs, in paper and improved modes; progress on stderr.\n"
        "\n"
        "  -l, --logs DIR      folder with lab28.lcmlog, orientation.lcmlog, tour.lcmlog\n"
        "                      (default: logs)\n"
        "  -o, --out DIR       where results and figures go (default: build/experiments)\n"
        "  -r, --reps N        Table 1: random map subsets per setting, 1..100 (default 8)\n"
        "  -x, --only NAMES    run only these, comma-separated: table1, orientation,\n"
        "                      combined, limits\n"
        "  -w, --world FILE    limits: the world the logs were simulated in (default: the\n"
        "                      built-in lab, as `make logs` uses)\n"
        "  -s, --set M.NAME=V  change one parameter of mode M (paper or improved); repeat\n"
        "                      as needed. NAME is a key of houghlocd's [slam], [localize],\n"
        "                      [echo], [normals] or [reloc] (houghlocd --print-config=all),\n"
        "                      with or without its section, or table1_prior_sigma_mm\n"
        "      --no-figures    skip the PNG figures\n"
        "  -h, --help          this text\n");
}

bool load(const std::string &path, hlexp::Soundings *s)
{
    std::string err;
    if (!hlexp::read_soundings(path, s, &err)) {
        std::fprintf(stderr, "hl-experiments: %s\n", err.c_str());
        return false;
    }
    return true;
}

}  // namespace

int main(int argc, char **argv)
{
    hlexp::Context ctx;
    hlexp::Mode paper = hlexp::paper_mode(), improved = hlexp::improved_mode();
    ctx.out_dir = "build/experiments";
    std::string logs = "logs", world_path;
    std::set<std::string> only;     // empty: all
    const struct option opts[] = {
        { "logs", required_argument, nullptr, 'l' }, { "out", required_argument, nullptr, 'o' },
        { "reps", required_argument, nullptr, 'r' }, { "only", required_argument, nullptr, 'x' },
        { "world", required_argument, nullptr, 'w' },
        { "set", required_argument, nullptr, 's' }, { "no-figures", no_argument, nullptr, 'F' }, { "help", no_argument, nullptr, 'h' },
        { nullptr, 0, nullptr, 0 },
    };
    int c;
    opterr = 0;     // one line of our own instead of getopt's and the usage
    while ((c = getopt_long(argc, argv, ":l:o:r:x:w:s:h", opts, nullptr)) != -1) {
        switch (c) {
        case 'l': logs = optarg; break;
        case 'o': ctx.out_dir = optarg; break;
        case 'r': {
            char *end;
            errno = 0;
            long v = std::strtol(optarg, &end, 10);
            if (*optarg < '0' || *optarg > '9' || errno || *end || v < 1 || v > 100) {
                std::fprintf(stderr, "hl-experiments: --reps must be a whole number 1..100, not '%s'\n", optarg);
                return 2;
            }
            ctx.reps = static_cast<int>(v);
            break;
        }
        case 'x': {
            // a comma-separated list of experiment names
            std::string list = optarg;
            for (size_t at = 0; at <= list.size();) {
                size_t comma = std::min(list.find(',', at), list.size());
                std::string name = list.substr(at, comma - at);
                if (name != "table1" && name != "orientation" && name != "combined" &&
                    name != "limits") {
                    std::fprintf(stderr, "hl-experiments: --only takes table1, orientation, combined or limits, not '%s'\n", name.c_str());
                    return 2;
                }
                only.insert(name);
                at = comma + 1;
            }
            break;
        }
        case 's': {
            std::string err;
            if (!hlexp::apply_override(optarg, &paper, &improved, &err)) {
                std::fprintf(stderr, "hl-experiments: %s\n", err.c_str());
                return 2;
            }
            break;
        }
        case 'w': world_path = optarg; break;
        case 'F': ctx.figures = false; break;
        case 'h': usage(stdout); return 0;
        case ':':
            std::fprintf(stderr, "hl-experiments: %s needs a value (try --help)\n", argv[optind - 1]);
            return 2;
        default:
            std::fprintf(stderr, "hl-experiments: unknown option '%s' (try --help)\n", argv[optind - 1]);
            return 2;
        }
    }
    if (optind < argc) {
        std::fprintf(stderr, "hl-experiments: unexpected argument '%s'\n", argv[optind]);
        return 2;
    }
    if (mkdir(ctx.out_dir.c_str(), 0777) != 0 && errno != EEXIST) {
        std::fprintf(stderr, "hl-experiments: cannot create %s: %s\n", ctx.out_dir.c_str(),
                     std::strerror(errno));
        return 1;
    }

    for (const hlexp::Mode *m : { &paper, &improved }) {
        const char *e = hl_slam_params_error(&m->slam);
        if (!e)
            e = hl_loc_params_error(&m->loc);
        if (e) {
            std::fprintf(stderr, "hl-experiments: %s mode: %s\n", m->name.c_str(), e);
            return 2;
        }
    }
    const hlexp::Mode modes[] = { paper, improved };
    auto want = [&](const char *name) { return only.empty() || only.count(name) > 0; };
    hlsim::World world;
    std::string err;
    if (want("limits") && !hlsim::World::load_or_lab(world_path, &world, &err)) {
        std::fprintf(stderr, "hl-experiments: %s\n", err.c_str());
        return 1;
    }
    hlexp::Soundings lab, orientation, tour;
    if (((want("table1") || want("limits")) && !load(logs + "/lab28.lcmlog", &lab)) ||
        ((want("orientation") || want("limits")) &&
         !load(logs + "/orientation.lcmlog", &orientation)) ||
        ((want("combined") || want("limits")) && !load(logs + "/tour.lcmlog", &tour)))
        return 1;
    hlexp::Results res;
    if (want("table1")) {
        // Improved mode both with its prior estimate and, like the paper's method,
        // without one (a global search).
        hlexp::Mode improved_global = improved;
        improved_global.prior_sigma_mm = 0;
        for (const auto *m : { &paper, &improved_global, &improved }) {
            auto rows = hlexp::run_table1(lab, *m, ctx);
            res.table1.insert(res.table1.end(), rows.begin(), rows.end());
        }
    }
    if (want("orientation"))
        for (const auto &m : modes)
            res.orientation.push_back(hlexp::run_orientation(orientation, m, ctx));
    if (want("combined"))
        for (const auto &m : modes) {
            auto rows = hlexp::run_combined(tour, m, ctx, &m == &modes[0]);
            res.combined.insert(res.combined.end(), rows.begin(), rows.end());
        }
    if (want("limits"))
        res.limits = hlexp::run_limits({ &lab, &orientation, &tour }, world, improved, ctx);
    res.reps = ctx.reps;
    if (!hlexp::write_results(ctx.out_dir, res, &err)) {
        std::fprintf(stderr, "hl-experiments: %s\n", err.c_str());
        return 1;
    }
    std::fprintf(stderr, "hl-experiments: results in %s/results.md\n", ctx.out_dir.c_str());
    return 0;
}
