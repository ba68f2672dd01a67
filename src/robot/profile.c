/* profile.c - the built-in robot profiles: where each sonar transducer points, and how
 * its raw ranges read in millimetres. */
#include "houghloc/sounder.h"

#include <string.h>

typedef struct profile_def {
    const char *name;
    int32_t transducers;
    int32_t spacing_bam;                         /* an even ring: k x this; else ... */
    int16_t degrees[HL_ROBOT_MAX_TRANSDUCERS];   /* ... these, ccw from ahead */
    int32_t gain_q16, offset_mm;                 /* 0, 0: the default calibration */
} profile_def_t;

static const profile_def_t profiles[] = {
    /* The paper's robot: an even ring of 16, transducer 0 ahead (paper, section 3). */
    { "bonnie", 16, 4096, { 0 }, 0, 0 },        /* 22.5 deg */
    /* A Pioneer 3: the front ring's eight, then the rear ring's eight, in ARCOS's
     * numbering (Pioneer 3 operations manual; ARIA's p3dx parameter file). The
     * transducers sit up to 0.2 m from the centre; the scan treats them as at the
     * centre, an error of under 2 degrees of bearing beyond 6 m and more up close. */
    { "pioneer3", 16, 0, { 90, 50, 30, 10, -10, -30, -50, -90,
                        -90, -130, -150, -170, 170, 150, 130, 90 }, 0, 0 },
    /* houghloc-sim's default robot: bonnie's ring, its raw values off by the linear
     * calibration `hl-calibrate --simulate` fits to the simulated transducers
     * (mm = 1.07 x raw - 35), so that a daemon pointed at the simulator needs no
     * calibration keys. */
    { "houghloc-sim", 16, 4096, { 0 }, 70124, -35 },
};

hl_status_t hl_robot_profile_find(const char *name, hl_robot_profile_t *out)
{
    if (!name || !out)
        return HL_ERR_ARG;
    for (size_t i = 0; i < sizeof profiles / sizeof profiles[0]; i++) {
        const profile_def_t *d = &profiles[i];
        if (strcmp(name, d->name) != 0)
            continue;
        memset(out, 0, sizeof *out);
        strncpy(out->name, d->name, sizeof out->name - 1);
        out->transducers = d->transducers;
        for (int32_t k = 0; k < d->transducers; k++) {
            int32_t bam = d->spacing_bam ? k * d->spacing_bam : d->degrees[k] * 65536 / 360;
            out->bearing[k] = (hl_bam_t)bam;
        }
        hl_calib_default(&out->calib);
        if (d->gain_q16) {
            out->calib.gain_q16 = d->gain_q16;
            out->calib.offset_mm = d->offset_mm;
        }
        return HL_OK;
    }
    return HL_ERR_ARG;
}
