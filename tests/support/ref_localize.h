/*
 * ref_localize.h - a plain floating-point reference of the localizer in
 * houghloc/localize.h, written for clarity, not speed: double trigonometry, double vote
 * and blur arrays, an exact Gaussian. It places the raster by the same rules (so cells
 * can be compared one to one) and is used by the tests and the benchmark to check the
 * fixed-point implementation. No odometry prior.
 */
#ifndef HOUGHLOC_TEST_SUPPORT_REF_LOCALIZE_H
#define HOUGHLOC_TEST_SUPPORT_REF_LOCALIZE_H

#include <stddef.h>

#include "houghloc/localize.h"

typedef struct ref_result {
    int ix, iy, it;             /* peak cell */
    double x_mm, y_mm;          /* interpolated */
    double theta_bam;           /* interpolated heading, BAM as a real number */
    double peak, second;        /* blurred votes x 256 */
    long votes;
} ref_result_t;

typedef struct ref_localizer ref_localizer_t;

ref_localizer_t *ref_create(const hl_loc_params_t *p);
void ref_destroy(ref_localizer_t *r);
size_t ref_mem_bytes(const ref_localizer_t *r);

/** @return 0 on success, -1 if there is nothing to localize or the raster is too big. */
int ref_run(ref_localizer_t *r, const hl_vector_t *map, unsigned n, const hl_scan_t *scan,
            const hl_loc_query_t *q, ref_result_t *out);

#endif
