/* trial_args.c - options, strict numbers and usage errors for the trial programs
 * (trial_args.h). */
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

int trial_next_option(const trial_cli_t *c, int argc, char **argv, int *i,
                      const char **value, int *status)
{
    const char *a = argv[*i];
    *status = 0;
    if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0)
        return fputs(c->usage, stdout), -1;
    if (strcmp(a, "--version") == 0)
        return printf("%s %s\n", c->prog, c->version), -1;
    const char *eq = strchr(a, '=');
    size_t n = eq ? (size_t)(eq - a) : strlen(a);
    int k = -1;
    for (int j = 0; j < c->nnames; j++)
        if (strlen(c->names[j]) == n && strncmp(a, c->names[j], n) == 0)
            k = j;
    if (k < 0) {
        *status = trial_usage_error(c->prog, a[0] == '-' ? "unknown option" : "unexpected argument", a);
        return -1;
    }
    const char *v = eq ? eq + 1 : *i + 1 < argc ? argv[++*i] : NULL;
    if (!v || (!c->empty_ok && !*v)) {
        *status = trial_usage_error(c->prog, "a value is missing after", a);
        return -1;
    }
    *value = v;
    return k;
}
