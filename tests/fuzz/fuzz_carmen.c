/*
 * fuzz_carmen.c - the CARMEN line parser (tools/carmen/carmen_log.h): the input is one
 * line of a CARMEN log as the reader hands it over (no line end; a NUL ends it early,
 * as in the reader's buffer).
 *
 * carmen_parse_line gets the line; carmen_parse_number and carmen_parse_time_us get each
 * of its whitespace-separated words. Checked: what carmen_log.h promises of a parsed
 * FLASER (2..8192 beams, every value finite, ranges >= 0, a time >= 0) or PARAM (name and
 * value pointing into the line); a refusal comes with a reason; a time read exactly from
 * a plain decimal agrees with the same word read as a number.
 */
#include <ctype.h>
#include <math.h>
#include <string.h>

#include "carmen_log.h"
#include "fuzz.h"

static bool finite_pose(carmen_pose_t p)
{
    return isfinite(p.x) && isfinite(p.y) && isfinite(p.theta);
}

static void check_line(char *line, size_t len, double *ranges)
{
    carmen_line_t out;
    memset(&out, 0, sizeof out);
    out.flaser.ranges = ranges;
    char why[CARMEN_WHY_LEN] = "";
    if (carmen_parse_line(line, &out, why) != 0) {
        FUZZ_CHECK(memchr(why, '\0', sizeof why) != NULL && why[0] != '\0');
        return;
    }
    if (out.kind == CARMEN_FLASER) {
        const carmen_flaser_t *f = &out.flaser;
        FUZZ_CHECK(f->nbeams >= 2 && f->nbeams <= CARMEN_MAX_BEAMS);
        for (int i = 0; i < f->nbeams; i++)
            FUZZ_CHECK(isfinite(f->ranges[i]) && f->ranges[i] >= 0);
        FUZZ_CHECK(finite_pose(f->pose) && finite_pose(f->odom));
        FUZZ_CHECK(f->time_us >= 0);
    } else if (out.kind == CARMEN_PARAM) {
        FUZZ_CHECK(out.param.name && out.param.value);
        FUZZ_CHECK(out.param.name >= line && out.param.name < line + len);
        FUZZ_CHECK(out.param.value > out.param.name && out.param.value < line + len);
        FUZZ_CHECK(out.param.name[0] != '\0' && out.param.value[0] != '\0');
    } else {
        FUZZ_CHECK(out.kind == CARMEN_SKIP);
    }
}

static void check_word(const char *w)
{
    double v = 0;
    bool number = carmen_parse_number(w, &v);
    if (number)
        FUZZ_CHECK(isfinite(v));
    int64_t us = -1;
    if (!carmen_parse_time_us(w, &us))
        return;
    /* 0 .. 10^12 s; and whatever reads as a time reads as a number, within the
     * rounding of a double (128 us at 10^12 s). */
    FUZZ_CHECK(us >= 0 && us <= INT64_C(1000000000000000000));
    FUZZ_CHECK(number);
    double want = v * 1e6;
    FUZZ_CHECK(fabs((double)us - want) <= 1.0 + fabs(want) * 1e-15);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *line = malloc(size + 1), *words = malloc(size + 1);
    double *ranges = malloc(CARMEN_MAX_BEAMS * sizeof *ranges);
    FUZZ_CHECK(line && words && ranges);
    memcpy(line, data, size);
    line[size] = '\0';
    memcpy(words, line, size + 1);
    size_t len = strlen(line);

    check_line(line, len, ranges);

    char *p = words;
    while (*p) {
        while (*p && isspace((unsigned char)*p))
            p++;
        char *start = p;
        while (*p && !isspace((unsigned char)*p))
            p++;
        if (*p)
            *p++ = '\0';
        if (*start)
            check_word(start);
    }
    free(ranges);
    free(words);
    free(line);
    return 0;
}
