/*
 * seqfile.h - the request state file: the highest DESTINATION/COMMAND seq the daemon
 * accepted, kept on its own, apart from the map file, so that neither a new map
 * (--fresh-map), nor the map file renamed or lost, nor a crash before the next map save
 * can let captured signed requests be played again (README, "Who may command the robot").
 *
 * Format (version HL_SEQFILE_VERSION), one line of text, at most HL_SEQFILE_MAX_BYTES:
 *   hlseq 1 SEQ CRC\n
 * SEQ in decimal, 0..INT64_MAX, no sign and no leading zero; CRC the zlib crc32 of the
 * bytes before the space in front of it ("hlseq 1 SEQ"), as 8 lowercase hexadecimal
 * digits. Saving writes PATH.tmp, fsyncs it, renames it over PATH and fsyncs the folder,
 * as the map file does: a crash leaves the old line or the new one. Loading refuses
 * anything else (empty, cut short, altered, too long) rather than guess: a state that
 * silently fell back to 0 would accept every captured request again.
 */
#ifndef HOUGHLOC_SEQFILE_H
#define HOUGHLOC_SEQFILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc/status.h"

#define HL_SEQFILE_VERSION 1
#define HL_SEQFILE_MAX_BYTES 64
#define HL_SEQFILE_WHY_LEN 512
#define HL_SEQFILE_NAME "requests.seq"  /* the default file, in the map file's folder */

/**
 * Writes the file's text for @p seq (0..INT64_MAX) into @p buf.
 * @return its length (without the NUL), or -1 when @p seq is negative or @p cap is too
 *         small (HL_SEQFILE_MAX_BYTES + 1 always suffices).
 */
int hl_seqfile_format(int64_t seq, char *buf, size_t cap);

/**
 * Parses a file's bytes (@p len of them; no NUL needed).
 * @return HL_OK with @p seq; HL_ERR_PARSE with a reason in @p why (HL_SEQFILE_WHY_LEN
 *         bytes, may be NULL) for anything but one well-formed line.
 */
hl_status_t hl_seqfile_parse(const char *text, size_t len, int64_t *seq, char *why);

/**
 * Loads the file at @p path (a regular file of at most HL_SEQFILE_MAX_BYTES).
 * @return HL_OK with @p seq; HL_ERR_OS with errno (ENOENT: no file yet) for a file that
 *         cannot be opened or read; HL_ERR_PARSE for a file that is not a request state
 *         file, cut short, altered or too long. @p why names the file and the reason in
 *         one line.
 */
hl_status_t hl_seqfile_load(const char *path, int64_t *seq, char *why);

/**
 * Replaces the file at @p path with @p seq, durably (temp, fsync, rename, folder fsync).
 * @return HL_OK; HL_ERR_ARG for a negative seq or no path; HL_ERR_OS with errno and a
 *         reason naming the file and the step that failed.
 */
hl_status_t hl_seqfile_save(const char *path, int64_t seq, char *why);

/**
 * The default state file for the map file @p map_path: HL_SEQFILE_NAME in its folder,
 * so that it stays put when the map file is renamed in that folder or replaced.
 * @return false when it does not fit in @p cap bytes.
 */
bool hl_seqfile_default_path(const char *map_path, char *out, size_t cap);

#endif
