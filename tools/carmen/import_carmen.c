/*
 * import_carmen.c - houghloc-import-carmen: a CARMEN laser log (the Radish building
 * data sets) as an LCM event log of SONAR, ODOMETRY and GROUND_TRUTH messages that
 * houghlocd replays. A thin main: options (carmen_args.c), the import
 * (carmen_import.c), the text dump (carmen_dump.c). docs/manual/real-data.md tells the rules.
 */
#include <stdio.h>

#include "carmen_args.h"
#include "carmen_import.h"

int main(int argc, char **argv)
{
    carmen_options_t o;
    int rc = carmen_parse_args(argc, argv, &o);
    if (rc != CARMEN_CONTINUE)
        return rc;
    if (o.dump)
        return carmen_dump(o.dump, stdout);
    return carmen_import(&o, stderr);
}
