/* fileio.c - the POSIX calls the store's files share (fileio.h). */
#include "fileio.h"

#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

void hl_fileio_why(char *why, size_t cap, const char *path, const char *fmt, va_list ap)
{
    if (!why || cap == 0)
        return;
    int saved = errno;
    int n = path ? snprintf(why, cap / 2, "%s: ", path) : 0;
    if (n < 0 || (size_t)n >= cap / 2)
        n = path ? (int)strlen(why) : 0;
    vsnprintf(why + n, cap - (size_t)n, fmt, ap);
    for (unsigned char *p = (unsigned char *)why; *p; p++)
        if (*p < 0x20 || *p == 0x7f)
            *p = '?';
    errno = saved;
}

bool hl_fileio_write_all(int fd, const uint8_t *b, size_t n)
{
    while (n > 0) {
        ssize_t w;
        HL_FILEIO_RETRY(w, write(fd, b, n));
        if (w == 0)     /* not expected from a regular file; do not spin */
            errno = EIO;
        if (w <= 0)
            return false;
        b += w;
        n -= (size_t)w;
    }
    return true;
}

ssize_t hl_fileio_read_full(int fd, uint8_t *b, size_t n)
{
    size_t got = 0;
    while (got < n) {
        ssize_t r;
        HL_FILEIO_RETRY(r, read(fd, b + got, n - got));
        if (r < 0)
            return -1;
        if (r == 0)
            break;
        got += (size_t)r;
    }
    return (ssize_t)got;
}

int hl_fileio_fsync(int fd)
{
    int r;
    HL_FILEIO_RETRY(r, fsync(fd));
    return r;
}

void hl_fileio_close_quietly(int fd)
{
    int saved = errno;
    close(fd);
    errno = saved;
}

bool hl_fileio_sync_folder(const char *path)
{
    char dir[PATH_MAX];
    const char *slash = strrchr(path, '/');
    int len = !slash ? 1 : slash == path ? 1 : (int)(slash - path);
    snprintf(dir, sizeof dir, "%.*s", len, !slash ? "." : path);
    int fd;
    HL_FILEIO_RETRY(fd, open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (fd < 0)
        return false;
    bool ok = hl_fileio_fsync(fd) == 0;
    hl_fileio_close_quietly(fd);
    return ok;
}

/* A symlink planted at PATH.tmp does not redirect the write (O_NOFOLLOW); a stale one (a
 * crash mid-save) is simply truncated. */
static int open_tmp(const char *tmp)
{
    int fd;
    HL_FILEIO_RETRY(fd, open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644));
    return fd;
}

/* fsync, close (which reports late write-back errors: on NFS the file may be short),
 * rename. @return NULL, or the call that failed, with errno. */
static const char *commit_tmp(int fd, const char *tmp, const char *path)
{
    if (hl_fileio_fsync(fd) != 0) {
        hl_fileio_close_quietly(fd);
        return "fsync";
    }
    if (close(fd) != 0)
        return "close";
    if (rename(tmp, path) != 0)
        return "rename";
    return NULL;
}

bool hl_fileio_replace(const char *path, hl_fileio_writer_t write, const void *ctx,
                       char *reason, size_t cap)
{
    char tmp[PATH_MAX];
    if ((size_t)snprintf(tmp, sizeof tmp, "%s.tmp", path) >= sizeof tmp) {
        snprintf(reason, cap, "not saved: the path is too long");
        errno = ENAMETOOLONG;
        return false;
    }
    int fd = open_tmp(tmp);
    if (fd < 0) {
        snprintf(reason, cap, "not saved: cannot create %s: %s", tmp, strerror(errno));
        return false;
    }
    const char *step = NULL;
    if (!write(fd, ctx)) {
        step = "write";
        hl_fileio_close_quietly(fd);
    } else {
        step = commit_tmp(fd, tmp, path);
    }
    if (step) {
        int saved = errno;
        unlink(tmp);
        snprintf(reason, cap, "not saved: %s of %s failed: %s", step, tmp, strerror(saved));
        errno = saved;
        return false;
    }
    /* The new file is whole under PATH; only the folder entry may not be on disk yet. */
    if (!hl_fileio_sync_folder(path)) {
        snprintf(reason, cap, "saved, but syncing its folder failed: %s", strerror(errno));
        return false;
    }
    return true;
}
