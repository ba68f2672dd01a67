/*
 * params_table.c - every setting of the tracker, once: its key, type, level, range,
 * default and one line of help (params.h); the profiles, presets of them; and the keys
 * that are settings no more, with the constant each is fixed at (its reason stands by the
 * constant). houghlocd's configuration passes its [slam], [localize], [echo], [normals]
 * and [reloc] keys here unchanged, and prints them in this order.
 *
 * Why the defaults are what they are, and what each profile's values were measured on:
 * docs/design/expert-keys.md and the pages it points to.
 */
#include <stddef.h>

#include "houghloc-internal/closure.h"
#include "houghloc-internal/params.h"

#define STR_(x) #x
#define STR(x) STR_(x)

#define FIELD(f) offsetof(hl_slam_params_t, f)

/* A number of [lo, hi] (or also 0, off, with the _OR_0 forms), written once: the table
 * enforces it and shows it as text. */
#define NUM(key, type, level, store, field, lo, hi, dflt, help) \
    { { key, type, level, #lo ".." #hi, dflt, help }, store, FIELD(field), lo, hi, false }
#define NUM_OR_0(key, type, level, store, field, lo, hi, dflt, help) \
    { { key, type, level, "0 or " #lo ".." #hi, dflt, help }, store, FIELD(field), lo, hi, true }
#define INT(key, level, store, field, lo, hi, dflt, help) \
    NUM(key, HL_PARAM_INT, level, HL_PARAM_STORE_##store, field, lo, hi, dflt, help)
#define INT_OR_0(key, level, store, field, lo, hi, dflt, help) \
    NUM_OR_0(key, HL_PARAM_INT, level, HL_PARAM_STORE_##store, field, lo, hi, dflt, help)
#define REAL(key, level, field, lo, hi, dflt, help) \
    NUM(key, HL_PARAM_REAL, level, HL_PARAM_STORE_DOUBLE, field, lo, hi, dflt, help)
#define DEG(key, level, field, lo, hi, dflt, help) \
    NUM(key, HL_PARAM_DEG, level, HL_PARAM_STORE_BAM, field, lo, hi, dflt, help)
#define FLAG(key, level, field, dflt, help) \
    { { key, HL_PARAM_BOOL, level, "true or false", dflt, help }, HL_PARAM_STORE_BOOL, \
      FIELD(field), 0, 0, false }
/* A key fixed at @p value (a constant's text), with what replaces it (or NULL). */
#define FIXED(key, type, value, instead) \
    { { key, type, HL_PARAM_FIXED, NULL, value, instead }, HL_PARAM_STORE_NONE, 0, 0, 0, false }

#define O HL_PARAM_OPERATOR
#define E HL_PARAM_EXPERT
#define S HL_PARAM_STUDY

_Static_assert(HL_MAP_MAX_CAPACITY == 1048576, "slam.map_capacity's range");
_Static_assert(HL_CLOSURE_MAX_STOPS == 4096, "slam.closure_stops' range");
_Static_assert(HL_LOC_MAX_CELLS == 67108864, "the rasters' ranges");
_Static_assert(HL_SCAN_MAX_READINGS == 1024, "slam.closure_match_readings' range");
_Static_assert(HL_RELOC_MAX_SCANS == 4 && HL_RELOC_MAX_HEADINGS == 64 &&
               HL_RELOC_MAX_HYPOTHESES == 64, "the global search's ranges");

const hl_param_entry_t hl_param_table[] = {
    /* ---- [slam]: the online cycle and the map ---- */
    { { "slam.profile", HL_PARAM_PRESET, O, "sonar-stops, sonar-continuous, laser or paper",
        "sonar-stops",
        "the sensor's preset, applied before every other key: sonar-stops (a sonar ring "
        "sounded at stops, the paper's), sonar-continuous, laser, or paper (the paper's "
        "method alone) (--print-profile)" },
      HL_PARAM_STORE_NONE, 0, 0, 0, false },
    INT("slam.map_capacity", O, U32, map_capacity, 1, 1048576, "1500",
        "vectors kept, the one bound on the map (the localizer is made for as many); new "
        "ones beyond it are culled at random (paper: 1500)"),
    INT("slam.map_per_place", E, U32, map_per_place, 0, 1000, "0",
        "at most this many vectors of one place (map_round_places) seen from one side (a "
        "new one replaces one at random); 0: no bound (paper)"),
    INT("slam.map_square_mm", E, I32, map_square_mm, 10, 1000, "50",
        "the square whose area map_per_place's place has"),
    FLAG("slam.map_round_places", E, map_round_places, "true",
         "map_per_place's place is the disc of the square's area about a new vector, facing "
         "within 22.5 degrees (false: the map frame's square, seen from one side)"),
    INT("slam.cull_choices", E, U32, cull_choices, 1, 64, "1",
        "a full map drops the least confirmed of this many vectors drawn at random (a new "
        "vector confirms old ones near it facing alike); 1: uniform (paper)"),
    FLAG("slam.cull_crowded", S, cull_crowded, "false",
         "with cull_choices > 1 and map_per_place: drop the most crowded of them instead, "
         "spreading the map over every surface seen"),
    INT_OR_0("slam.crowd_square_mm", S, I32, crowd_square_mm, 10, 1000, "0",
             "the crowding cull counts a vector's crowd in squares this wide (0: its "
             "map_square_mm square and the 8 around it)"),
    INT("slam.seed", E, U64, seed, 0, 9007199254740992, "1",
        "seeds the culling (compare designs over several: a building's error moves with it)"),
    REAL("slam.heading_gain", S, heading_gain, 0, 1, "1",
         "the part of a localization's heading correction taken (the rest stays with the "
         "odometry); 1: all"),
    REAL("slam.wall_gain", E, wall_gain, 0, 1, "0",
         "the building's walls run square to each other: each accepted scan's heading is "
         "turned this part of the way to the nearest that puts its walls square to the "
         "map's (0: off)"),
    FLAG("slam.guarded", E, guarded, "true",
         "reject implausible localizations instead of adding them to the map"),
    FLAG("slam.interpolate", E, interpolate, "true", "sub-cell peak interpolation"),
    FLAG("slam.use_prior", E, use_prior, "true", "weigh votes by the odometry prior"),
    INT("slam.window_mm", E, I32, window_mm, 0, 1000000, "1000",
        "half-width of the search around the prediction; 0: the whole map"),
    FLAG("slam.echo_bearings", E, echo_bearings, "true",
         "move readings to their estimated echo bearings (sonar; off for a thin beam)"),
    FLAG("slam.fit_normals", E, fit_normals, "false",
         "give each reading its surface's normal from a line through its neighbours (a "
         "laser; normals.*)"),
    FLAG("slam.refine", E, refine, "true", "polish the Hough pose by point-to-line fit"),
    FLAG("slam.refine_heading", E, refine_heading, "true", "... in heading too"),
    FLAG("slam.close_loops", E, close_loops, "false",
         "loop closure: match each stop against the earlier stops near it and fit all stops "
         "to the matches, moving the map (not in the paper)"),
    INT("slam.closure_stops", E, U32, closure_stops, 2, 4096, "256",
        "... the stops it remembers (a fit of the synthetic worst case takes about 0.02 s "
        "at 256, 4 s at 4096: docs/results/pose-graph-solver.md)"),
    INT("slam.keyframe_mm", E, I32, keyframe_mm, 0, 100000, "0",
        "... a mapped scan is a stop of its own (a node of the fit) when the robot has moved "
        "this far (or turned 20 degrees) since the last stop (0: every scan is a stop)"),
    FLAG("slam.closure_correlative", E, closure_correlative, "false",
         "... match a stop by a correlative search of a region growing with the path since the "
         "last match, taken when unambiguous and two agree (false: the vote within 0.5 m)"),
    REAL("slam.closure_match_weight", E, closure_match_weight, 0.001, 1, "1",
         "... a match counts this share of a step in the fit (1: as much)"),
    INT("slam.closure_matches_per_scan", E, U32, closure_matches_per_scan, 0, 16, "0",
        "... seek this many of a stop's matches a scan, in the scans after it, then fit in "
        "the next (0: all at once, in the scan that made the stop)"),
    INT("slam.closure_match_readings", E, U32, closure_match_readings, 0, 1024, "0",
        "... match a stop with at most this many of its readings, taken evenly through its "
        "scan (0: all)"),
    INT("slam.closure_redraw_mm", E, I32, closure_redraw_mm, 0, 1000, "0",
        "... with closure_redraw_readings, draw a fit only when it moves some stop more than "
        "this from where its vectors lie (0: every fit)"),
    INT("slam.closure_redraw_stop_mm", E, I32, closure_redraw_stop_mm, 0, 1000, "0",
        "... and draw again only the stops it moved more than this, the others' vectors "
        "staying as they lie (0: every stop)"),
    INT("slam.closure_redraw_readings", E, U32, closure_redraw_readings, 0, 100000000, "0",
        "... after a fit, draw the map again aside, about this many readings a scan, and "
        "put it in place when done (0: at once, in the scan that fitted)"),
    FLAG("slam.square_walls", E, square_walls, "false",
         "... and the building's walls run along the map frame's axes (turn the frame with "
         "start.heading_deg): each stop's readings tie its heading to the world"),
    INT("slam.multiscan_mm", S, I32, multiscan_mm, 0, 100000, "0",
        "sounding by motion: localize each scan with the readings of the last this much "
        "travel, placed by the odometry, and draw them into the map only then (0: each scan "
        "alone)"),
    DEG("slam.multiscan_deg", S, multiscan_turn, 0, 180, "90", "... or this much turning"),
    INT("slam.long_drive_mm", E, I32, long_drive_mm, 0, 1000000, "0",
        "after a drive this long since the last scan, also localize from the drive turned "
        "+-6 and +-12 degrees about its start (odometry's heading drift swings it) and keep "
        "what the judge prefers; 0: off"),
    /* The LOST state is on: the global search answers wrong on at most 1 % of the kidnap
     * trials of every row (docs/results/relocalization.md), so that a robot moved while
     * the program was down, or carried while it ran, is found rather than driven from
     * where it was. The watch searches every scan tracking is in doubt about (after a
     * restart until a search confirms the pose, a rejected one, one matched far worse
     * than the recent ones) and every 10th scan besides (about 30 ms a search against
     * 1 ms of tracking; the continuous profiles turn it off). */
    INT("slam.lost_after", O, I32, lost_after, 0, 1000000, "2",
        "doubtful scans in a row (rejected, or matched far worse than recent ones) that make "
        "the tracker LOST: each scan then searches the whole map; 0: never"),
    INT("slam.search_every", O, I32, search_every, 0, 1000000, "10",
        "while tracking, also search the whole map every this many scans and on every scan "
        "tracking is in doubt about, to notice a robot carried away; 0: never"),

    /* ---- [localize]: the Hough search ---- */
    INT("localize.cell_mm", E, I32, loc.cell_mm, 1, 1000, "24",
        "xy raster cell (the paper: 47 and 24)"),
    /* The spread of echo-placed readings: about 40 mm of range noise and a few degrees
     * of bearing; 36 mm gave 512 against 328 mm tour RMSE over 24 seeds. */
    INT("localize.blur_sigma_mm", E, I32, loc.blur_sigma_mm, 0, 1000, "60",
        "xy vote blur; 0: none"),
    INT("localize.prior_sigma_mm", E, I32, loc.prior_sigma_mm, 1, 1000000, "300",
        "odometry prior's spread in position"),
    /* Loose on purpose: odometry drifts in heading, and a tight prior pins the estimate to
     * that drift, which the map then inherits (docs/results/experiments.md). */
    DEG("localize.prior_sigma_deg", E, loc.prior_sigma_theta, 0.01, 180, "15",
        "odometry prior's spread in heading"),
    INT("localize.max_cells", E, U32, loc.max_cells, 1, 67108864, "1048576",
        "vote raster cells allocated at start (4 bytes + 2 bytes each)"),
    INT("localize.reading_stride", E, U16, loc.reading_stride, 1, 64, "1",
        "only every k-th reading of a scan votes (the refinement uses all); 1: all"),
    /* A sparse map gains nothing, and 48 mm cost 20 % on the tours. */
    INT_OR_0("localize.group_mm", E, I32, loc.group_mm, 8, 1000, "0",
             "map vectors in one square this wide vote together from their centroid; 0: "
             "each alone (the paper)"),

    /* ---- [echo]: echo bearings (slam.echo_bearings) ---- */
    /* Not the 22-degree cone's 11: an echo must clear the receiver's threshold, and off
     * the axis the beam loses it; 7 degrees is about where a Polaroid-type piston's
     * two-way response is 12 dB down (docs/manual/houghloc-sim.md, "Echo model"). */
    DEG("echo.half_beam_deg", E, echo.half_beam, 1, 45, "7",
        "half the width an echo can come from (a Polaroid-type beam: 7; a hard 22-degree "
        "cone: 11)"),
    FLAG("echo.flank_normals", E, echo.flank_normals, "false",
         "a reading on a wall's flank echoes from its cone's edge and takes the wall's "
         "normal, through its neighbour's echo (for rings whose cones overlap)"),

    /* ---- [normals]: fitted normals (slam.fit_normals) ---- */
    FLAG("normals.keep_unfitted", E, normals.keep_unfitted, "false",
         "keep a reading with no surface line, square to its beam (the paper's tangent), "
         "instead of dropping it (true for tracking, false for the global search)"),
    /* min_points' top: 2 x HL_NORMALS_HALF_WINDOW + 1, the points of a window. */
    INT("normals.min_points", S, U16, normals.min_points, 3, 9, "4",
        "points a surface line needs, the reading included; fewer: the reading is dropped"),
    INT("normals.max_residual_mm", S, I32, normals.max_residual_mm, 1, 10000, "20",
        "RMS distance from the line above which the reading is on no surface (a corner)"),
    DEG("normals.max_tilt_deg", S, normals.max_tilt, 0.1, 89, "75",
        "drop readings of surfaces turned farther than this from square to the beam"),

    /* ---- [reloc]: the global search (docs/design/relocalization.md) ---- */
    INT("reloc.coarse_cell_mm", E, I32, reloc.coarse_cell_mm, 10, 1000, "100",
        "the global search's coarse raster cell (200 for buildings larger than a few rooms)"),
    INT("reloc.coarse_max_cells", E, U32, reloc.coarse_max_cells, 1, 67108864, "262144",
        "coarse raster cells allocated at start (10 bytes each); the map's bounding box "
        "must fit"),
    INT("reloc.scans", S, U16, reloc.scans, 1, 4, "3",
        "while lost, the global search takes this many of the robot's scans together, each "
        "kept 0.5 m or 30 degrees from the one before"),
    /* A sonar's normals agree with the map's almost as well at any heading (the lab: the
     * best window's correlation within 5 % of the worst's), so the true heading's window
     * ranks anywhere in the first 9 of 18: 12 windows found 5 points more than 8 on the
     * lab's held-out soundings at 1.3 times the time (docs/results/relocalization.md). */
    INT("reloc.headings", S, U16, reloc.headings, 1, 64, "12",
        "heading windows tried, best first by the normals' agreement (18 cover every "
        "heading)"),
    INT_OR_0("reloc.coarse_group_mm", S, I32, reloc.coarse_group_mm, 8, 1000, "0",
             "the coarse vote's map merged into squares this wide (localize.group_mm)"),
    INT("reloc.coarse_stride", S, U16, reloc.coarse_stride, 0, 64, "0",
        "the coarse votes come from every k-th reading only (a laser's hundreds); 0 or 1: all"),
    FLAG("reloc.coarse_vote_once", S, reloc.coarse_vote_once, "false",
         "each reading votes at most once into a coarse cell: votes count readings that fit, "
         "not pairs, so dense clutter does not outvote the right place"),
    INT("reloc.hypotheses", S, U16, reloc.hypotheses, 1, 64, "8",
        "the best coarse peaks searched again finely"),
    INT("reloc.verify_mm", S, I32, reloc.verify_mm, 1, 1000, "60",
        "a reading is explained by a map vector this close that faces the same way"),
    INT("reloc.verify_along_mm", S, I32, reloc.verify_along_mm, 1, 1000, "60",
        "... measured across the vector's surface; the reading may lie this far along it"),
    DEG("reloc.judge_gate_deg", S, reloc.judge_gate, 0, 180, "90",
        "... and was seen from within this angle of the reading's direction"),
    REAL("reloc.min_explained_pct", S, reloc.min_explained_pct, 0, 100, "35",
         "found only when the answer explains at least this share of the readings"),
    REAL("reloc.max_ratio", S, reloc.max_ratio, 0.01, 1, "0.7",
         "found when the runner-up explains at most this fraction of what the answer does; "
         "else ambiguous"),
    REAL("reloc.max_edge_ratio", S, reloc.max_edge_ratio, 0, 1, "0",
         "also found when readings favouring the runner-up are at most this share of those "
         "favouring the answer; 0: off"),

    /* ---- settings no more: each fixed at its constant ---- */
    FIXED("slam.mode", HL_PARAM_WORD, "improved", "the paper's method is slam.profile = paper"),
    FIXED("slam.confirm_mm", HL_PARAM_INT, STR(HL_MAP_CONFIRM_MM), NULL),
    FIXED("slam.search_theta", HL_PARAM_BOOL, "true", NULL),
    FIXED("slam.wild_mm", HL_PARAM_INT, STR(HL_SLAM_WILD_MM), NULL),
    FIXED("slam.min_confidence", HL_PARAM_REAL, STR(HL_SLAM_MIN_CONFIDENCE), NULL),
    FIXED("slam.min_votes", HL_PARAM_INT, STR(HL_SLAM_MIN_VOTES), NULL),
    FIXED("slam.min_peak_ratio", HL_PARAM_REAL, STR(HL_SLAM_MIN_PEAK_RATIO), NULL),
    FIXED("slam.lost_peak_ratio", HL_PARAM_REAL, STR(HL_SLAM_LOST_PEAK_RATIO), NULL),
    FIXED("slam.wall_axis_deg", HL_PARAM_DEG, STR(HL_SLAM_WALL_AXIS_DEG),
          "start.heading_deg turns the map frame onto the walls"),
    FIXED("slam.keyframe_deg", HL_PARAM_DEG, STR(HL_SLAM_KEYFRAME_DEG),
          "keyframes (slam.keyframe_mm) start after 20 degrees of turning"),
    FIXED("slam.long_drive_turn_deg", HL_PARAM_DEG, STR(HL_SLAM_DRIVE_TURN_DEG), NULL),
    FIXED("slam.long_drive_turns", HL_PARAM_INT, STR(HL_SLAM_DRIVE_TURNS), NULL),
    FIXED("localize.theta_step_deg", HL_PARAM_DEG, STR(HL_LOC_THETA_STEP_DEG), NULL),
    FIXED("localize.theta_half_steps", HL_PARAM_INT, STR(HL_LOC_THETA_HALF_STEPS), NULL),
    FIXED("localize.normal_gate_deg", HL_PARAM_DEG, STR(HL_LOC_NORMAL_GATE_DEG), NULL),
    FIXED("localize.blur_sigma_deg", HL_PARAM_DEG, STR(HL_LOC_BLUR_SIGMA_THETA_DEG), NULL),
    FIXED("localize.peak_separation_mm", HL_PARAM_INT, STR(HL_LOC_PEAK_SEPARATION_MM), NULL),
    FIXED("echo.step_deg", HL_PARAM_DEG, STR(HL_ECHO_STEP_DEG), NULL),
    FIXED("echo.noise_mm", HL_PARAM_INT, STR(HL_ECHO_NOISE_MM), NULL),
    FIXED("echo.noise_permille", HL_PARAM_INT, STR(HL_ECHO_NOISE_PERMILLE), NULL),
    FIXED("echo.cap", HL_PARAM_REAL, STR(HL_ECHO_CAP), NULL),
    FIXED("echo.tie", HL_PARAM_REAL, STR(HL_ECHO_TIE), NULL),
    FIXED("normals.half_window", HL_PARAM_INT, STR(HL_NORMALS_HALF_WINDOW), NULL),
    FIXED("normals.reach_mm", HL_PARAM_INT, STR(HL_NORMALS_REACH_MM), NULL),
    FIXED("refine.normal_radius_mm", HL_PARAM_INT, STR(HL_REFINE_NORMAL_RADIUS_MM), NULL),
    FIXED("refine.match_mm", HL_PARAM_INT, STR(HL_REFINE_MATCH_MM), NULL),
    FIXED("refine.huber_mm", HL_PARAM_INT, STR(HL_REFINE_HUBER_MM), NULL),
    FIXED("refine.max_shift_mm", HL_PARAM_INT, STR(HL_REFINE_MAX_SHIFT_MM), NULL),
    FIXED("refine.max_turn_deg", HL_PARAM_DEG, STR(HL_REFINE_MAX_TURN_DEG), NULL),
    FIXED("refine.iterations", HL_PARAM_INT, STR(HL_REFINE_ITERATIONS), NULL),
    FIXED("refine.min_matches", HL_PARAM_INT, STR(HL_REFINE_MIN_MATCHES), NULL),
    FIXED("reloc.heading_smooth_deg", HL_PARAM_DEG, STR(HL_RELOC_HEADING_SMOOTH_DEG), NULL),
    FIXED("reloc.coarse_theta_step_deg", HL_PARAM_DEG, STR(HL_RELOC_COARSE_THETA_STEP_DEG),
          NULL),
    FIXED("reloc.coarse_half_steps", HL_PARAM_INT, STR(HL_RELOC_COARSE_HALF_STEPS), NULL),
    FIXED("reloc.coarse_blur_mm", HL_PARAM_INT, STR(HL_RELOC_COARSE_BLUR_MM), NULL),
    FIXED("reloc.peaks_per_heading", HL_PARAM_INT, STR(HL_RELOC_PEAKS_PER_HEADING), NULL),
    FIXED("reloc.fine_window_mm", HL_PARAM_INT, STR(HL_RELOC_FINE_WINDOW_MM), NULL),
    FIXED("reloc.short_mm", HL_PARAM_INT, STR(HL_RELOC_SHORT_MM), NULL),
    FIXED("reloc.distinct_mm", HL_PARAM_INT, STR(HL_RELOC_DISTINCT_MM), NULL),
    FIXED("reloc.distinct_deg", HL_PARAM_DEG, STR(HL_RELOC_DISTINCT_DEG), NULL),
};

const size_t hl_param_table_len = sizeof hl_param_table / sizeof hl_param_table[0];

/* ---- the profiles ---------------------------------------------------------------------- */

/* Loop closure for a sensor that scans several times a second, should it be turned on
 * (slam.close_loops): keyframes, and its work a share a scan (docs/design/loop-closure.md). */
#define CONTINUOUS_CLOSURE \
    { "slam.keyframe_mm", "500", \
      "with loop closure: a stop of its own every 0.5 m (or 20 degrees) of a continuous " \
      "drive, the scans between joining it, rather than a stop a scan" }, \
    { "slam.closure_stops", "1024", \
      "... remembering 1,024 keyframes (500 m): each real building measured whole" }, \
    { "slam.closure_correlative", "true", \
      "... a keyframe matched by a correlative search of the region its drift allows: on " \
      "five real buildings better than the vote within 0.5 m on most" }, \
    { "slam.closure_matches_per_scan", "4", \
      "... and a stop's matches sought 4 a scan in the scans after it, its fit in the next" }, \
    { "slam.closure_redraw_readings", "50000", \
      "... and after a fit the map (a whole building's stops) drawn again aside, 50,000 " \
      "readings a scan (a few milliseconds), so that no scan waits for all of it" },

/* The LOST state off for a sensor that scans several times a second: lost, every scan
 * searches the whole map, 50-250 ms against a scan period of 100-250 ms, and the program
 * falls behind the sensor (the Flood trial's pseudo-sonar at 20x with the search on every
 * scan: 894 of 1,200 scans published, compute median 17 ms against 11 ms a scan); and the
 * search's settings that answer wrong on 1 % or fewer of a building's trials were measured
 * on maps made for the search (tools/lab/kidnap/laser-search.conf, sonar-search.conf), not
 * on the tracking maps these profiles make. A relocalization on demand still searches. */
#define LOST_OFF \
    { "slam.search_every", "0", \
      "no global search besides tracking (lost, every scan would search: more than a scan " \
      "period)" }, \
    { "slam.lost_after", "0", "... and no LOST state on doubtful scans" },

/* A sonar sounded at the laser's rate rather than at stops: the settings measured on the
 * pseudo-sonar ring of five real buildings (docs/results/real-buildings.md, "Pseudo-sonar"). */
static const hl_param_setting_t sonar_continuous[] = {
    { "localize.prior_sigma_mm", "100",
      "soundings centimetres apart: a tighter odometry prior in position ..." },
    { "localize.prior_sigma_deg", "5", "... and in heading" },
    { "echo.half_beam_deg", "11",
      "the nearest return anywhere in a hard 22-degree cone (half of it), not the 7 degrees "
      "of a Polaroid-type beam" },
    { "echo.flank_normals", "true",
      "... cones every few degrees overlap: a reading on a wall's flank gets the wall's "
      "normal, not its beam's (most readings of a moving ring are on flanks)" },
    { "slam.refine", "false",
      "the point-to-line polish moves a sonar sounding off the Hough peak: against a map "
      "drawn at the true poses it doubles one sounding's error on freiburg-079" },
    { "slam.map_capacity", "15000",
      "a map that holds whole floors, so that the robot finds the walls it passed minutes "
      "ago ..." },
    { "slam.map_per_place", "1",
      "... kept sparse: one vector of a round place (the disc of a 50 mm square's area "
      "about a new one, facing alike; a new one replaces it at random)" },
    { "slam.wall_gain", "0.1",
      "a ring's heading drifts a degree or so a scan between returns: a tenth of the way to "
      "walls square to the map's (a building's walls mostly are) each scan" },
    CONTINUOUS_CLOSURE
    { "slam.closure_match_readings", "256",
      "... a keyframe matched with 256 of its readings (up to 1,024 joined), which keeps a "
      "scan's matches within 50 ms" },
    { "slam.closure_redraw_mm", "25",
      "... and a fit drawn only once it has moved some stop 25 mm from where its vectors "
      "lie: most move the map less than its 50 mm squares, and a redraw is most of a "
      "scan's time" },
    { "reloc.coarse_cell_mm", "200",
      "maps of whole buildings (up to 46 x 45 m): the global search's coarse cell doubled, "
      "a quarter of the cells for as many answers" },
    { "reloc.coarse_max_cells", "1048576", "... and room for such a map drawn at drifted poses" },
    LOST_OFF
};

/* A laser scanner: the settings of all five real buildings (docs/results/real-buildings.md). */
static const hl_param_setting_t laser[] = {
    { "slam.map_capacity", "15000",
      "360 readings a scan: 1500 vectors hold a few seconds of them, 15,000 hold whole floors" },
    { "slam.map_per_place", "1",
      "at most 1 vector of a round place (the disc of a map_square_mm square's area about a "
      "new one, facing alike; a new one replaces it at random): with 2, intel slipped at "
      "some seeds" },
    { "slam.map_square_mm", "50", "... in 50 mm squares" },
    { "slam.window_mm", "500",
      "scans several times a second: odometry is off by centimetres between two, and a "
      "+-0.5 m window is plenty" },
    { "slam.echo_bearings", "false", "a thin beam: the echo lies on the beam's axis" },
    { "slam.fit_normals", "true",
      "a laser hears a wall at any angle: each reading takes the normal of a line through "
      "its neighbours" },
    { "normals.keep_unfitted", "true",
      "... and a reading on no line (a corner, clutter) stays square to its beam" },
    { "localize.reading_stride", "2",
      "every second reading votes, which pins the peak as well (the refinement fits all)" },
    { "localize.group_mm", "48",
      "the map stays dense along walls: vectors of one 48 mm square vote together" },
    CONTINUOUS_CLOSURE
    { "slam.closure_match_readings", "512",
      "... a keyframe matched with 512 of its readings (up to 1,024 joined), which keeps a "
      "scan's matches within 50 ms" },
    { "slam.closure_match_weight", "0.3",
      "... a match counting 0.3 of a step: the tracker's steps between keyframes are surer "
      "than a correlative match (full weight cost freiburg-101 its 0.042 m)" },
    { "slam.closure_redraw_stop_mm", "2",
      "... and a fit that moves few keyframes (most move a few recent ones) draws again "
      "only those moved over 2 mm: a scan's median 7 -> 4.5 ms on freiburg-079" },
    { "reloc.coarse_cell_mm", "200",
      "maps of whole buildings (up to 56 x 84 m): the global search's coarse cell doubled, "
      "a quarter of the cells" },
    { "reloc.coarse_max_cells", "2097152", "... and room for such a map drawn at drifted poses" },
    LOST_OFF
};

/* The paper's method (its sections 5-7): every localization extends the map, a global
 * search, the best cell, readings on their beam axes. The laboratory's experiments run it
 * as its "paper" mode. */
static const hl_param_setting_t paper[] = {
    { "localize.cell_mm", "47", "the coarser raster of the paper's Table 1" },
    { "localize.blur_sigma_mm", "50", "the paper gives no sigma: about one coarse cell" },
    { "localize.max_cells", "4194304",
      "room for global (x, y, theta) searches over a whole lab" },
    { "slam.guarded", "false", "every localization extends the map" },
    { "slam.use_prior", "false", "no odometry prior" },
    { "slam.interpolate", "false", "the best cell is the pose" },
    { "slam.window_mm", "0", "a global search over the map" },
    { "slam.echo_bearings", "false", "readings on their beam axes" },
    { "slam.refine", "false", "no refinement: the raster's answer stands" },
    { "slam.search_every", "0", "the paper has no global search besides the tracker's ..." },
    { "slam.lost_after", "0", "... and no LOST state" },
};

#define PRESET(name, summary, settings) \
    { name, summary, settings, sizeof settings / sizeof settings[0] }

const hl_param_preset_t hl_param_presets[] = {
    { "sonar-stops",
      "the paper's sonar ring, sounded at stops a metre or so apart: the compiled-in "
      "defaults", NULL, 0 },
    PRESET("sonar-continuous",
           "a sonar ring sounded several times a second while the robot moves",
           sonar_continuous),
    PRESET("laser", "a laser scanner: hundreds of thin beams several times a second", laser),
    PRESET("paper",
           "the paper's method alone: readings on their beam axes, 47 mm cells, a global "
           "search, no prior, no guard, no refinement", paper),
};

const size_t hl_param_presets_len = sizeof hl_param_presets / sizeof hl_param_presets[0];
