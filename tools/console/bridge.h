/*
 * bridge.h - houghlocd's messages as the JSON the console's page reads (private to
 * tools/console). Pure: decoded messages in (houghloc/bus.h), text out, no I/O.
 *
 * Every object is one line of plain ASCII (jbuf_str), so it fits one Server-Sent
 * Events "data:" line. Lengths are millimetres, headings degrees (0..360, counter-
 * clockwise from the map's +x axis), times microseconds. Sequence numbers are int64
 * values a client chooses, beyond what a JavaScript number holds exactly: they travel
 * as decimal strings. The shapes are listed in docs/manual/houghloc-console.md.
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_BRIDGE_H
#define HOUGHLOC_TOOLS_CONSOLE_BRIDGE_H

#include <stdbool.h>

#include "houghloc/bus.h"
#include "jbuf.h"

/** The STATUS state's name ("IDLE", ...); "UNKNOWN" for a value beyond the list. */
const char *bridge_state_name(int8_t state);
/** The POSE status's name ("ACCEPTED", "REJECTED_WILD", ...); "UNKNOWN" beyond. */
const char *bridge_pose_status_name(int8_t status);

/* The most vectors of a map the page gets: at most 30 bytes of JSON each, 2 MB in all,
 * whatever the map's size (the wire allows 2^20 vectors, 31 MB of JSON). A page draws
 * 65,536 vectors in a few milliseconds; the console's memory bound (hub.h) counts on it. */
#define BRIDGE_MAP_MAX_VECTORS 65536u

/**
 * MAP: {"utime","version","capacity","count","v":[x_mm,y_mm,normal_bam,range_mm,...]},
 * the vectors flat, four integers each, so a 15,000-vector map is one compact array the
 * page walks without building an object per vector. A map of more than
 * BRIDGE_MAP_MAX_VECTORS vectors is thinned to every stride-th vector (the fewest that
 * fit) and says so: "stride" follows "count" (absent when every vector is there).
 */
void bridge_map(jbuf_t *b, const hl_bus_map_t *m);
/** POSE or GROUND_TRUTH: position, heading, status name, confidence and the votes. */
void bridge_pose(jbuf_t *b, const hl_bus_pose_t *p);
/** STATUS: state name, counters, destination seq (null when none), estimate, error. */
void bridge_status(jbuf_t *b, const hl_bus_status_t *s);
/** REPLY: seq, result name, message; @p mine when the console sent that seq. */
void bridge_reply(jbuf_t *b, const hl_bus_reply_t *r, bool mine);
/** A DESTINATION the console published: seq, x_mm, y_mm, heading (null), signed. */
void bridge_sent(jbuf_t *b, const hl_bus_destination_t *d, bool is_signed);
/**
 * PATH: {"utime","seq","points":[x_mm,y_mm,...]}: seq the destination's (null when
 * none), the points flat, two integers each, the robot's estimate first and the
 * destination last; [] when the destination has ended.
 */
void bridge_path(jbuf_t *b, const hl_bus_path_t *p);
/** A STOP command the console published (POST /stop's answer): utime, seq, signed. */
void bridge_stop(jbuf_t *b, const hl_bus_command_t *c, bool is_signed);

#endif
