/*
 * carmen_tum.h - a ground-truth trajectory in TUM format, looked up by exact time
 * (private to tools/carmen).
 *
 * One pose a line: "time x y z qx qy qz qw" (seconds, metres, a unit quaternion); lines
 * starting with '#' and empty lines are skipped. Only the planar part is used: x, y and
 * the yaw of the quaternion. Times are kept in microseconds exactly as written
 * (carmen_parse_time_us), so a scan whose CARMEN timestamp was printed with the same six
 * decimals finds its pose by equality: no interpolation, no nearest neighbour.
 */
#ifndef HOUGHLOC_TOOLS_CARMEN_TUM_H
#define HOUGHLOC_TOOLS_CARMEN_TUM_H

#include <stddef.h>
#include <stdint.h>

#include "carmen_log.h"

typedef struct carmen_truth {
    int64_t time_us;
    double x, y, yaw;       /* metres, radians in (-pi, pi] */
} carmen_truth_t;

typedef struct carmen_tum {
    carmen_truth_t *poses;  /* sorted by time_us, no two equal */
    size_t n;
} carmen_tum_t;

/**
 * Loads @p path (plain or gzip) into @p out (zeroed first; free with carmen_tum_free).
 * @return 0, or -1 with "PATH:LINE: reason" (or "PATH: reason") in @p why
 *         (CARMEN_WHY_LEN + 1024 bytes): a line without exactly 8 numbers, a negative
 *         time, a quaternion whose norm is not 1 within 1e-3, two poses at one time, no
 *         pose at all, a read error.
 */
int carmen_tum_load(const char *path, carmen_tum_t *out, char *why);

/** The pose at exactly @p time_us, or NULL. @p t must not be NULL. */
const carmen_truth_t *carmen_tum_find(const carmen_tum_t *t, int64_t time_us);

/** Frees what carmen_tum_load allocated; NULL is allowed. */
void carmen_tum_free(carmen_tum_t *t);

#define CARMEN_TUM_WHY_LEN (CARMEN_WHY_LEN + 1024)

#endif
