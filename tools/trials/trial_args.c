/* trial_args.c - strict numbers and usage errors for the trial programs (trial_args.h). */
#include "trial_args.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int trial_usage_error(const char *prog, const char *what, const char *value)
{
    fprintf(stderr, "%s: %s \"%s\"; try %s --help\n", prog, what, value, prog);
    return TRIAL_EXIT_USAGE;
}

bool trial_parse_double(const char *s, double lo, double hi, double *out)
{
    if (!*s || strpbrk(s, " \t\nxX"))
        return false;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (*end || errno || !(v >= lo && v <= hi))
        return false;
    *out = v;
    return true;
}
