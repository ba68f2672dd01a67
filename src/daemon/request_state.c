/* request_state.c - the request state file at start-up (request_state.h). */
#include "request_state.h"

#include <errno.h>
#include <stdio.h>

#include "houghloc/seqfile.h"
#include "log.h"

bool hl_request_state_path(const char *configured, const char *map_path, char *out,
                           size_t cap)
{
    if (configured && configured[0])
        return (size_t)snprintf(out, cap, "%s", configured) < cap;
    return hl_seqfile_default_path(map_path, out, cap);
}

/* Loads the file: @p missing when there is none. @return false with the start-up line. */
static bool load(const char *path, int64_t *kept, bool *missing, char *why)
{
    char reason[HL_SEQFILE_WHY_LEN];
    *kept = 0;
    hl_status_t st = hl_seqfile_load(path, kept, reason);
    *missing = st == HL_ERR_OS && errno == ENOENT;
    if (st == HL_OK || *missing)
        return true;
    snprintf(why, HL_REQUEST_STATE_WHY_LEN,
             "request state %s; not starting, as captured requests could be accepted "
             "again: to reset it deliberately, remove the file (auth.state_file)", reason);
    return false;
}

bool hl_request_state_check(const char *path, char *why)
{
    int64_t kept;
    bool missing;
    return load(path, &kept, &missing, why);
}

bool hl_request_state_open(hl_cycle_t *cycle, const char *path, char *why)
{
    char reason[HL_SEQFILE_WHY_LEN];
    int64_t kept;
    bool missing;
    if (!load(path, &kept, &missing, why))
        return false;
    if (missing)
        hl_log(HL_LOG_INFO, "request state %s does not exist yet: the map file's last "
               "request seq (%lld) holds", path, (long long)hl_cycle_request_seq(cycle));
    else
        hl_cycle_take_request_seq(cycle, kept, "the request state file");
    int64_t now = hl_cycle_request_seq(cycle);
    if (now != kept || missing) {
        if (hl_seqfile_save(path, now, reason) != HL_OK) {
            snprintf(why, HL_REQUEST_STATE_WHY_LEN, "request state %s (set auth.state_file "
                     "to a writable file)", reason);
            return false;
        }
    }
    hl_log(HL_LOG_INFO, "request state %s: requests with seq above %lld are fresh", path,
           (long long)now);
    return true;
}
