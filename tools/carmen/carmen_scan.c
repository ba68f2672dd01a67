/* carmen_scan.c - FLASER beams -> hl_scan_t: laser readings or a pseudo-sonar ring. */
#include "carmen_scan.h"

#include <math.h>
#include <stddef.h>

carmen_beam_t carmen_classify(const carmen_ranges_t *cfg, double r_m, int32_t *mm)
{
    if (r_m <= 0.0 || r_m >= cfg->no_return_m || (cfg->has_sentinel && r_m == cfg->sentinel_m))
        return CARMEN_BEAM_NO_RETURN;
    long long v = llround(r_m * 1000.0);
    if (v > HL_RANGE_MAX_MM)
        return CARMEN_BEAM_BEYOND;
    if (v <= 0)     /* below half a millimetre: as good as nothing */
        return CARMEN_BEAM_NO_RETURN;
    *mm = (int32_t)v;
    return CARMEN_BEAM_VALID;
}

int carmen_sonar_readings(double fov_deg)
{
    /* the tolerance (a thousandth of a step) keeps csail's PARAM of 3.14159 rad, 179.9998
     * degrees, at the 64 readings of 180 degrees */
    return (int)floor(fov_deg / CARMEN_SONAR_STEP_DEG + 1e-3);
}

double carmen_sick_step_deg(int n, double fov_deg)
{
    double step = n == 180 || n == 181 ? 1.0 : n == 360 || n == 361 ? 0.5
                : n == 400 || n == 401 ? 0.25 : 0.0;
    double span = (n - 1) * step;
    /* n - 1 steps fill it, or n with the last beam dropped; a thousandth of a step for
     * a PARAM given in radians */
    bool fits = fabs(span - fov_deg) <= step * 1e-3 || fabs(span + step - fov_deg) <= step * 1e-3;
    return fits ? step : 0.0;
}

double carmen_beam_step_deg(const carmen_beams_t *g, int n, const char **from)
{
    const char *why = "spread over the field of view";
    double step = 0.0;
    if (g->spread)
        why = "spread over --fov-deg";
    else if (g->res_deg > 0)
        step = g->res_deg, why = "PARAM";
    else if ((step = carmen_sick_step_deg(n, g->fov_deg)) > 0)
        why = "the SICK's for the beam count";
    if (from)
        *from = why;
    return step > 0 ? step : g->fov_deg / (double)(n - 1);
}

hl_status_t carmen_make_scan(const carmen_flaser_t *f, const carmen_beams_t *g, carmen_input_t mode,
                             const carmen_ranges_t *cfg, hl_scan_t *out, carmen_counts_t *counts)
{
    if (!f || !g || !cfg || !out || f->nbeams < 2)
        return HL_ERR_ARG;
    carmen_counts_t c = { 0 };
    /* the classes of every beam, once: mm[i] >= 0 for a valid beam, -1 otherwise */
    int32_t mm[CARMEN_MAX_BEAMS];     /* 32 KiB */
    for (int i = 0; i < f->nbeams; i++) {
        carmen_beam_t b = carmen_classify(cfg, f->ranges[i], &mm[i]);
        if (b != CARMEN_BEAM_VALID)
            mm[i] = -1;
        c.valid += b == CARMEN_BEAM_VALID;
        c.no_return += b == CARMEN_BEAM_NO_RETURN;
        c.beyond += b == CARMEN_BEAM_BEYOND;
    }
    /* beam i at first + i * step degrees */
    double first = -g->fov_deg / 2.0, step = carmen_beam_step_deg(g, f->nbeams, NULL);
    hl_scan_clear(out);
    if (mode == CARMEN_INPUT_LASER) {
        if (f->nbeams > HL_SCAN_MAX_READINGS)
            return HL_ERR_CAPACITY;
        for (int i = 0; i < f->nbeams; i++) {
            hl_bam_t bearing = hl_bam_from_deg(first + i * step);
            hl_scan_add(out, bearing, mm[i] >= 0 ? mm[i] : 0, -1, mm[i] >= 0);
        }
    } else {
        int n = carmen_sonar_readings(g->fov_deg);
        if (n > 128)    /* transducer numbers are 0..127 */
            return HL_ERR_CAPACITY;
        for (int j = 0; j < n; j++) {
            /* centred on the field of view: (j - (n - 1) / 2) steps, exact in BAM */
            int32_t bam = (2 * j - (n - 1)) * (CARMEN_SONAR_STEP_BAM / 2);
            double centre = (j - (n - 1) / 2.0) * CARMEN_SONAR_STEP_DEG;
            int32_t nearest = -1;
            for (int i = 0; i < f->nbeams; i++) {
                if (mm[i] < 0 || fabs(first + i * step - centre) >
                                     CARMEN_SONAR_HALF_CONE_DEG + 1e-9)
                    continue;
                if (nearest < 0 || mm[i] < nearest)
                    nearest = mm[i];
            }
            hl_scan_add(out, (hl_bam_t)(uint16_t)bam, nearest >= 0 ? nearest : 0, (int8_t)j,
                        nearest >= 0);
        }
    }
    c.readings = out->count;
    c.readings_valid = hl_scan_valid_count(out);
    if (counts) {
        counts->valid += c.valid;
        counts->no_return += c.no_return;
        counts->beyond += c.beyond;
        counts->readings += c.readings;
        counts->readings_valid += c.readings_valid;
    }
    return HL_OK;
}
