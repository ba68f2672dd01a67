/* trial_args.h - the command-line pieces hl-flood and hl-forge share: strict numbers and
 * the one-line usage error (exit 2). */
#ifndef HOUGHLOC_TRIALS_ARGS_H
#define HOUGHLOC_TRIALS_ARGS_H

#include <stdbool.h>

#define TRIAL_EXIT_USAGE 2

/** Prints "PROG: WHAT "VALUE"; try PROG --help" and @return TRIAL_EXIT_USAGE. */
int trial_usage_error(const char *prog, const char *what, const char *value);

/** A whole-string number in [lo, hi]: no spaces, no hexadecimal, no trailing text. */
bool trial_parse_double(const char *s, double lo, double hi, double *out);

#endif
