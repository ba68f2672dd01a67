/*
 * mapstore.h - the map file: everything a restarted daemon needs to continue exactly
 * where the last one stopped, saved so that a crash at any instant leaves either the
 * old file or the new one, never a mix.
 *
 * Format (little-endian, version HL_MAPSTORE_VERSION; docs/manual/mapfile.md):
 *   header  magic "HLMAP\r\n\x1a" (8 bytes), format version u32, header bytes u32,
 *           capacity u32, count u32, map version u64, started u8, pose (x i32, y i32,
 *           theta u16), odometry reference (same), peak average u32, culling PRNG
 *           (state u64, inc u64), last request seq i64, last scan utime i64,
 *           scans integrated u64
 *   body    count vectors: x i32, y i32, normal u16, range u16
 *   trailer crc32 (zlib) of everything before it, u32
 * Format version 1 differs only in the map version, a u32 (a 93-byte header): it is still
 * read, its map version widened; saving always writes version 2.
 * Saving writes PATH.tmp, fsyncs it, renames it over PATH and fsyncs the directory.
 * Loading checks the magic, version, sizes, every field's range and the checksum before
 * it returns anything. A file that fails to load is never overwritten by a save: the
 * caller moves it aside first (hl_mapstore_move_aside). One process at a time uses a map
 * file: it holds the lock on PATH.lock (hl_mapstore_lock) while it does.
 */
#ifndef HOUGHLOC_MAPSTORE_H
#define HOUGHLOC_MAPSTORE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#include "houghloc/slam.h"

#define HL_MAPSTORE_VERSION 2u          /* the format saves write; loads read 1 too */
#define HL_MAPSTORE_WHY_LEN 512
#define HL_MAPSTORE_HEADER_BYTES 97     /* the header of format version 2 */
#define HL_MAPSTORE_V1_HEADER_BYTES 93  /* ... and of version 1 */
#define HL_MAPSTORE_LOCK_SUFFIX ".lock" /* the lock file: PATH.lock */

typedef struct hl_mapfile {
    hl_slam_state_t state;
    uint32_t capacity;          /* the map's capacity when saved (informational) */
    uint32_t count;             /* vectors */
    hl_vector_t *vectors;       /* save: count vectors; load: caller storage for
                                   max_vectors */
    uint32_t max_vectors;       /* load only */
    uint32_t needed;            /* load only: when HL_ERR_CAPACITY refuses the file, the
                                   vectors it holds (the capacity it takes) */
    int64_t last_request_seq;   /* highest DESTINATION/COMMAND seq accepted (replay guard) */
    int64_t last_scan_utime;    /* the newest integrated scan's time */
    uint64_t scans;             /* scans integrated over the map's life */
    uint32_t format;            /* load only: the file's format version (1 or 2) */
} hl_mapfile_t;

/**
 * Saves atomically. Allocates nothing (writes through a fixed buffer on the stack).
 * @return HL_OK, or HL_ERR_OS with errno kept and a one-line reason naming the file.
 */
hl_status_t hl_mapstore_save(const char *path, const hl_mapfile_t *m, char *why);

/**
 * Loads and checks. @return HL_OK; HL_ERR_OS with errno == ENOENT when the file does not
 * exist (the caller starts a fresh map), other HL_ERR_OS for a read error; HL_ERR_PARSE
 * for a file that is not a map file, truncated, of a format version other than 1 and 2,
 * or fails its checksum; HL_ERR_CAPACITY when it holds more than max_vectors vectors
 * (out->needed says how many, nothing else of @p out changes); HL_ERR_RANGE for a field
 * out of range (a map version above HL_COUNT_MAX too). @p why names the file and the
 * reason in one line.
 */
hl_status_t hl_mapstore_load(const char *path, hl_mapfile_t *out, char *why);

/**
 * Renames a bad map file to PATH.bad-N (the first N >= 1 not taken) so that a fresh map
 * never overwrites it. @p moved_to receives the new name (may be NULL; cap bytes).
 * The same as hl_mapstore_move_aside_as(path, "bad", ...).
 */
hl_status_t hl_mapstore_move_aside(const char *path, char *moved_to, size_t cap, char *why);

/**
 * Renames the map file to PATH.KIND-N, the first N from 1 to 1000 not taken, by link()
 * then unlink(), so that no older PATH.KIND-N is ever replaced, and fsyncs the folder.
 * @p kind is a short name without '/' ("bad": a file that does not load; "old": a good
 * map set aside for a fresh one). @p moved_to receives the new name (may be NULL).
 * @return HL_OK; HL_ERR_OS with errno (ENOENT: no file at PATH) and a reason; HL_ERR_ARG.
 */
hl_status_t hl_mapstore_move_aside_as(const char *path, const char *kind, char *moved_to,
                                      size_t cap, char *why);

/**
 * The header hl_mapstore_save writes for @p m: the file's first HL_MAPSTORE_HEADER_BYTES
 * bytes, every field the file holds but the vectors and the checksum. Two states with
 * the same header differ at most in their vectors (whose changes the map version, in the
 * header, counts: hl_map_version).
 */
void hl_mapstore_header(const hl_mapfile_t *m, uint8_t out[HL_MAPSTORE_HEADER_BYTES]);

/**
 * Takes the map file's lock: an exclusive flock(2) on PATH.lock (created 0644 when
 * missing, never removed), which then holds the taker's pid in decimal and a newline
 * (unless the file is another user's, which is locked read-only and left as it is).
 * The lock lasts while the returned descriptor is open (close-on-exec), and the kernel
 * drops it when the process ends, however it ends: a lock file left by a killed process
 * is simply locked again. Neither PATH nor its folder is touched.
 * @param[out] holder  when another process holds the lock: the pid it wrote (0 when the
 *                     file holds none, or one that names no process); else 0. May be NULL.
 * @return the lock's descriptor (>= 0), to keep open while the map is in use and give to
 *         hl_mapstore_unlock; or -1 with errno (EWOULDBLOCK: held by another process) and
 *         a one-line reason naming the lock file.
 */
int hl_mapstore_lock(const char *path, pid_t *holder, char *why);

/** Releases the lock: empties the lock file (its pid is no longer a holder's), then
 *  closes @p fd. Accepts -1. */
void hl_mapstore_unlock(int fd);

#endif
