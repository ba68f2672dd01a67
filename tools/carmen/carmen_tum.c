/* carmen_tum.c - TUM trajectories: load, sort, find by exact time. */
#include "carmen_tum.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int by_time(const void *a, const void *b)
{
    int64_t ta = ((const carmen_truth_t *)a)->time_us, tb = ((const carmen_truth_t *)b)->time_us;
    return (ta > tb) - (ta < tb);
}

/* Parses one data line into @p p. @return 0, or -1 with the reason in @p why. */
static int parse_pose(char *line, carmen_truth_t *p, char *why)
{
    char *tok[8];
    int n = 0;
    for (char *save = NULL, *t = strtok_r(line, " \t", &save); t; t = strtok_r(NULL, " \t", &save))
        if (n++ < 8)
            tok[n - 1] = t;
    if (n != 8)
        return snprintf(why, CARMEN_WHY_LEN,
                        "expected 8 fields (time x y z qx qy qz qw), found %d", n), -1;
    if (!carmen_parse_time_us(tok[0], &p->time_us))
        return snprintf(why, CARMEN_WHY_LEN, "time '%.40s' is not a time of 0 to 10^12 s", tok[0]), -1;
    double v[7];
    for (int i = 0; i < 7; i++)
        if (!carmen_parse_number(tok[i + 1], &v[i]))
            return snprintf(why, CARMEN_WHY_LEN, "field %d '%.40s' is not a number", i + 2,
                            tok[i + 1]), -1;
    double qx = v[3], qy = v[4], qz = v[5], qw = v[6];
    double norm = sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
    if (fabs(norm - 1.0) > 1e-3)
        return snprintf(why, CARMEN_WHY_LEN, "quaternion norm %.6f is not 1", norm), -1;
    p->x = v[0];
    p->y = v[1];
    p->yaw = atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
    return 0;
}

int carmen_tum_load(const char *path, carmen_tum_t *out, char *why)
{
    *out = (carmen_tum_t){ 0 };
    char reason[CARMEN_WHY_LEN];
    carmen_reader_t *r = carmen_open(path, reason);
    if (!r)
        return snprintf(why, CARMEN_TUM_WHY_LEN, "%s: %s", path, reason), -1;
    size_t cap = 0;
    char *line;
    long lineno = 0;
    int rc, status = 0;
    while ((rc = carmen_next_line(r, &line, &lineno, reason)) == 1) {
        char *p = line;
        while (isspace((unsigned char)*p))
            p++;
        if (*p == '\0' || *p == '#')
            continue;
        if (out->n == cap) {
            size_t ncap = cap ? cap * 2 : 1024;
            carmen_truth_t *bigger = realloc(out->poses, ncap * sizeof *bigger);
            if (!bigger) {
                snprintf(why, CARMEN_TUM_WHY_LEN, "%s: out of memory", path);
                status = -1;
                break;
            }
            out->poses = bigger;
            cap = ncap;
        }
        if (parse_pose(p, &out->poses[out->n], reason) != 0) {
            snprintf(why, CARMEN_TUM_WHY_LEN, "%s:%ld: %s", path, lineno, reason);
            status = -1;
            break;
        }
        out->n++;
    }
    if (rc < 0 && status == 0) {
        snprintf(why, CARMEN_TUM_WHY_LEN, "%s: %s", path, reason);
        status = -1;
    }
    carmen_close(r);
    if (status == 0 && out->n == 0) {
        snprintf(why, CARMEN_TUM_WHY_LEN, "%s: no pose", path);
        status = -1;
    }
    if (status == 0) {
        qsort(out->poses, out->n, sizeof *out->poses, by_time);
        for (size_t i = 1; i < out->n; i++)
            if (out->poses[i].time_us == out->poses[i - 1].time_us) {
                int64_t t = out->poses[i].time_us;
                snprintf(why, CARMEN_TUM_WHY_LEN, "%s: two poses at time %lld.%06lld", path,
                         (long long)(t / 1000000), (long long)(t % 1000000));
                status = -1;
                break;
            }
    }
    if (status != 0)
        carmen_tum_free(out);
    return status;
}

const carmen_truth_t *carmen_tum_find(const carmen_tum_t *t, int64_t time_us)
{
    size_t lo = 0, hi = t->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (t->poses[mid].time_us < time_us)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < t->n && t->poses[lo].time_us == time_us ? &t->poses[lo] : NULL;
}

void carmen_tum_free(carmen_tum_t *t)
{
    if (!t)
        return;
    free(t->poses);
    *t = (carmen_tum_t){ 0 };
}
