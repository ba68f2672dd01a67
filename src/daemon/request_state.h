/*
 * request_state.h - the request state file at start-up (with a key only): which file,
 * its lock, and the seq it holds, merged with the map file's into the cycle.
 *
 * The file (seqfile.h) is auth.state_file, by default requests.seq in the map file's
 * folder: a fixed name there stays put when the map file is renamed in that folder or
 * moved aside by --fresh-map, so a new map inherits the replay window of the old. Like a
 * map file it is one daemon's: its lock is PATH.lock (hl_mapstore_lock), and a second
 * daemon with a key whose state would be the same file does not start (two daemons
 * writing one file would lower each other's seq).
 */
#ifndef HOUGHLOC_DAEMON_REQUEST_STATE_H
#define HOUGHLOC_DAEMON_REQUEST_STATE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cycle.h"

#define HL_REQUEST_STATE_WHY_LEN 1024

/** The state file: @p configured when not empty, else requests.seq beside @p map_path.
 *  @return false when it does not fit in @p cap bytes. */
bool hl_request_state_path(const char *configured, const char *map_path, char *out,
                           size_t cap);

/**
 * Checks, before anything else is done (a map moved aside by --fresh-map), that the state
 * file at @p path is missing or readable. @return false as hl_request_state_open.
 */
bool hl_request_state_check(const char *path, char *why);

/**
 * Reads the state file at @p path into the cycle (hl_cycle_take_request_seq, with the
 * map file's seq already taken by hl_cycle_restore), then writes the file again when the
 * cycle's seq is above what it held (the map file's was higher, or none was kept yet).
 * A missing file is an empty state. A file that cannot be read or parsed is a start-up
 * error: silently starting from 0 would accept captured requests again.
 * @return false with one line in @p why (HL_REQUEST_STATE_WHY_LEN bytes) saying how to
 *         reset the state deliberately.
 */
bool hl_request_state_open(hl_cycle_t *cycle, const char *path, char *why);

#endif
