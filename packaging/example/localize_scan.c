/*
 * localize_scan.c - the houghloc core in a program of one's own: one sonar sounding
 * localized in a square room.
 *
 * The map is the four walls of a 4 m x 4 m room centred on the origin, as tangent
 * vectors (a surface point every 100 mm, its normal pointing into the room). The scan is
 * a ring of 128 readings taken at the true pose given on the command line (x and y in
 * mm, heading in degrees; default 400 -250 12). A tracker (slam.h) is given the walls as
 * its map and a guess 150 mm and 4 degrees off as its estimate, as odometry would give
 * it; it searches +-500 mm (slam.window_mm) and +-8.8 degrees around the guess, and the
 * program prints the pose it finds. Build it against an installed houghloc:
 *
 *     cc localize_scan.c $(pkg-config --cflags --libs houghloc) -o localize_scan
 */
#include <stdio.h>
#include <stdlib.h>

#include "houghloc/params.h"
#include "houghloc/slam.h"

#define HALF_MM 2000 /* the walls stand at x = +-HALF_MM and y = +-HALF_MM */

/* The distance from (x, y) along the world direction a to the nearest wall. */
static int32_t range_to_wall(int32_t x, int32_t y, hl_bam_t a)
{
    int64_t c = hl_cos(a), s = hl_sin(a), range = INT32_MAX;
    if (c != 0) {
        int64_t t = ((c > 0 ? HALF_MM : -HALF_MM) - x) * (int64_t)HL_TRIG_ONE / c;
        range = t < range ? t : range;
    }
    if (s != 0) {
        int64_t t = ((s > 0 ? HALF_MM : -HALF_MM) - y) * (int64_t)HL_TRIG_ONE / s;
        range = t < range ? t : range;
    }
    return (int32_t)range;
}

int main(int argc, char **argv)
{
    double truth[3] = { 400, -250, 12 };
    if (argc != 1 && argc != 4) {
        fprintf(stderr, "usage: localize_scan [X_MM Y_MM HEADING_DEG]\n");
        return 2;
    }
    for (int i = 1; i < argc; i++) {
        char *end;
        truth[i - 1] = strtod(argv[i], &end);
        if (end == argv[i] || *end != '\0') {
            fprintf(stderr, "localize_scan: '%s' is not a number\n", argv[i]);
            return 2;
        }
        double limit = i < 3 ? 1500 : 360; /* inside the room; a heading within a turn */
        if (!(truth[i - 1] >= -limit && truth[i - 1] <= limit)) {
            fprintf(stderr, "localize_scan: %s is outside -%.0f..%.0f\n", argv[i], limit, limit);
            return 2;
        }
    }
    hl_pose_t at = { (hl_mm_t)truth[0], (hl_mm_t)truth[1], hl_bam_from_deg(truth[2]) };

    static hl_vector_t walls[4 * (2 * HALF_MM / 100)];
    uint32_t n = 0;
    for (int32_t k = -HALF_MM + 50; k < HALF_MM; k += 100) {
        walls[n++] = (hl_vector_t){ HALF_MM, k, hl_bam_from_deg(180), 1000 };
        walls[n++] = (hl_vector_t){ -HALF_MM, k, hl_bam_from_deg(0), 1000 };
        walls[n++] = (hl_vector_t){ k, HALF_MM, hl_bam_from_deg(270), 1000 };
        walls[n++] = (hl_vector_t){ k, -HALF_MM, hl_bam_from_deg(90), 1000 };
    }

    static hl_scan_t scan;
    hl_scan_clear(&scan);
    for (int i = 0; i < 128; i++) {
        hl_bam_t bearing = (hl_bam_t)(i * (HL_BAM_PER_TURN / 128));
        hl_scan_add(&scan, bearing, range_to_wall(at.x_mm, at.y_mm, (hl_bam_t)(at.theta + bearing)),
                    (int8_t)i, true);
    }

    /* The tracker's settings by name (params.h): the window, no echo bearings (the scan's
     * rays are thin), no global search (the guess is good). */
    static const char *const settings[][2] = {
        { "slam.window_mm", "500" }, { "slam.echo_bearings", "false" },
        { "slam.search_every", "0" }, { "slam.lost_after", "0" },
    };
    hl_params_t params;
    hl_params_default(&params);
    for (size_t i = 0; i < sizeof settings / sizeof settings[0]; i++)
        if (hl_params_set(&params, settings[i][0], settings[i][1]) != HL_OK) {
            fprintf(stderr, "localize_scan: %s\n", hl_params_error(&params));
            return 1;
        }
    hl_slam_t *slam = hl_slam_create(&params);
    if (!slam) {
        fprintf(stderr, "localize_scan: %s\n", hl_status_str(HL_ERR_NOMEM));
        return 1;
    }
    /* The walls as the tracker's map, the guess as its estimate and odometry. */
    hl_pose_t guess = { at.x_mm + 150, at.y_mm - 100, (hl_bam_t)(at.theta + hl_bam_from_deg(4)) };
    hl_slam_state_t st;
    hl_slam_get_state(slam, &st);
    st.started = true;
    st.pose = st.odom = guess;
    hl_slam_step_t step;
    hl_status_t status = hl_slam_restore(slam, &st, walls, n);
    if (status == HL_OK)
        status = hl_slam_update(slam, &scan, guess, &step);
    hl_slam_destroy(slam);
    if (status != HL_OK || step.status != HL_SLAM_ACCEPTED) {
        fprintf(stderr, "localize_scan: %s\n",
                status != HL_OK ? hl_status_str(status) : "the localization was not accepted");
        return 1;
    }
    printf("pose x_mm=%d y_mm=%d heading_deg=%.2f confidence=%.2f\n", (int)step.pose.x_mm,
           (int)step.pose.y_mm, hl_bam_to_sdeg(step.pose.theta), hl_loc_confidence(&step.loc));
    return 0;
}
