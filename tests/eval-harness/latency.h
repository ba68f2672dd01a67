/* latency.h - hl-eval latency (latency.c): each POSE's time after its scan, from the
 * recorded input and output logs of a live run. */
#ifndef HOUGHLOC_TESTS_LATENCY_H
#define HOUGHLOC_TESTS_LATENCY_H

/**
 * Pairs the SONAR scans of the log @p in with the POSE of the log @p out by seq and prints
 *   latency poses=<n> p50_ms=<x> p99_ms=<y> max_ms=<z> scans_unanswered=<k>
 *           poses_unpaired=<j>
 * @return 0, or 1 after one line on stderr starting with @p prog (a bad log, no pair).
 */
int hl_eval_latency(const char *prog, const char *in, const char *out);

#endif
