/*
 * carmen_scan.h - one FLASER line's beams as a houghloc scan: every beam a reading
 * (laser), or a pseudo-sonar ring (sonar). Private to tools/carmen.
 *
 * Beams (carmen_beams_t): the first at -F/2 in the robot frame, F the field of view, and
 * the next ones a step apart. A FLASER line does not say its step; CARMEN's own reader
 * of it (carmen_string_to_robot_laser_message_orig, carmen_laser_guess_angle_increment)
 * takes the SICK's: 1 degree for 180 or 181 beams, 0.5 for 360 or 361, 0.25 for 400 or
 * 401, the 180- and 360-beam scans ending a step short of +F/2 ("last beam ignored").
 * The step is the log's laser_front_laser_resolution PARAM when it has one, else that
 * SICK step when it fits F (n - 1 or n steps), else F / (n - 1); with --fov-deg the n
 * beams are spread evenly across it, the last at +F/2. Spreading 180 beams evenly over
 * 180 degrees instead stretches a scan by half a degree at its edges (44 mm at 5 m),
 * which bends every wall the robot sees from the side. The log's pose fields are the
 * laser's pose, so the readings' origin is the laser and no mounting offset is applied.
 *
 * Each beam's range r (metres) is one of:
 *   no return  r >= no_return_m (49.9 m: the 50, 81.83, 81.91 m values of the logs), or
 *              r == the log's maximum when that is its no-return value (sentinel), or
 *              r == 0 (a reading some lasers give for "nothing");
 *   beyond     a return whose millimetres do not fit a reading (> 32767 mm): it cannot
 *              be written, and is counted;
 *   valid      0 < round(r * 1000) <= 32767 mm.
 *
 * Pseudo-sonar: readings every 2.8125 degrees (512 BAM, the paper's ring spacing)
 * centred on the field of view: N = floor(F / 2.8125 deg) readings (64 for 180
 * degrees, 128 for a full turn), reading j at (j - (N - 1) / 2) * 2.8125 deg, each the
 * nearest valid beam within +-11 degrees of its bearing (a 22-degree cone, the paper's
 * "cone of about 22 degrees"), at the cone's bearing: a sonar cannot tell where in its
 * cone the echo came from. A cone with no valid beam is an invalid reading (no echo).
 */
#ifndef HOUGHLOC_TOOLS_CARMEN_SCAN_H
#define HOUGHLOC_TOOLS_CARMEN_SCAN_H

#include <stdbool.h>
#include <stdint.h>

#include "carmen_log.h"
#include "houghloc/scan.h"

#define CARMEN_NO_RETURN_M 49.9
#define CARMEN_SONAR_STEP_BAM 512           /* 2.8125 degrees */
#define CARMEN_SONAR_STEP_DEG 2.8125
#define CARMEN_SONAR_HALF_CONE_DEG 11.0

typedef enum carmen_input {
    CARMEN_INPUT_LASER = 0,
    CARMEN_INPUT_SONAR,
} carmen_input_t;

/** How a log's ranges are read (decided once per log, see carmen_import). */
typedef struct carmen_ranges {
    double no_return_m;         /* ranges >= this are no return */
    bool has_sentinel;          /* ranges == sentinel_m are no return too */
    double sentinel_m;
} carmen_ranges_t;

typedef enum carmen_beam {
    CARMEN_BEAM_VALID = 0,
    CARMEN_BEAM_NO_RETURN,
    CARMEN_BEAM_BEYOND,
} carmen_beam_t;

/** Beam counts, added to by carmen_make_scan. */
typedef struct carmen_counts {
    long valid, no_return, beyond;      /* input beams */
    long readings, readings_valid;      /* output readings */
} carmen_counts_t;

/** Classifies range @p r_m (finite, >= 0); @p mm gets its millimetres when valid. */
carmen_beam_t carmen_classify(const carmen_ranges_t *cfg, double r_m, int32_t *mm);

/** Where a log's beams point (decided once per log, see carmen_import). */
typedef struct carmen_beams {
    double fov_deg;             /* F: the first beam at -F/2 */
    double res_deg;             /* the step between beams; 0: by the scan's beam count */
    bool spread;                /* n beams evenly across F (--fov-deg), res_deg unused */
} carmen_beams_t;

/** The SICK's step for @p n beams (CARMEN's guess) when n or n - 1 of them fill
 *  @p fov_deg, else 0. */
double carmen_sick_step_deg(int n, double fov_deg);

/** Degrees between beams of a scan of @p n beams (n >= 2; 0 for a log of mixed counts,
 *  whose step is then not one), the first at -fov/2; @p from (may be NULL) gets what
 *  set it, as the import's summary names it. */
double carmen_beam_step_deg(const carmen_beams_t *g, int n, const char **from);

/** Readings of the pseudo-sonar ring over @p fov_deg: floor(fov / 2.8125), 0 when the
 *  field of view is narrower than one step. */
int carmen_sonar_readings(double fov_deg);

/**
 * Fills @p out with the readings of @p f (nbeams >= 2), its beams pointing as @p g says
 * (0 < fov <= 360), in mode @p mode, adding to @p counts (may be NULL).
 * @return HL_OK; HL_ERR_CAPACITY when the laser has more than HL_SCAN_MAX_READINGS
 *         beams, or the ring would (fov > 360); HL_ERR_ARG on NULL.
 */
hl_status_t carmen_make_scan(const carmen_flaser_t *f, const carmen_beams_t *g, carmen_input_t mode,
                             const carmen_ranges_t *cfg, hl_scan_t *out, carmen_counts_t *counts);

#endif
