/*
 * carmen_import.h - houghloc-import-carmen's work: a CARMEN log in, an LCM event log
 * of SONAR, ODOMETRY and GROUND_TRUTH out (private to tools/carmen).
 *
 * Two passes over the input. The first parses and checks every line (malformed lines,
 * time going backwards, poses outside the coordinate range, scans without a truth pose)
 * and learns what only the whole log tells: the field of view (PARAM) and the largest
 * range, which decides the no-return value (carmen_scan.h). Nothing is written unless
 * it succeeds, so a bad log leaves no output file. The second pass converts and writes;
 * every message is checked (hl_scan_check, encoded and decoded again by the codecs the
 * daemon uses) before it is written.
 */
#ifndef HOUGHLOC_TOOLS_CARMEN_IMPORT_H
#define HOUGHLOC_TOOLS_CARMEN_IMPORT_H

#include <stdio.h>

#include "carmen_args.h"

/**
 * Imports o->in into o->out as @p o says, printing the summary on @p summary (several
 * lines, each starting with PROG ": "), or one line "FILE:LINE: reason" (or
 * "FILE: reason") on stderr on failure, when an output file written so far is removed.
 * @return CARMEN_EXIT_OK or CARMEN_EXIT_ERROR.
 */
int carmen_import(const carmen_options_t *o, FILE *summary);

/**
 * Prints the LCM log @p path as text on @p out: one line per SONAR (then one indented
 * line per reading), ODOMETRY and GROUND_TRUTH message, and "CHANNEL utime=T bytes=N"
 * for other channels. The log is checked (hl_log_check) first.
 * @return CARMEN_EXIT_OK, or CARMEN_EXIT_ERROR after one line on stderr.
 */
int carmen_dump(const char *path, FILE *out);

#endif
