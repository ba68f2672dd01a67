/*
 * fileio.h - the POSIX calls the store's files share (private to src/store): EINTR
 * retried, short reads and writes completed, errno kept, and the folder fsync that
 * makes a rename durable. Every file written whole goes the same way: PATH.tmp
 * (O_NOFOLLOW), its bytes, fsync, close, rename over PATH, fsync of the folder.
 */
#ifndef HOUGHLOC_STORE_FILEIO_H
#define HOUGHLOC_STORE_FILEIO_H

#include <errno.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#define HL_FILEIO_RETRY(r, call)            \
    do                                      \
        (r) = (call);                       \
    while ((r) < 0 && errno == EINTR)

/** Writes "PATH: text" (no "PATH: " when @p path is NULL) into @p why, @p cap bytes, as
 *  one line: control characters (a newline in the path, say) become '?'. A very long
 *  path keeps its start and leaves half of @p why to the text. Keeps errno; nothing is
 *  written when @p why is NULL. */
void hl_fileio_why(char *why, size_t cap, const char *path, const char *fmt, va_list ap);

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

/** Writes a file's whole contents into @p fd. @return false with errno. */
typedef bool (*hl_fileio_writer_t)(int fd, const void *ctx);

/**
 * Replaces @p path's contents durably: PATH.tmp (created 0644, truncated if a crash left
 * one, never through a symbolic link planted there) filled by @p write, fsync, close,
 * rename over @p path, fsync of the folder. A crash at any point leaves the old file or
 * the new one, whole.
 * @return true; or false with errno and one line in @p reason (@p cap bytes): "not
 *         saved: ..." when @p path still holds the old contents (PATH.tmp removed), or
 *         "saved, but syncing its folder failed: ..." when only the folder sync failed.
 */
bool hl_fileio_replace(const char *path, hl_fileio_writer_t write, const void *ctx,
                       char *reason, size_t cap);

#endif
