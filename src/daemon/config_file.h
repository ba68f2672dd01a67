/*
 * config_file.h - a configuration file read whole, and checked, before libinih sees it
 * (private to config.c).
 *
 * libinih reads whatever stream it is given, line by line, until its end: /dev/zero
 * never ends (the daemon spun at full CPU), a FIFO blocks the open until a writer comes
 * (the daemon hung, silent), and a NUL byte ends its line early (a short line was
 * reported as too long). So the file is opened without blocking, checked on the open
 * descriptor (fstat: nothing can be swapped in between the check and the read), read
 * into memory with a bound, and searched for NUL bytes; the parser then reads the text.
 */
#ifndef HOUGHLOC_DAEMON_CONFIG_FILE_H
#define HOUGHLOC_DAEMON_CONFIG_FILE_H

#include <stddef.h>

/* A configuration file is a few kilobytes (every key with its comment: about 14 KiB). */
#define HL_CONFIG_FILE_MAX_BYTES (1024 * 1024)

typedef enum hl_config_file_status {
    HL_CONFIG_FILE_OK,
    HL_CONFIG_FILE_MISSING,     /* it does not exist (ENOENT) */
    HL_CONFIG_FILE_BAD,         /* any other refusal */
} hl_config_file_status_t;

/**
 * Reads @p path whole: a regular file of at most HL_CONFIG_FILE_MAX_BYTES holding no NUL
 * byte, or /dev/null (read as empty: `--config /dev/null` means no file).
 * @param[out] text  on HL_CONFIG_FILE_OK a NUL-terminated copy (its only NUL) that the
 *                   caller frees; NULL otherwise.
 * @param[out] why   otherwise one line naming the file and what is wrong
 *                   (HL_CONFIG_WHY_LEN bytes): "FILE: not a regular file (a FIFO)",
 *                   "FILE: larger than 1048576 bytes ...", "FILE:LINE: holds a NUL byte",
 *                   "FILE: cannot open: REASON".
 */
hl_config_file_status_t hl_config_file_read(const char *path, char **text, char *why);

#endif
