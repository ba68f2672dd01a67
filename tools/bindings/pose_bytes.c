/*
 * pose_bytes.c - hl-pose-bytes: prints the LCM encoding of one houghloc.pose_t, built
 * from the arguments with the generated C types, as lowercase hex on one line.
 *
 *   hl-pose-bytes UTIME SCAN_SEQ X_MM Y_MM HEADING_BAM STATUS CONFIDENCE PEAK SECOND VOTES
 *                 SEARCH_SCORE RUNNER_X_MM RUNNER_Y_MM RUNNER_HEADING_BAM RUNNER_SCORE
 *
 * tests/integration/test_bindings.sh encodes the same message with the generated Python
 * (and Java) types and compares the bytes, so the bindings handed to users (scripts,
 * lcm-spy) are known to agree with the C code the daemon is built from: same fingerprint,
 * same field order, same byte order. Exit 0, or 2 with one line on stderr.
 */
#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc_pose_t.h"

#define NARGS 15

/* Parses a whole decimal integer in [lo, hi]; false on anything else. */
static int parse_int(const char *s, long long lo, long long hi, long long *out)
{
    char *end;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (errno != 0 || end == s || *end != '\0' || v < lo || v > hi)
        return 0;
    *out = v;
    return 1;
}

int main(int argc, char **argv)
{
    static const struct { const char *name; long long lo, hi; } spec[NARGS] = {
        { "UTIME", INT64_MIN, INT64_MAX }, { "SCAN_SEQ", INT32_MIN, INT32_MAX },
        { "X_MM", INT32_MIN, INT32_MAX },  { "Y_MM", INT32_MIN, INT32_MAX },
        { "HEADING_BAM", INT16_MIN, INT16_MAX }, { "STATUS", INT8_MIN, INT8_MAX },
        { "CONFIDENCE", 0, 0 },            { "PEAK", INT32_MIN, INT32_MAX },
        { "SECOND", INT32_MIN, INT32_MAX }, { "VOTES", INT32_MIN, INT32_MAX },
        { "SEARCH_SCORE", 0, 0 },          { "RUNNER_X_MM", INT32_MIN, INT32_MAX },
        { "RUNNER_Y_MM", INT32_MIN, INT32_MAX }, { "RUNNER_HEADING_BAM", INT16_MIN, INT16_MAX },
        { "RUNNER_SCORE", 0, 0 },
    };
    long long v[NARGS] = { 0 };
    float f[NARGS] = { 0 };     /* the float fields: CONFIDENCE, SEARCH_SCORE, RUNNER_SCORE */

    static const char usage[] = "usage: hl-pose-bytes UTIME SCAN_SEQ X_MM Y_MM HEADING_BAM "
                                "STATUS CONFIDENCE PEAK SECOND VOTES SEARCH_SCORE RUNNER_X_MM "
                                "RUNNER_Y_MM RUNNER_HEADING_BAM RUNNER_SCORE\n"
                                "Prints the LCM encoding of one houghloc_pose_t, in hex (the "
                                "bindings' cross-language check).\n";
    if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        fputs(usage, stdout);
        return 0;
    }
    if (argc != NARGS + 1) {
        fputs("hl-pose-bytes: want 15 fields (--help)\n", stderr);
        return 2;
    }
    for (int i = 0; i < NARGS; i++) {
        const char *a = argv[i + 1];
        if (i == 6 || i == 10 || i == 14) {     /* the float fields */
            char *end;
            errno = 0;
            f[i] = strtof(a, &end);
            if (errno == 0 && end != a && *end == '\0')
                continue;
        } else if (parse_int(a, spec[i].lo, spec[i].hi, &v[i])) {
            continue;
        }
        fprintf(stderr, "hl-pose-bytes: bad %s '%s'\n", spec[i].name, a);
        return 2;
    }

    houghloc_pose_t p = {
        .utime = v[0], .scan_seq = (int32_t)v[1], .x_mm = (int32_t)v[2],
        .y_mm = (int32_t)v[3], .heading_bam = (int16_t)v[4], .status = (int8_t)v[5],
        .confidence = f[6], .peak = (int32_t)v[7], .second_peak = (int32_t)v[8],
        .votes = (int32_t)v[9], .search_score = f[10], .runner_up_x_mm = (int32_t)v[11],
        .runner_up_y_mm = (int32_t)v[12], .runner_up_heading_bam = (int16_t)v[13],
        .runner_up_score = f[14],
    };
    /* Encoded size = 8 fingerprint bytes + the fields; a fixed-size message, but ask. */
    uint8_t buf[128];
    int n = houghloc_pose_t_encoded_size(&p);
    if (n <= 0 || n > (int)sizeof buf || houghloc_pose_t_encode(buf, 0, n, &p) != n) {
        fprintf(stderr, "hl-pose-bytes: the message does not encode\n");
        return 2;
    }
    for (int i = 0; i < n; i++)
        printf("%02x", buf[i]);
    printf("\n");
    return 0;
}
