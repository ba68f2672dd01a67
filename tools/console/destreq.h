/*
 * destreq.h - the body of POST /destination, parsed without trusting it (private to
 * tools/console). Pure: bytes in, a checked request or a one-line reason out; written
 * to be fuzzed (no allocation, no reads past @p len, no NUL needed).
 *
 * The body is one JSON object with exactly the members
 *     "x_m": number, "y_m": number             metres in the map frame
 *     "heading_deg": number or null            optional: the heading to arrive with
 * in any order, each at most once, and nothing else. Numbers follow JSON's grammar
 * strictly (no leading '+', no leading zeros, no "NaN" or "Infinity", no hexadecimal);
 * x and y must lie within +-HL_COORD_MAX_MM once rounded to the millimetre, a heading
 * may be any finite number of degrees (370 is 10).
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_DESTREQ_H
#define HOUGHLOC_TOOLS_CONSOLE_DESTREQ_H

#include <stdbool.h>
#include <stddef.h>

#include "houghloc/bus.h"
#include "houghloc/status.h"

#define DESTREQ_MAX_BYTES 1024  /* a longer body is refused unread */
#define DESTREQ_WHY_LEN 128

typedef struct destreq {
    double x_m, y_m;
    bool has_heading;
    double heading_deg;         /* finite when has_heading */
} destreq_t;

/**
 * Parses @p len bytes of @p body.
 * @param[out] out  written only on success.
 * @param[out] why  on failure one line naming the fault (DESTREQ_WHY_LEN bytes; may be
 *                  NULL).
 * @return HL_OK; HL_ERR_PARSE for text that is not such an object; HL_ERR_RANGE for a
 *         number that is not finite or a coordinate out of range; HL_ERR_ARG for NULL
 *         @p body or @p out, or @p len above DESTREQ_MAX_BYTES.
 */
hl_status_t destreq_parse(const char *body, size_t len, destreq_t *out, char *why);

/** The DESTINATION for @p r: millimetres rounded, heading in binary angle units; the
 *  stamps, seq and mac left zero for the sender. */
hl_bus_destination_t destreq_message(const destreq_t *r);

#endif
