/*
 * sonar_study.c - hl-sonar-study: where the pseudo-sonar ring's error comes from, on a
 * real building (docs/results/real-buildings.md, "Where the sonar's error goes").
 *
 *   hl-sonar-study echo SONAR.lcmlog LASER.lcmlog [KEY=VALUE ...]
 *       each pseudo-sonar reading, prepared as the tracker prepares it (echo bearings,
 *       normals), against the laser scan it was made from: the true echo is the nearest
 *       laser return in the reading's 22-degree cone, the true normal that of the line
 *       through the laser returns within 3 beams and 300 mm of it. Prints one line:
 *         echo readings=N bearing_median_deg=X bearing_p90_deg=X point_median_mm=X
 *              point_p90_mm=X normal_median_deg=X normal_p90_deg=X normal_over30_pct=X
 *   hl-sonar-study oracle SONAR.lcmlog NPREV [KEY=VALUE ...]
 *       each scan localized (hl_slam_localize) against a map of the NPREV scans
 *       before it drawn at their TRUE poses, from the true pose before it moved by the
 *       odometry: the localizer's own precision, with no drift in the map. With WINDOW=W
 *       in the environment, the scan is localized with the W scans before it placed by
 *       the odometry (a multiscan, multiscan.h) against the NPREV scans before those.
 *       Prints one line:
 *         oracle scans=N failed=N heading_rms_deg=X position_rms_mm=X
 *                odometry_heading_rms_deg=X odometry_position_rms_mm=X
 *   hl-sonar-study truth LASER.lcmlog
 *       how well the ground truth itself agrees with the laser: each laser scan matched
 *       (corrmatch.h, +-150 mm and 3 degrees about its true pose) against the scan before
 *       it drawn at its true pose, and against the scan two before; the first match's
 *       answer against the true pose is the truth's disagreement with the laser from one
 *       scan to the next, and the two matches' triangle (one step and the next against
 *       the two at once) the matcher's own. Pairs whose three matches all score 0.8 or
 *       more count. Prints one line:
 *         truth pairs=N heading_rms_deg=X position_rms_mm=X triangle_heading_rms_deg=X
 *               triangle_position_rms_mm=X
 *   hl-sonar-study revisits LASER.lcmlog [GAP]
 *       how well the ground truth agrees with itself where the robot comes back: each laser
 *       scan matched (+-300 mm and 5 degrees about its true pose) against the scan at
 *       least GAP scans (default 300) before it whose true pose lies nearest, within
 *       0.5 m and 20 degrees, drawn at its true pose; the answer against the true pose is
 *       the truth's disagreement between the two visits (the local scatter that truth
 *       measures included). Matches scoring 0.8 or more count. Prints one line:
 *         revisits pairs=N heading_rms_deg=X position_rms_mm=X position_p90_mm=X
 *
 *   hl-sonar-study views SONAR.lcmlog LASER.lcmlog N GAP [odometry|truth] [SUPPORT]
 *       echo placement from several views: each reading's bearing within its cone from the
 *       contradictions of this scan's readings and of N earlier scans' (every GAP-th, N
 *       0..16, placed by the odometry or the true poses), and with SUPPORT > 0 the earlier
 *       views' range arcs through it (below); scored against the laser as echo does.
 *       Prints one line:
 *         views n=N gap=GAP poses=P support=S readings=N bearing_median_deg=X
 *               bearing_p90_deg=X point_median_mm=X point_p90_mm=X
 *
 * SONAR.lcmlog and LASER.lcmlog are houghloc-import-carmen's --input sonar and --input
 * laser logs of one building, read with the experiments' reader (dataset.hpp): both have
 * one scan per laser scan, in order, each with its true pose. The tracker's settings are the sonar-continuous profile's, then each KEY=VALUE
 * (hl_params_set). Exit status 0, 1 on an unreadable file, 2 on bad usage.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <algorithm>
#include <string>
#include <vector>

#include "dataset.hpp"

extern "C" {
#include "houghloc-internal/corrmatch.h"
}
#include "houghloc-internal/multiscan.h"
#include "houghloc-internal/params.h"
#include "houghloc-internal/slam_params.h"
#include "houghloc-internal/slam_search.h"
#include "houghloc/params.h"
#include "houghloc/slam.h"

#define CONE_BAM 2003           /* 11 degrees: the importer's cone */
#define PI 3.14159265358979323846

/* One import's scans, their odometry and true poses, in log order. */
struct run_log {
    std::vector<hl_scan_t> scans;
    std::vector<hl_pose_t> odometry, truth;
    int n = 0;
};

static int usage(void)
{
    fprintf(stderr, "usage: hl-sonar-study echo SONAR.lcmlog LASER.lcmlog [KEY=VALUE ...]\n"
                    "       hl-sonar-study oracle SONAR.lcmlog NPREV [KEY=VALUE ...]\n"
                    "       hl-sonar-study truth LASER.lcmlog\n"
                    "       hl-sonar-study revisits LASER.lcmlog [GAP]\n"
                    "       hl-sonar-study views SONAR.lcmlog LASER.lcmlog N GAP "
                    "[odometry|truth] [SUPPORT]\n");
    return 2;
}

static int read_log(const char *path, run_log *out)
{
    hlexp::Soundings all;
    std::string err;
    if (!hlexp::read_soundings(path, &all, &err)) {
        fprintf(stderr, "hl-sonar-study: %s\n", err.c_str());
        return 1;
    }
    for (const hlexp::Sounding *s : hlexp::on_channel(all, "SONAR")) {
        out->scans.push_back(s->msg.scan);
        out->odometry.push_back(s->msg.odometry);
        out->truth.push_back(s->truth);
    }
    out->n = (int)out->scans.size();
    return 0;
}

/* The q-quantile of @p v (sorted here). */
static double quantile(std::vector<double> &v, double q)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[(size_t)(q * (double)(v.size() - 1))];
}

/* The nearest laser return within the cone of @p bearing, or -1. */
static int true_echo(const hl_scan_t *laser, hl_bam_t bearing)
{
    int best = -1;
    for (uint32_t j = 0; j < laser->count; j++) {
        const hl_reading_t *l = &laser->readings[j];
        if (l->valid && abs(hl_bam_diff(l->bearing, bearing)) <= CONE_BAM &&
            (best < 0 || l->range_mm < laser->readings[best].range_mm))
            best = (int)j;
    }
    return best;
}

static void point(const hl_reading_t *r, double *x, double *y)
{
    double a = hl_bam_to_rad(r->bearing);
    *x = r->range_mm * cos(a);
    *y = r->range_mm * sin(a);
}

/* The normal (towards the sensor) of the line through the laser returns within 3 beams
 * and 300 mm of return @p at; false with fewer than 5 of them. */
static bool true_normal(const hl_scan_t *laser, int at, double *normal)
{
    double tx, ty, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    point(&laser->readings[at], &tx, &ty);
    int n = 0;
    for (int j = at - 3; j <= at + 3; j++) {
        if (j < 0 || j >= (int)laser->count || !laser->readings[j].valid)
            continue;
        double x, y;
        point(&laser->readings[j], &x, &y);
        x -= tx;
        y -= ty;
        if (hypot(x, y) > 300)
            continue;
        sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y, n++;
    }
    if (n < 5)
        return false;
    double mx = sx / n, my = sy / n;
    double along = 0.5 * atan2(2 * (sxy / n - mx * my), (sxx / n - mx * mx) - (syy / n - my * my));
    double nx = -sin(along), ny = cos(along);
    if (nx * tx + ny * ty > 0)
        nx = -nx, ny = -ny;
    *normal = atan2(ny, nx);
    return true;
}

static int study_echo(const hl_slam_params_t *sp, const run_log *sonar, const run_log *laser)
{
    std::vector<double> bearing, place, normal;
    hl_scan_t echoed, fitted;
    int over30 = 0;
    for (int k = 0; k < sonar->n && k < laser->n; k++) {
        const hl_scan_t *in = &sonar->scans[k];
        const hl_scan_t *ready = hl_slam_prepare(sp, in, &echoed, &fitted);
        for (uint32_t i = 0; i < ready->count; i++) {
            const hl_reading_t *r = &ready->readings[i];
            int t = r->valid ? true_echo(&laser->scans[k], in->readings[i].bearing) : -1;
            double n_true;
            if (t < 0 || abs(laser->scans[k].readings[t].range_mm - in->readings[i].range_mm) > 15 ||
                !true_normal(&laser->scans[k], t, &n_true))
                continue;
            const hl_reading_t *tr = &laser->scans[k].readings[t];
            double ex, ey, tx, ty;
            point(r, &ex, &ey);
            point(tr, &tx, &ty);
            bearing.push_back(abs(hl_bam_diff(r->bearing, tr->bearing)) * 360.0 / 65536);
            place.push_back(hypot(ex - tx, ey - ty));
            normal.push_back(fabs(remainder(hl_bam_to_rad(hl_reading_normal(r, 0)) - n_true,
                                            2 * PI)) * 180 / PI);
            over30 += normal.back() > 30;
        }
    }
    printf("echo readings=%d bearing_median_deg=%.2f bearing_p90_deg=%.2f point_median_mm=%.0f "
           "point_p90_mm=%.0f normal_median_deg=%.1f normal_p90_deg=%.1f normal_over30_pct=%.0f\n",
           (int)normal.size(), quantile(bearing, .5), quantile(bearing, .9), quantile(place, .5),
           quantile(place, .9), quantile(normal, .5), quantile(normal, .9),
           normal.empty() ? 0 : 100.0 * over30 / (double)normal.size());
    return 0;
}

/* Echo placement from several views (views): a ring reading's candidate bearings within
 * its cone, each scored by how much the readings of this scan and of N earlier ones
 * (every GAP-th, placed by the odometry or the truth) contradict an echo there: a
 * reading whose cone holds the candidate point nearer than its own range would have
 * heard it first ((excess / sigma)^2 / 2, capped at 8, sigma 10 mm + 1 %, as echo.h
 * scores one scan). With SUPPORT > 0 an earlier view's reading whose range arc passes
 * within 2 sigma of the point takes SUPPORT off (the arcs' intersection). The reading
 * goes to the middle of the least contradicted bearings (within 0.5). */
struct views_setup {
    int n, gap;
    bool truth;
    double support;
};

struct view {
    double x, y, theta;             /* the view's sensor in the scan's frame */
    const hl_scan_t *scan;
};

static double wrap_rad(double a)
{
    return remainder(a, 2 * PI);
}

/* The contradiction (less the support) of an echo at (px, py) of reading @p self. */
static double views_score(const std::vector<view> &vs, const hl_reading_t *self, double px,
                          double py, double support)
{
    const double half = hl_bam_to_rad(CONE_BAM);
    double score = 0;
    for (size_t v = 0; v < vs.size(); v++)
        for (uint32_t j = 0; j < vs[v].scan->count; j++) {
            const hl_reading_t *q = &vs[v].scan->readings[j];
            if (!q->valid || q == self)
                continue;
            double dx = px - vs[v].x, dy = py - vs[v].y, d = hypot(dx, dy);
            if (fabs(wrap_rad(atan2(dy, dx) - vs[v].theta - hl_bam_to_rad(q->bearing))) > half)
                continue;
            double z = (q->range_mm - d) / (10 + 0.01 * q->range_mm);
            if (support > 0 && v > 0 && fabs(z) < 2)
                score -= support;
            if (z > 0)
                score += fmin(8, z * z / 2);
        }
    return score;
}

static int study_views(const run_log *sonar, const run_log *laser, views_setup vp)
{
    const double half = hl_bam_to_rad(CONE_BAM), step = 0.5 * PI / 180;
    const int candidates = (int)lround(2 * half / step) + 1;
    const std::vector<hl_pose_t> &at = vp.truth ? sonar->truth : sonar->odometry;
    std::vector<double> bearing, place, score(candidates);
    for (int k = vp.n * vp.gap; k < sonar->n && k < laser->n; k++) {
        const hl_scan_t *in = &sonar->scans[k];
        std::vector<view> vs;
        for (int v = 0; v <= vp.n; v++) {
            hl_pose_t rel = hl_pose_between(at[k], at[k - v * vp.gap]);
            vs.push_back({ (double)rel.x_mm, (double)rel.y_mm, hl_bam_to_rad(rel.theta),
                           &sonar->scans[k - v * vp.gap] });
        }
        for (uint32_t i = 0; i < in->count; i++) {
            const hl_reading_t *r = &in->readings[i];
            int t = r->valid ? true_echo(&laser->scans[k], r->bearing) : -1;
            if (t < 0 || abs(laser->scans[k].readings[t].range_mm - r->range_mm) > 15)
                continue;
            double axis = hl_bam_to_rad(r->bearing);
            for (int c = 0; c < candidates; c++) {
                double psi = axis - half + c * step;
                score[c] = views_score(vs, r, r->range_mm * cos(psi), r->range_mm * sin(psi),
                                       vp.support);
            }
            double least = *std::min_element(score.begin(), score.end());
            int first = -1, last = -1;
            for (int c = 0; c < candidates; c++)
                if (score[c] <= least + 0.5) {
                    first = first < 0 ? c : first;
                    last = c;
                }
            double est = axis - half + (first + last) / 2.0 * step;
            const hl_reading_t *tr = &laser->scans[k].readings[t];
            double tb = hl_bam_to_rad(tr->bearing);
            bearing.push_back(fabs(wrap_rad(est - tb)) * 180 / PI);
            place.push_back(hypot(r->range_mm * cos(est) - tr->range_mm * cos(tb),
                                  r->range_mm * sin(est) - tr->range_mm * sin(tb)));
        }
    }
    printf("views n=%d gap=%d poses=%s support=%g readings=%d bearing_median_deg=%.2f "
           "bearing_p90_deg=%.2f point_median_mm=%.0f point_p90_mm=%.0f\n", vp.n, vp.gap,
           vp.truth ? "truth" : "odometry", vp.support, (int)bearing.size(),
           quantile(bearing, .5), quantile(bearing, .9), quantile(place, .5), quantile(place, .9));
    return 0;
}

static double sdeg(hl_bam_t a)
{
    return hl_bam_diff(a, 0) * 360.0 / 65536;
}

static int study_oracle(hl_slam_t *s, const hl_slam_params_t *sp, const run_log *sonar,
                        int nprev, int window)
{
    std::vector<hl_scan_t> ready(sonar->scans.size());
    hl_scan_t echoed, fitted, seen;
    hl_multiscan_t *ms = hl_multiscan_create(HL_MULTISCAN_MAX_SCANS, 100000, HL_BAM_HALF_TURN);
    if (!ms)
        return 1;
    for (int k = 0; k < sonar->n; k++)
        ready[k] = *hl_slam_prepare(sp, &sonar->scans[k], &echoed, &fitted);
    double h2 = 0, p2 = 0, oh2 = 0, op2 = 0;
    int m = 0, failed = 0;
    const hl_pose_t *odo = sonar->odometry.data(), *gt = sonar->truth.data();
    for (int k = nprev + window; k < sonar->n; k++) {
        hl_map_t *map = hl_slam_map(s);
        hl_map_clear(map);
        for (int j = k - window - nprev; j < k - window; j++)
            hl_map_add_scan(map, &ready[j], gt[j], NULL);
        hl_multiscan_clear(ms);
        for (int j = k - window; j < k; j++)
            hl_multiscan_push(ms, &ready[j], odo[j], gt[j], true);
        hl_multiscan_assemble(ms, &ready[k], odo[k], &seen);
        hl_pose_t predicted, pose;
        hl_loc_result_t loc;
        hl_pose_predict(gt[k - 1], odo[k - 1], odo[k], &predicted);
        double odh = sdeg((hl_bam_t)(predicted.theta - gt[k].theta));
        oh2 += odh * odh;
        op2 += pow(hypot(predicted.x_mm - gt[k].x_mm, predicted.y_mm - gt[k].y_mm), 2);
        if (hl_slam_localize(s, &seen, predicted, &loc, &pose) != HL_OK) {
            failed++;
            continue;
        }
        double dh = sdeg((hl_bam_t)(pose.theta - gt[k].theta));
        h2 += dh * dh;
        p2 += pow(hypot(pose.x_mm - gt[k].x_mm, pose.y_mm - gt[k].y_mm), 2);
        m++;
    }
    int all = m + failed;
    printf("oracle scans=%d failed=%d heading_rms_deg=%.3f position_rms_mm=%.1f "
           "odometry_heading_rms_deg=%.3f odometry_position_rms_mm=%.1f\n", m, failed,
           m ? sqrt(h2 / m) : 0, m ? sqrt(p2 / m) : 0, all ? sqrt(oh2 / all) : 0,
           all ? sqrt(op2 / all) : 0);
    hl_multiscan_destroy(ms);
    return 0;
}

/* Scan @p k matched against scan @p j drawn at its true pose, from its own true pose,
 * within @p reach_mm and @p turn_rad: the answer less the true pose (world frame, mm
 * and degrees); false unless it scores TRUTH_MIN_SCORE. */
#define TRUTH_MIN_SCORE 0.8
static bool match_truth(hl_corr_t *c, const run_log *l, int j, int k, double reach_mm,
                        double turn_rad, double err[3])
{
    static hl_corr_point_t map[HL_CORR_MAX_POINTS], query[HL_CORR_MAX_POINTS];
    const hl_pose_t *gt = l->truth.data();
    uint32_t n_map = hl_corr_points(&l->scans[j], hl_pg_from_pose(gt[j]), map, 0,
                                    HL_CORR_MAX_POINTS);
    uint32_t n_query = hl_corr_points(&l->scans[k], hl_pg_pose_t{ 0, 0, 0 }, query, 0,
                                      HL_CORR_MAX_POINTS);
    hl_corr_params_t p = { reach_mm, turn_rad, TRUTH_MIN_SCORE, 1, 0, 0 };
    hl_corr_result_t r;
    hl_pg_pose_t at = hl_pg_from_pose(gt[k]);
    if (!hl_corr_search(c, map, n_map, query, n_query, at, &p, &r) || !r.matched)
        return false;
    err[0] = r.pose.x - at.x;
    err[1] = r.pose.y - at.y;
    err[2] = remainder(r.pose.theta - at.theta, 2 * PI) * 180 / PI;
    return true;
}

static int study_truth(const run_log *laser)
{
    hl_corr_t *c = hl_corr_create();
    if (!c)
        return 1;
    std::vector<std::vector<double>> one(laser->n);
    std::vector<bool> ok(laser->n, false);
    double h2 = 0, p2 = 0, th2 = 0, tp2 = 0;
    int m = 0;
    for (int k = 1; k < laser->n; k++) {
        one[k].resize(3);
        ok[k] = match_truth(c, laser, k - 1, k, 150, 3 * PI / 180, one[k].data());
        double two[3];
        if (k < 2 || !ok[k] || !ok[k - 1] ||
            !match_truth(c, laser, k - 2, k, 150, 3 * PI / 180, two))
            continue;
        /* Scan k-1 to k and k-2 to k-1, added, against k-2 to k at once: the steps are a
         * few centimetres, so their errors add in the world frame. */
        double tx = one[k][0] + one[k - 1][0] - two[0], ty = one[k][1] + one[k - 1][1] - two[1];
        double th = one[k][2] + one[k - 1][2] - two[2];
        h2 += one[k][2] * one[k][2];
        p2 += one[k][0] * one[k][0] + one[k][1] * one[k][1];
        th2 += th * th;
        tp2 += tx * tx + ty * ty;
        m++;
    }
    printf("truth pairs=%d heading_rms_deg=%.3f position_rms_mm=%.1f triangle_heading_rms_deg=%.3f "
           "triangle_position_rms_mm=%.1f\n", m, m ? sqrt(h2 / m) : 0, m ? sqrt(p2 / m) : 0,
           m ? sqrt(th2 / m) : 0, m ? sqrt(tp2 / m) : 0);
    hl_corr_destroy(c);
    return 0;
}

/* The earlier scan, at least @p gap before scan @p k, whose true pose lies nearest k's,
 * within 500 mm and 20 degrees; -1 if none. */
static int revisited(const run_log *l, int k, int gap)
{
    const hl_pose_t *gt = l->truth.data();
    int best = -1;
    double best_d = 500;
    for (int j = 0; j + gap <= k; j++) {
        double d = hypot(gt[j].x_mm - gt[k].x_mm, gt[j].y_mm - gt[k].y_mm);
        if (d < best_d && fabs(sdeg((hl_bam_t)(gt[j].theta - gt[k].theta))) < 20) {
            best_d = d;
            best = j;
        }
    }
    return best;
}

static int study_revisits(const run_log *laser, int gap)
{
    hl_corr_t *c = hl_corr_create();
    if (!c)
        return 1;
    std::vector<double> position;
    double h2 = 0, p2 = 0;
    for (int k = gap; k < laser->n; k++) {
        int j = revisited(laser, k, gap);
        double err[3];
        if (j < 0 || !match_truth(c, laser, j, k, 300, 5 * PI / 180, err))
            continue;
        double d = hypot(err[0], err[1]);
        position.push_back(d);
        h2 += err[2] * err[2];
        p2 += d * d;
    }
    size_t m = position.size();
    std::sort(position.begin(), position.end());
    printf("revisits pairs=%zu heading_rms_deg=%.3f position_rms_mm=%.1f position_p90_mm=%.1f\n",
           m, m ? sqrt(h2 / m) : 0, m ? sqrt(p2 / m) : 0, m ? position[m * 9 / 10] : 0);
    hl_corr_destroy(c);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "--help") == 0) {
        printf("usage: hl-sonar-study echo SONAR.lcmlog LASER.lcmlog [KEY=VALUE ...]\n"
               "       hl-sonar-study oracle SONAR.lcmlog NPREV [KEY=VALUE ...]\n"
               "       hl-sonar-study truth LASER.lcmlog\n"
               "       hl-sonar-study revisits LASER.lcmlog [GAP]\n"
               "       hl-sonar-study views SONAR.lcmlog LASER.lcmlog N GAP [odometry|truth] [SUPPORT]\n"
               "The pseudo-sonar ring against the laser it is made from (echo; views: echo\n"
               "bearings from N earlier scans too, N 0..16, every GAP-th), one\n"
               "sounding against a map at the true poses (oracle; WINDOW=W: a multiscan of\n"
               "the W scans before), or the ground truth against the laser (truth) and\n"
               "against itself where the robot comes back GAP scans or more later (revisits).\n"
               "Inputs: houghloc-import-carmen's logs of one building. See\n"
               "tools/lab/realeval/sonar_study.sh.\n");
        return 0;
    }
    if (argc >= 6 && argc <= 8 && strcmp(argv[1], "views") == 0) {
        char *end_n, *end_gap, *end_support = NULL;
        views_setup vp = { (int)strtol(argv[4], &end_n, 10), (int)strtol(argv[5], &end_gap, 10),
                           argc > 6 && strcmp(argv[6], "truth") == 0,
                           argc > 7 ? strtod(argv[7], &end_support) : 0 };
        if (*end_n || *end_gap || (end_support && *end_support) || vp.n < 0 || vp.n > 16 ||
            vp.gap < 1 || vp.gap > 100 || !(vp.support >= 0 && vp.support <= 100) ||
            (argc > 6 && !vp.truth && strcmp(argv[6], "odometry") != 0))
            return usage();
        run_log sonar, laser;
        return read_log(argv[2], &sonar) || read_log(argv[3], &laser)
                   ? 1 : study_views(&sonar, &laser, vp);
    }
    if (argc == 3 && strcmp(argv[1], "truth") == 0) {
        run_log laser;
        return read_log(argv[2], &laser) ? 1 : study_truth(&laser);
    }
    if ((argc == 3 || argc == 4) && strcmp(argv[1], "revisits") == 0) {
        char *end = NULL;
        long gap = argc == 4 ? strtol(argv[3], &end, 10) : 300;
        if ((end && *end) || gap < 1 || gap > 100000)
            return usage();
        run_log laser;
        return read_log(argv[2], &laser) ? 1 : study_revisits(&laser, (int)gap);
    }
    if (argc < 4)
        return usage();
    bool oracle = strcmp(argv[1], "oracle") == 0;
    if (!oracle && strcmp(argv[1], "echo") != 0)
        return usage();
    int first_key = 4, nprev = 0, window = 0;
    if (oracle && ((nprev = atoi(argv[3])) < 1 || nprev > 1000))
        return usage();
    if (oracle && getenv("WINDOW"))
        window = atoi(getenv("WINDOW"));
    if (window < 0 || window > HL_MULTISCAN_MAX_SCANS)
        return usage();
    hl_params_t params;
    hl_params_default(&params);
    hl_params_set(&params, "slam.profile", "sonar-continuous");
    for (int i = first_key; i < argc; i++) {
        char key[128];
        const char *eq = strchr(argv[i], '=');
        if (!eq || eq - argv[i] >= (long)sizeof key)
            return usage();
        memcpy(key, argv[i], (size_t)(eq - argv[i]));
        key[eq - argv[i]] = '\0';
        if (hl_params_set(&params, key, eq + 1) != HL_OK) {
            fprintf(stderr, "hl-sonar-study: %s\n", hl_params_error(&params));
            return 2;
        }
    }
    /* The scans are prepared once with the settings; the tracker that localizes them
     * takes them as they are (no second echo estimate or normals fit). */
    hl_params_t as_is = params;
    hl_params_set(&as_is, "slam.echo_bearings", "false");
    hl_params_set(&as_is, "slam.fit_normals", "false");
    hl_slam_t *s = hl_slam_create(&as_is);
    run_log sonar, laser;
    if (!s || read_log(argv[2], &sonar) || (!oracle && read_log(argv[3], &laser))) {
        hl_slam_destroy(s);
        return 1;
    }
    const hl_slam_params_t *sp = hl_params_slam_const(&params);
    int st = oracle ? study_oracle(s, sp, &sonar, nprev, window)
                    : study_echo(sp, &sonar, &laser);
    hl_slam_destroy(s);
    return st;
}
