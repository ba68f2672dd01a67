// report.cpp - see report.hpp.
#include "report.hpp"

#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>

namespace hlexp {

namespace {

// The paper's Table 1: wild %, tame mean mm, tame sigma mm by (raster, fraction).
struct PaperRow { int raster, fraction16; double wild_pct, mean_mm, sigma_mm; };
const PaperRow PAPER_TABLE1[] = {
    { 47, 1, 10.7, 91, 48 }, { 47, 2, 3.6, 54, 28 }, { 47, 3, 7.1, 47, 20 },
    { 24, 1, 10.7, 86, 49 }, { 24, 2, 3.6, 46, 25 }, { 24, 3, 3.6, 34, 19 },
};
const double PAPER_ORIENT_MEAN = 1.27, PAPER_ORIENT_SIGMA = 0.72;

const PaperRow *paper_row(int raster, int fraction16)
{
    for (const auto &p : PAPER_TABLE1)
        if (p.raster == raster && p.fraction16 == fraction16)
            return &p;
    return nullptr;
}

class File {
public:
    File(const std::string &path, std::string *err) : path_(path), err_(err)
    {
        f_ = std::fopen(path.c_str(), "w");
        if (!f_)
            *err_ = "cannot write " + path + ": " + std::strerror(errno);
    }
    ~File() { close(); }
    bool ok() const { return f_ != nullptr; }
    FILE *get() { return f_; }
    bool close()
    {
        if (!f_)
            return false;
        bool good = !std::ferror(f_);
        good = (std::fclose(f_) == 0) && good;
        f_ = nullptr;
        if (!good)
            *err_ = "error writing " + path_;
        return good;
    }

private:
    FILE *f_ = nullptr;
    std::string path_;
    std::string *err_;
};

// A number with @p decimals and @p unit, or @p none when it is NaN (not measured).
std::string cell(double v, int decimals, const char *unit = "", const char *none = "")
{
    if (std::isnan(v))
        return none;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f%s", decimals, v, unit);
    return buf;
}

double pct(int n, int of)
{
    return of ? 100.0 * n / of : 0.0;
}

// One TSV file: a header line, then one line per row from `print`. Skipped when there
// are no rows (that experiment was not run).
template <typename Row, typename Print>
bool write_tsv(const std::string &path, const char *header, const std::vector<Row> &rows,
               Print print, std::string *err)
{
    if (rows.empty())
        return true;
    File f(path, err);
    if (!f.ok())
        return false;
    std::fprintf(f.get(), "%s\n", header);
    for (const Row &row : rows)
        print(f.get(), row);
    return f.close();
}

bool write_tsvs(const std::string &dir, const Results &r, std::string *err)
{
    return write_tsv(dir + "/table1.tsv",
                     "mode\tfraction\traster_mm\ttrials\twild\twild_pct\ttame_mean_mm\ttame_sigma_mm\tprior",
                     r.table1, [](FILE *f, const Table1Row &t) {
                         std::fprintf(f, "%s\t%d/16\t%d\t%d\t%d\t%.1f\t%.1f\t%.1f\t%s\n",
                                      t.mode.c_str(), t.fraction16, t.raster_mm, t.trials,
                                      t.wild, pct(t.wild, t.trials), t.tame_mean_mm,
                                      t.tame_sigma_mm, t.prior ? "yes" : "no");
                     }, err) &&
           write_tsv(dir + "/orientation.tsv", "mode\ttrials\tmean_deg\tsigma_deg\tmax_abs_deg",
                     r.orientation, [](FILE *f, const OrientationRow &o) {
                         std::fprintf(f, "%s\t%d\t%.3f\t%.3f\t%.3f\n", o.mode.c_str(),
                                      o.trials, o.mean_deg, o.sigma_deg, o.max_abs_deg);
                     }, err) &&
           write_tsv(dir + "/combined.tsv",
                     "mode\tstops\taccepted\trejected\twild_accepted\trmse_mm\tmax_mm\tfinal_mm",
                     r.combined, [](FILE *f, const CombinedRow &c) {
                         std::fprintf(f, "%s\t%d\t%d\t%d\t%d\t%.1f\t%.1f\t%.1f\n",
                                      c.mode.c_str(), c.stops, c.accepted, c.rejected,
                                      c.wild_accepted, c.rmse_mm, c.max_mm, c.final_mm);
                     }, err) &&
           write_tsv(dir + "/limits.tsv",
                     "what\ttrials\twild\tposition_mm\theading_mean_deg\theading_sigma_deg",
                     r.limits, [](FILE *f, const LimitsRow &l) {
                         std::fprintf(f, "%s\t%d\t%d\t%s\t%s\t%s\n", l.what.c_str(), l.trials,
                                      l.wild, cell(l.pos_mean_mm, 1).c_str(),
                                      cell(l.heading_mean_deg, 3).c_str(),
                                      cell(l.heading_sigma_deg, 3).c_str());
                     }, err);
}

void markdown_table1(FILE *f, const Results &r)
{
    std::fprintf(f, "## 1. Localization against a known map (Table 1)\n\n"
                    "Leave-one-out over the positions of `logs/lab28.lcmlog` (the map: every "
                    "sounding of the other positions; the test: the left-out position's first "
                    "sounding), heading known; %d random map subsets per setting, so %d trials "
                    "per row with 28 positions (the paper: 28). Paper mode searches the whole "
                    "map, as the paper did; so does improved mode without a prior. Improved mode "
                    "with a prior is given a prior estimate, the measured position plus a seeded "
                    "Gaussian error of 150 mm per axis (what odometry over a short hop would "
                    "give), and searches +-1 m around it with the odometry prior. Wild = error "
                    "above 0.5 m; tame = the rest.\n\n",
                 r.reps, r.reps * 28);
    std::fprintf(f, "| raster | fraction | paper: wild | tame mean | sigma | paper mode: wild | tame mean | sigma | improved, no prior: wild | tame mean | sigma | improved, prior: wild | tame mean | sigma |\n"
                    "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int raster : { 47, 24 })
        for (int fr = 1; fr <= 3; fr++) {
            const PaperRow *p = paper_row(raster, fr);
            std::fprintf(f, "| %d mm | %d/16 | %.1f %% | %.0f mm | %.0f mm", raster, fr,
                         p->wild_pct, p->mean_mm, p->sigma_mm);
            const std::pair<const char *, bool> cols[] = { { "paper", false },
                                                            { "improved", false },
                                                            { "improved", true } };
            for (const auto &[mode, prior] : cols) {
                const Table1Row *row = nullptr;
                for (const auto &t : r.table1)
                    if (t.mode == mode && t.prior == prior && t.raster_mm == raster &&
                        t.fraction16 == fr)
                        row = &t;
                if (row)
                    std::fprintf(f, " | %.1f %% | %.0f mm | %.0f mm", pct(row->wild, row->trials),
                                 row->tame_mean_mm, row->tame_sigma_mm);
                else
                    std::fprintf(f, " | - | - | -");
            }
            std::fprintf(f, " |\n");
        }
    std::fprintf(f, "\n");
}

void markdown_orientation(FILE *f, const Results &r)
{
    std::fprintf(f, "## 2. Orientation (section 6)\n\n"
                    "Baseline map made online from six positions; test soundings over a 17 degree "
                    "range, (x, y, theta) search at a 1.1 degree raster. Heading error against "
                    "ground truth.\n\n"
                    "| | soundings | mean error | sigma | largest |\n|---|---|---|---|---|\n"
                    "| the paper | ? | %.2f deg | %.2f deg | - |\n",
                 PAPER_ORIENT_MEAN, PAPER_ORIENT_SIGMA);
    for (const auto &o : r.orientation)
        std::fprintf(f, "| %s mode | %d | %.2f deg | %.2f deg | %.2f deg |\n", o.mode.c_str(),
                     o.trials, o.mean_deg, o.sigma_deg, o.max_abs_deg);
    std::fprintf(f, "\n");
}

void markdown_combined(FILE *f, const Results &r)
{
    std::fprintf(f, "## 3. Combined map-making and localization (section 7)\n\n"
                    "The space-filling tour of `logs/tour.lcmlog`; the map culled at random to "
                    "1500 vectors. Position error against ground truth at every stop. The paper "
                    "reports this experiment only as pictures (its Fig. 7).\n\n"
                    "| | stops | accepted | rejected | wild accepted | RMSE | largest | final |\n"
                    "|---|---|---|---|---|---|---|---|\n");
    for (const auto &c : r.combined)
        std::fprintf(f, "| %s | %d | %d | %d | %d | %.0f mm | %.0f mm | %.0f mm |\n",
                     c.mode.c_str(), c.stops, c.accepted, c.rejected, c.wild_accepted,
                     c.rmse_mm, c.max_mm, c.final_mm);
    std::fprintf(f, "\n");
}

void markdown_limits(FILE *f, const Results &r)
{
    std::fprintf(f, "## 4. What the simulated sonar allows\n\n"
                    "Two oracles that use the simulator's own world and physics, which no robot "
                    "has (`tools/lab/experiments/limits.hpp`): the exact first-echo model fitted to "
                    "each sounding near its true pose (the floor set by range noise, the body "
                    "rotation error and the ring's sampling), and the improved mode's own "
                    "experiments with every reading moved to the bearing its echo really came "
                    "from (what perfect echo-bearing estimation would give). Position: the mean "
                    "error of the non-wild trials, or the RMSE where the row says so.\n\n"
                    "| oracle and experiment | trials | wild | position | heading mean | heading sigma |\n"
                    "|---|---|---|---|---|---|\n");
    for (const auto &l : r.limits)
        std::fprintf(f, "| %s | %d | %d | %s | %s | %s |\n", l.what.c_str(), l.trials, l.wild,
                     cell(l.pos_mean_mm, 0, " mm", "-").c_str(),
                     cell(l.heading_mean_deg, 2, " deg", "-").c_str(),
                     cell(l.heading_sigma_deg, 2, " deg", "-").c_str());
    std::fprintf(f, "\n");
}

}  // namespace

void progress(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    std::vfprintf(stderr, fmt, ap);
    va_end(ap);
    std::fputc('\n', stderr);
}

bool write_results(const std::string &dir, const Results &r, std::string *err)
{
    if (!write_tsvs(dir, r, err))
        return false;
    File f(dir + "/results.md", err);
    if (!f.ok())
        return false;
    std::fprintf(f.get(), "# houghloc: the paper's experiments, rerun\n\n"
                          "Made by `make experiments` (`build/bin/hl-experiments`) from the "
                          "simulated data sets in `logs/` (`make logs`, seed 1). Paper mode: the "
                          "paper's method and parameters; improved mode: ours (see README).\n\n");
    if (!r.table1.empty())
        markdown_table1(f.get(), r);
    if (!r.orientation.empty())
        markdown_orientation(f.get(), r);
    if (!r.combined.empty())
        markdown_combined(f.get(), r);
    if (!r.limits.empty())
        markdown_limits(f.get(), r);
    return f.close();
}

}  // namespace hlexp
