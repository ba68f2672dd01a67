/*
 * fuzz_console_body.c - destreq_parse (tools/console/destreq.h): the body of the
 * console's POST /destination, as a browser or anyone who holds the token sends it.
 * destreq.h promises: no read past the input, no allocation, a one-line reason on every
 * refusal, HL_ERR_ARG above DESTREQ_MAX_BYTES; on success coordinates within
 * +-HL_COORD_MAX_MM once rounded and a finite heading. A body it accepts, written again
 * as JSON with every digit, must parse to the very same request, and its DESTINATION
 * (destreq_message) must hold the rounded millimetres.
 */
#include <math.h>
#include <string.h>

#include "destreq.h"
#include "fuzz.h"
#include "houghloc/fixed.h"

/* The reason: NUL-terminated within DESTREQ_WHY_LEN, one line, not empty. */
static void check_why(const char *why)
{
    size_t n = strnlen(why, DESTREQ_WHY_LEN);
    FUZZ_CHECK(n > 0 && n < DESTREQ_WHY_LEN);
    FUZZ_CHECK(!memchr(why, '\n', n));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    destreq_t r;
    char why[DESTREQ_WHY_LEN];
    memset(why, 0x55, sizeof why); /* no NUL: the parser must write one */
    hl_status_t st = destreq_parse((const char *)data, size, &r, why);
    if (size > DESTREQ_MAX_BYTES)
        FUZZ_CHECK(st == HL_ERR_ARG);
    if (st != HL_OK) {
        FUZZ_CHECK(st == HL_ERR_PARSE || st == HL_ERR_RANGE || st == HL_ERR_ARG);
        check_why(why);
        return 0;
    }
    FUZZ_CHECK(isfinite(r.x_m) && isfinite(r.y_m));
    FUZZ_CHECK(fabs(round(r.x_m * 1000.0)) <= HL_COORD_MAX_MM);
    FUZZ_CHECK(fabs(round(r.y_m * 1000.0)) <= HL_COORD_MAX_MM);
    FUZZ_CHECK(!r.has_heading || isfinite(r.heading_deg));
    hl_bus_destination_t d = destreq_message(&r);
    FUZZ_CHECK(d.x_mm == (int32_t)lround(r.x_m * 1000.0));
    FUZZ_CHECK(d.y_mm == (int32_t)lround(r.y_m * 1000.0));
    FUZZ_CHECK(d.has_heading == r.has_heading);

    /* again, as the page would write it: the same request, exactly */
    char again[DESTREQ_MAX_BYTES];
    int n = r.has_heading
                ? snprintf(again, sizeof again, "{\"x_m\":%.17g,\"y_m\":%.17g,\"heading_deg\":%.17g}",
                           r.x_m, r.y_m, r.heading_deg)
                : snprintf(again, sizeof again, "{\"y_m\":%.17g,\"x_m\":%.17g}", r.y_m, r.x_m);
    FUZZ_CHECK(n > 0 && (size_t)n < sizeof again);
    destreq_t r2;
    FUZZ_CHECK(destreq_parse(again, (size_t)n, &r2, why) == HL_OK);
    FUZZ_CHECK(r2.x_m == r.x_m && r2.y_m == r.y_m && r2.has_heading == r.has_heading);
    FUZZ_CHECK(!r.has_heading || r2.heading_deg == r.heading_deg);
    return 0;
}
