/* fileio.c - the POSIX calls the store's files share (fileio.h). */
#include "fileio.h"

#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

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

int hl_fileio_open_tmp(const char *tmp)
{
    int fd;
    HL_FILEIO_RETRY(fd, open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644));
    return fd;
}

bool hl_fileio_commit_tmp(int fd, const char *tmp, const char *path, const char **step)
{
    *step = NULL;
    if (hl_fileio_fsync(fd) != 0) {
        *step = "fsync";
        hl_fileio_close_quietly(fd);
    } else if (close(fd) != 0) {    /* late write-back errors (NFS): the file may be short */
        *step = "close";
    } else if (rename(tmp, path) != 0) {
        *step = "rename";
    }
    if (!*step)
        return true;
    int saved = errno;
    unlink(tmp);
    errno = saved;
    return false;
}
