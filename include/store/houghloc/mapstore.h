/*
 * mapstore.h - the map file: everything a restarted daemon needs to continue exactly
 * where the last one stopped, saved so that a crash at any instant leaves either the
 * old file or the new one, never a mix.
 *
 * Format (little-endian, version HL_MAPSTORE_VERSION; docs/manual/mapfile.md):
 *   header  magic "HLMAP\r\n\x1a" (8 bytes), format version u32, header bytes u32,
 *           capacity u32, count u32, map version u32, started u8, pose (x i32, y i32,
 *           theta u16), odometry reference (same), peak average u32, culling PRNG
 *           (state u64, inc u64), last request seq i64, last scan utime i64,
 *           scans integrated u64
 *   body    count vectors: x i32, y i32, normal u16, range u16
 *   trailer crc32 (zlib) of everything before it, u32
 * Saving writes PATH.tmp, fsyncs it, renames it over PATH and fsyncs the directory.
 * Loading checks the magic, version, sizes, every field's range and the checksum before
 * it returns anything. A file that fails to load is never overwritten by a save: the
 * caller moves it aside first (hl_mapstore_move_aside).
 */
#ifndef HOUGHLOC_MAPSTORE_H
#define HOUGHLOC_MAPSTORE_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/slam.h"

#define HL_MAPSTORE_VERSION 1u
#define HL_MAPSTORE_WHY_LEN 512

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
} hl_mapfile_t;

/**
 * Saves atomically. Allocates nothing (writes through a fixed buffer on the stack).
 * @return HL_OK, or HL_ERR_OS with errno kept and a one-line reason naming the file.
 */
hl_status_t hl_mapstore_save(const char *path, const hl_mapfile_t *m, char *why);

/**
 * Loads and checks. @return HL_OK; HL_ERR_OS with errno == ENOENT when the file does not
 * exist (the caller starts a fresh map), other HL_ERR_OS for a read error; HL_ERR_PARSE
 * for a file that is not a map file, truncated, of another format version, or fails its
 * checksum; HL_ERR_CAPACITY when it holds more than max_vectors vectors (out->needed
 * says how many, nothing else of @p out changes); HL_ERR_RANGE for
 * a field out of range. @p why names the file and the reason in one line.
 */
hl_status_t hl_mapstore_load(const char *path, hl_mapfile_t *out, char *why);

/**
 * Renames a bad map file to PATH.bad-N (the first N >= 1 not taken) so that a fresh map
 * never overwrites it. @p moved_to receives the new name (may be NULL; cap bytes).
 */
hl_status_t hl_mapstore_move_aside(const char *path, char *moved_to, size_t cap, char *why);

#endif
