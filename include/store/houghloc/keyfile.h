/* keyfile.h - loading the shared request-signing key from a file (see houghloc/auth.h). */
#ifndef HOUGHLOC_DAEMON_KEYFILE_H
#define HOUGHLOC_DAEMON_KEYFILE_H

#include "houghloc/auth.h"
#include "houghloc/status.h"

#define HL_KEYFILE_WHY_LEN 256
#define HL_KEYFILE_MAX_BYTES 1024

/**
 * Reads a key file: 64 hexadecimal digits, optionally followed by one newline.
 *
 * The file must be a regular file (not a symbolic link: opened with O_NOFOLLOW; not a
 * directory, FIFO or device), at most HL_KEYFILE_MAX_BYTES long, and neither readable
 * nor writable by group or others (mode 0600 or 0400), so that the key stays a secret
 * of its owner. The checks are made on the open file (fstat), not on the path.
 *
 * @param[in]  path  the file's path. Must not be NULL.
 * @param[out] key   the key, written only on success. Must not be NULL.
 * @param[out] why   on failure one line naming the file and the reason
 *                   (HL_KEYFILE_WHY_LEN bytes); may be NULL.
 * @return HL_OK; HL_ERR_ARG for a NULL argument; HL_ERR_OS when the file cannot be opened
 *         or read (errno kept); HL_ERR_RANGE for a file that is not regular, is too large,
 *         or is open to group or others; HL_ERR_PARSE for content that is not a key.
 */
hl_status_t hl_keyfile_load(const char *path, hl_auth_key_t *key, char *why);

#endif
