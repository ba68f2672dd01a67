// table1.cpp - the localization experiment (paper, section 5, Table 1): leave-one-out
// over the 28 hand-placed positions. The soundings of the other 27 positions (the
// paper's 7,616 readings suggest two at each), placed at their measured poses, make the
// "known map"; a random fraction of it is kept; the left-out position's first sounding
// is localized over the whole map with its heading known. An error above 0.5 m is wild.
#include <cmath>
#include <cstdio>

#include "experiment.hpp"
#include "figures.hpp"
#include "houghloc-internal/localize.h"
#include "houghloc/rng.h"
#include "stats.hpp"

namespace hlexp {

namespace {

const double WILD_MM = 500.0;

// Every valid reading of a sounding as a map vector at its measured pose.
std::vector<hl_vector_t> vectors_of(const Sounding &s, const Mode &m)
{
    std::vector<hl_vector_t> v;
    hl_scan_t scan = as_localized(m, s.msg.scan);
    for (uint32_t i = 0; i < scan.count; i++) {
        hl_vector_t t;
        if (hl_vector_from_reading(s.msg.odometry, &scan.readings[i], &t))
            v.push_back(t);
    }
    return v;
}

// A uniformly random subset of round(all * sixteenths / 16) vectors (partial shuffle).
std::vector<hl_vector_t> sample(std::vector<hl_vector_t> all, int sixteenths, hl_rng_t *rng)
{
    size_t k = (all.size() * static_cast<size_t>(sixteenths) + 8) / 16;
    for (size_t i = 0; i < k; i++) {
        size_t j = i + hl_rng_below(rng, static_cast<uint32_t>(all.size() - i));
        std::swap(all[i], all[j]);
    }
    all.resize(k);
    return all;
}

struct Trial {
    double error_mm;
    hl_pose_t found;
    hl_loc_result_t result;
};

// Standard normal deviate (Box-Muller) from the core's generator, so runs are identical
// on every platform.
double gauss(hl_rng_t *rng)
{
    double u1 = (hl_rng_next(rng) + 1.0) / 4294967297.0, u2 = hl_rng_next(rng) / 4294967296.0;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

// Localizes sounding `test` against `map` with its heading known: over the whole map
// (paper), or in a window around a prior estimate (improved, see Mode::prior_sigma_mm).
bool localize(hl_localizer_t *loc, hl_refiner_t *refiner, const Mode &m,
              const std::vector<hl_vector_t> &map, const Sounding &test, hl_rng_t *rng,
              Trial *t)
{
    hl_loc_query_t q{};
    q.predicted = test.msg.odometry;    // the hand-measured pose
    q.window_mm = 0;
    q.search_theta = false;
    if (m.prior_sigma_mm > 0) {
        q.predicted.x_mm += static_cast<hl_mm_t>(std::lround(m.prior_sigma_mm * gauss(rng)));
        q.predicted.y_mm += static_cast<hl_mm_t>(std::lround(m.prior_sigma_mm * gauss(rng)));
        q.window_mm = m.slam.window_mm;
        q.use_prior = true;
    }
    hl_scan_t scan = as_localized(m, test.msg.scan);
    hl_status_t st = hl_loc_run(loc, map.data(), static_cast<uint32_t>(map.size()), &scan, &q,
                                &t->result);
    if (st != HL_OK) {
        progress("table1: sounding %d: %s", test.msg.seq, hl_status_str(st));
        return false;
    }
    hl_pose_t found = m.interpolate ? t->result.pose : t->result.cell_pose;
    if (refiner)    // heading known: polish x and y; a refused refinement keeps the peak
        hl_refine_run(refiner, map.data(), static_cast<uint32_t>(map.size()), &scan, found,
                      false, &found);
    t->found = found;
    t->error_mm = distance_mm(found, test.truth);
    return true;
}

// The soundings of each position, in log order: a position is a measured pose (the
// operator's tile intersection and heading), consecutive soundings there share it.
std::vector<std::vector<size_t>> by_position(const Soundings &lab)
{
    std::vector<std::vector<size_t>> groups;
    for (size_t i = 0; i < lab.size(); i++) {
        const hl_pose_t &p = lab[i]->msg.odometry;
        bool same = !groups.empty();
        if (same) {
            const hl_pose_t &q = lab[groups.back()[0]]->msg.odometry;
            same = p.x_mm == q.x_mm && p.y_mm == q.y_mm && p.theta == q.theta;
        }
        if (same)
            groups.back().push_back(i);
        else
            groups.push_back({ i });
    }
    return groups;
}

// The map vectors of every position but `skip`.
std::vector<hl_vector_t> others_of(const std::vector<std::vector<size_t>> &groups,
                                   const std::vector<std::vector<hl_vector_t>> &per, size_t skip)
{
    std::vector<hl_vector_t> map;
    for (size_t g = 0; g < groups.size(); g++)
        if (g != skip)
            for (size_t i : groups[g])
                map.insert(map.end(), per[i].begin(), per[i].end());
    return map;
}

void draw_figures(const Soundings &lab, const std::vector<std::vector<size_t>> &groups,
                  const std::vector<std::vector<hl_vector_t>> &per, const Mode &m,
                  const Context &ctx)
{
    // Fig. 3: the known map, every valid reading pointing back at its robot position.
    std::vector<hl_vector_t> all;
    std::vector<hl_pose_t> where;
    for (size_t i = 0; i < lab.size(); i++) {
        all.insert(all.end(), per[i].begin(), per[i].end());
        where.push_back(lab[i]->msg.odometry);
    }
    save_map_figure(ctx, "fig3_known_map.png", all, where,
                    "Known map: " + std::to_string(all.size()) + " valid readings from " +
                        std::to_string(groups.size()) + " positions" +
                        (m.slam.echo_bearings ? ", at their estimated echo bearings" : ""));

    // Figs. 4 and 5, as in the paper: a global search over the map (3/16 of it, 24 mm
    // raster, heading known) and, like its Fig. 5, a successful one: the first sounding
    // from P11 on that lands within 0.1 m.
    hl_loc_params_t p = m.loc;
    p.cell_mm = 24;
    hl_localizer_t *loc = hl_loc_create(&p);
    Mode global = m;
    global.prior_sigma_mm = 0;
    for (size_t k = 0; loc && k < groups.size(); k++) {
        size_t test = (10 + k) % groups.size();
        hl_rng_t rng;
        hl_rng_seed(&rng, 3);
        std::vector<hl_vector_t> map = sample(others_of(groups, per, test), 3, &rng);
        const Sounding &s = *lab[groups[test][0]];
        Trial t;
        if (localize(loc, nullptr, global, map, s, &rng, &t) && t.error_mm < 100.0) {
            save_localization_figures(ctx, loc, map, s, t.found);
            break;
        }
    }
    hl_loc_destroy(loc);
}

}  // namespace

std::vector<Table1Row> run_table1(const Soundings &lab, const Mode &m, const Context &ctx)
{
    std::vector<std::vector<hl_vector_t>> per;
    for (const auto &s : lab)
        per.push_back(vectors_of(*s, m));
    const std::vector<std::vector<size_t>> groups = by_position(lab);
    const bool prior = m.prior_sigma_mm > 0;
    std::vector<Table1Row> rows;
    for (int raster : { 47, 24 }) {
        hl_loc_params_t p = m.loc;
        p.cell_mm = raster;
        hl_localizer_t *loc = hl_loc_create(&p);
        hl_refiner_t *refiner =
            m.slam.refine ? hl_refine_create(&m.slam.refine_params, p.max_map_vectors) : nullptr;
        if (!loc || (m.slam.refine && !refiner)) {
            hl_refine_destroy(refiner);
            hl_loc_destroy(loc);
            progress("table1: %s", hl_loc_params_error(&p) ? hl_loc_params_error(&p) : "no memory");
            return rows;
        }
        for (int f = 1; f <= 3; f++) {
            Table1Row row{ m.name, prior, f, raster, 0, 0, 0, 0 };
            std::vector<double> tame;
            for (int rep = 0; rep < ctx.reps; rep++) {
                hl_rng_t rng;
                hl_rng_seed(&rng, static_cast<uint64_t>(1000 * rep + 16 * f + raster));
                for (size_t g = 0; g < groups.size(); g++) {
                    Trial t;
                    if (!localize(loc, refiner, m, sample(others_of(groups, per, g), f, &rng),
                                  *lab[groups[g][0]], &rng, &t)) {
                        row.trials++;
                        row.wild++;     // no answer counts as a wild error
                        continue;
                    }
                    row.trials++;
                    if (t.error_mm > WILD_MM)
                        row.wild++;
                    else
                        tame.push_back(t.error_mm);
                }
            }
            row.tame_mean_mm = mean(tame);
            row.tame_sigma_mm = sigma(tame);
            progress("table1: %-8s %-8s %2d mm  %d/16: wild %5.1f %%  tame %5.1f +- %5.1f mm  (%d trials)",
                     m.name.c_str(), prior ? "prior" : "no prior", raster, f,
                     100.0 * row.wild / row.trials,
                     row.tame_mean_mm, row.tame_sigma_mm, row.trials);
            rows.push_back(row);
        }
        hl_refine_destroy(refiner);
        hl_loc_destroy(loc);
    }
    if (ctx.figures && m.name == "improved" && prior)
        draw_figures(lab, groups, per, m, ctx);
    return rows;
}

}  // namespace hlexp
