/*
 * maplock.h - houghlocd's hold on its map file, one per process (a daemon has one map):
 *
 * - the lock: one daemon per map file. hl_maplock_take takes hl_mapstore_lock's flock on
 *   FILE.lock (which then holds the daemon's pid) before the map is read or anything is
 *   written, and the daemon keeps it until it ends; the kernel drops it when the process
 *   dies, however it dies, so a killed daemon leaves nothing that blocks the next one.
 *   `--check-map` only reads, and takes no lock.
 * - the save rule: a save writes the file only when the state it would write differs from
 *   the daemon's state when it loaded the map or last saved it (hl_maplock_changed). A
 *   daemon that changed nothing leaves the file as it found it, byte for byte, whatever
 *   asks it to save (daemon.save_every, SIGHUP, a SAVE request, the stop). A daemon that
 *   started without a file (none yet, or --fresh-map set it aside) writes one at its
 *   first save.
 */
#ifndef HOUGHLOC_DAEMON_MAPLOCK_H
#define HOUGHLOC_DAEMON_MAPLOCK_H

#include <stdbool.h>
#include <stddef.h>

#include "houghloc/mapstore.h"

/**
 * Takes the lock on the map file @p path (kept until hl_maplock_release or the end of the
 * process). @return false with one line in @p why (cap bytes): when another daemon holds
 * it, "map PATH is in use by houghlocd pid N (lock PATH.lock)".
 */
bool hl_maplock_take(const char *path, char *why, size_t cap);

/** Releases the lock (empties the lock file) and forgets the saved state. */
void hl_maplock_release(void);

/** The map file holds @p m's state: the daemon loaded it (the cycle's snapshot right
 *  after the restore) or saved it. Its vectors are not kept (see hl_maplock_changed). */
void hl_maplock_saved(const hl_mapfile_t *m);

/**
 * Whether saving @p m would write anything new: true when it differs from the state noted
 * by hl_maplock_saved, or when none is noted (the daemon started without a map file and
 * has not saved one yet; after the release).
 * @param ignore_request_seq  leave the last request seq out (a SAVE request's own).
 */
bool hl_maplock_changed(const hl_mapfile_t *m, bool ignore_request_seq);

#endif
