/* trial_args.h - the command-line pieces hl-flood and hl-forge share: strict numbers and
 * the one-line usage error (exit 2). */
#ifndef HOUGHLOC_TRIALS_ARGS_H
#define HOUGHLOC_TRIALS_ARGS_H

#include <stdbool.h>

#define TRIAL_EXIT_USAGE 2

/** Prints "PROG: WHAT "VALUE"; try PROG --help" and @return TRIAL_EXIT_USAGE. */
int trial_usage_error(const char *prog, const char *what, const char *value);

/** What a program's options are: --NAME VALUE or --NAME=VALUE, and --help, --version. */
typedef struct trial_cli {
    const char *prog, *usage, *version;
    const char *const *names;   /* "--lcm-url", ...: an option's index is its place here */
    int nnames;
    bool empty_ok;              /* a value may be the empty string */
} trial_cli_t;

/**
 * Reads the option at argv[*i] (and its value, moving *i past it).
 * @return the option's index in names, with *value; or -1 with *status the exit status:
 *         0 after printing the usage (--help, -h) or the version, else a usage error
 *         (unknown option, stray argument, missing value) printed in one line.
 */
int trial_next_option(const trial_cli_t *c, int argc, char **argv, int *i,
                      const char **value, int *status);

/** A whole-string number in [lo, hi]: no spaces, no hexadecimal, no trailing text. */
bool trial_parse_double(const char *s, double lo, double hi, double *out);

#endif
