/*
 * fileio.h - the POSIX calls the store's files share (private to src/store): EINTR
 * retried, short reads and writes completed, errno kept, and the folder fsync that
 * makes a rename durable. Every file written whole goes the same way: PATH.tmp
 * (O_NOFOLLOW), its bytes, fsync, close, rename over PATH, fsync of the folder.
 */
#ifndef HOUGHLOC_STORE_FILEIO_H
#define HOUGHLOC_STORE_FILEIO_H

#include <errno.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#define HL_FILEIO_RETRY(r, call)            \
    do                                      \
        (r) = (call);                       \
    while ((r) < 0 && errno == EINTR)

/** Writes all of @p n bytes, through short writes. @return false with errno. */
bool hl_fileio_write_all(int fd, const uint8_t *b, size_t n);

/** Reads up to @p n bytes, through short reads. @return bytes read (fewer only at the
 *  end of the file), or -1 with errno. */
ssize_t hl_fileio_read_full(int fd, uint8_t *b, size_t n);

/** fsync through EINTR. @return 0, or -1 with errno. */
int hl_fileio_fsync(int fd);

/** close() keeping errno; not retried on EINTR (Linux has closed the fd anyway). */
void hl_fileio_close_quietly(int fd);

/** fsyncs the folder holding @p path, so that a rename or link in it is durable.
 *  @return false with errno. */
bool hl_fileio_sync_folder(const char *path);

/**
 * Opens @p tmp for writing a new version of a file: created 0644 when missing, truncated
 * (a stale one from a crash mid-save), never through a symbolic link planted there.
 * @return the descriptor, or -1 with errno.
 */
int hl_fileio_open_tmp(const char *tmp);

/**
 * Finishes a write begun with hl_fileio_open_tmp, whose bytes are all in @p fd: fsync,
 * close (which reports late write-back errors), rename over @p path; on failure @p tmp
 * is removed and @p step names the call that failed ("fsync", "close", "rename").
 * The folder is not synced: hl_fileio_sync_folder does that.
 * @return false with errno.
 */
bool hl_fileio_commit_tmp(int fd, const char *tmp, const char *path, const char **step);

#endif
