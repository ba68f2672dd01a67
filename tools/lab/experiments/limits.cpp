// limits.cpp - see limits.hpp.
#include "limits.hpp"

#include <algorithm>
#include <cmath>

#include "sonar.hpp"
#include "world.hpp"
#include "stats.hpp"

namespace hlexp {

namespace {

const double WILD_MM = 500.0;
const double NONE = std::nan("");   // not measured by this row

// Capped Gaussian misfit of a sounding at (x, y, th) against the exact first-echo model:
// each reading against the echo the simulated sonar would return from the true world.
double exact_misfit(const hlsim::World &w, const hlsim::SonarParams &sp, const hl_scan_t &scan,
                    const double pose[3])
{
    double cost = 0;
    for (uint32_t i = 0; i < scan.count; i++) {
        const hl_reading_t &r = scan.readings[i];
        if (!r.valid)
            continue;
        double e = hlsim::sonar_first_echo(w, sp, hlsim::Vec2(pose[0], pose[1]),
                                           pose[2] + hl_bam_to_rad(r.bearing));
        double z = (r.range_mm - e) / (sp.noise_sigma_mm + sp.noise_frac * r.range_mm);
        cost += e < 0 ? 2.0 : std::min(2.0, 0.5 * z * z);
    }
    return cost;
}

// The exact model's best pose near @p start: compass search, steps halving to 1 mm.
hl_pose_t exact_fit(const hlsim::World &w, const hlsim::SonarParams &sp, const hl_scan_t &scan,
                    hl_pose_t start)
{
    double pose[3] = { double(start.x_mm), double(start.y_mm), hl_bam_to_rad(start.theta) };
    double step[3] = { 40.0, 40.0, 0.02 };
    double best = exact_misfit(w, sp, scan, pose);
    while (step[0] >= 1.0) {
        bool better = false;
        for (int d = 0; d < 3; d++) {
            for (double sign : { -1.0, 1.0 }) {
                double trial[3] = { pose[0], pose[1], pose[2] };
                trial[d] += sign * step[d];
                double c = exact_misfit(w, sp, scan, trial);
                if (c < best) {
                    best = c;
                    std::copy(trial, trial + 3, pose);
                    better = true;
                }
            }
        }
        if (!better)
            for (double &s : step)
                s /= 2;
    }
    return { static_cast<hl_mm_t>(std::lround(pose[0])), static_cast<hl_mm_t>(std::lround(pose[1])),
             hl_bam_from_rad(pose[2]) };
}

double heading_error_deg(hl_pose_t a, hl_pose_t b)
{
    return hl_bam_diff(a.theta, b.theta) * 360.0 / 65536.0;
}

LimitsRow exact_model(const std::vector<const Sounding *> &soundings, const hlsim::World &w,
                      const std::string &what)
{
    hlsim::SonarParams sp;
    LimitsRow row{ what, 0, 0, 0, 0, 0 };
    std::vector<double> pos, head;
    for (const Sounding *s : soundings) {
        hl_pose_t start = s->truth;
        start.x_mm += 60;
        start.y_mm -= 60;
        start.theta = static_cast<hl_bam_t>(start.theta + hl_bam_from_deg(1.7));
        hl_pose_t found = exact_fit(w, sp, s->msg.scan, start);
        double e = distance_mm(found, s->truth);
        row.trials++;
        if (e > WILD_MM) {
            row.wild++;
            continue;
        }
        pos.push_back(e);
        head.push_back(heading_error_deg(found, s->truth));
    }
    row.pos_mean_mm = mean(pos);
    row.heading_mean_deg = mean(head);
    row.heading_sigma_deg = sigma(head);
    progress("limits: %s: %.1f mm, heading %.2f +- %.2f deg (%d soundings)", what.c_str(),
             row.pos_mean_mm, row.heading_mean_deg, row.heading_sigma_deg, row.trials);
    return row;
}

// A deep copy of @p in with every reading that echoed from a surface moved to the bearing
// of the point it echoed from, as the simulator's cone finds it from the true pose.
// Readings whose range does not match a surface echo (bounces, garbage) keep their axis.
Soundings with_true_bearings(const Soundings &in, const hlsim::World &w)
{
    hlsim::SonarParams sp;
    Soundings out;
    for (const auto &s : in) {
        out.push_back(std::make_unique<Sounding>(*s));
        if (!s->has_truth)
            continue;
        hl_scan_t &scan = out.back()->msg.scan;
        const double th = hl_bam_to_rad(s->truth.theta);
        const hlsim::Vec2 at(s->truth.x_mm, s->truth.y_mm);
        for (uint32_t i = 0; i < scan.count; i++) {
            hl_reading_t &r = scan.readings[i];
            hlsim::Hit hit;
            double e = hlsim::sonar_first_echo(w, sp, at, th + hl_bam_to_rad(r.bearing), &hit);
            if (!r.valid || e < 0 || std::fabs(e - r.range_mm) > 150.0)
                continue;
            hlsim::Vec2 d = hit.point - at;
            r.bearing = hl_bam_from_rad(std::atan2(d.y, d.x) - th);
        }
    }
    return out;
}

}  // namespace

std::vector<LimitsRow> run_limits(const LimitsInput &in, const hlsim::World &w,
                                  const Mode &improved, const Context &ctx)
{
    std::vector<LimitsRow> rows;
    if (in.lab)
        rows.push_back(exact_model(on_channel(*in.lab, "SONAR"), w,
                                   "exact model, lab28 soundings"));
    if (in.orientation)
        rows.push_back(exact_model(on_channel(*in.orientation, "SONAR_TEST"), w,
                                   "exact model, orientation test soundings"));

    Mode m = improved;
    m.name = "oracle";              // in the progress lines
    m.slam.echo_bearings = false;   // the bearings are already the true ones
    Context quiet = ctx;
    quiet.figures = false;
    if (in.lab) {
        Soundings lab = with_true_bearings(*in.lab, w);
        for (const Table1Row &t : run_table1(lab, m, quiet))
            if (t.raster_mm == 24 && t.fraction16 >= 2)
                rows.push_back({ "perfect echo bearings, Table 1, " +
                                     std::to_string(t.fraction16) + "/16, 24 mm (tame mean)",
                                 t.trials, t.wild, t.tame_mean_mm, NONE, NONE });
    }
    if (in.orientation) {
        Soundings log = with_true_bearings(*in.orientation, w);
        OrientationRow o = run_orientation(log, m, quiet);
        rows.push_back({ "perfect echo bearings, orientation", o.trials, 0, NONE, o.mean_deg,
                         o.sigma_deg });
    }
    if (in.tour) {
        Soundings tour = with_true_bearings(*in.tour, w);
        std::vector<CombinedRow> c = run_combined(tour, m, quiet, false);
        if (!c.empty())
            rows.push_back({ "perfect echo bearings, combined tour (RMSE)", c[0].stops,
                             c[0].wild_accepted, c[0].rmse_mm, NONE, NONE });
    }
    return rows;
}

}  // namespace hlexp
