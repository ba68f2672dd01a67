/* mapstore_lock.c - one process per map file (hl_mapstore_lock in mapstore.h). */
#include "houghloc/mapstore.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "fileio.h"

#define PID_TRIES 20        /* a lock's holder is read for up to 20 x 5 ms */

/* "PATH: text" in @p why (may be NULL), one line (hl_fileio_why). @return @p st. */
static hl_status_t __attribute__((format(printf, 4, 5)))
fail(hl_status_t st, char *why, const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    hl_fileio_why(why, HL_MAPSTORE_WHY_LEN, path ? path : "(null)", fmt, ap);
    va_end(ap);
    return st;
}

/*
 * Why a lock file beside the map rather than a lock on the map itself: a save replaces
 * the map by rename(), and a lock belongs to an inode, not a name. A lock on the map would
 * stay on the file the first save replaced, and a second process opening PATH after that
 * save would lock the new inode, which nobody holds; the map may also not exist yet, or be
 * moved aside (--fresh-map). PATH.lock is never replaced, renamed or removed (removing it
 * would let one process lock a new PATH.lock while another still holds the old inode), so
 * its one inode is the map's one lock. Nor the folder: several maps may share one.
 *
 * flock(2) rather than fcntl(2) record locks: a flock belongs to the open file
 * description, so nothing else the process opens and closes can drop it (a record lock
 * goes with the first close of any descriptor of the file), and two opens of the file in
 * one process exclude each other too (the unit tests rely on it). The kernel drops the
 * lock when the process ends, however it ends (kill -9 too): no stale lock survives its
 * holder, whatever pid the file still holds.
 */

/* The pid written in the lock file, 0 when there is none. */
static pid_t read_pid(int fd)
{
    char text[32];
    ssize_t n;
    HL_FILEIO_RETRY(n, pread(fd, text, sizeof text - 1, 0));
    if (n <= 0)
        return 0;
    text[n] = '\0';
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (errno != 0 || end == text || (*end != '\n' && *end != '\0') || v <= 0 || v > INT_MAX)
        return 0;
    return (pid_t)v;
}

/* The holder's pid, 0 when unknown. A holder writes it right after it takes the lock, so
 * an empty file or a pid that names no process (a killed holder's, still in the file) can
 * mean that it has not yet: read again for up to PID_TRIES x 5 ms. A pid that still names
 * no process is not reported (a holder that could not write the file, or one in another
 * pid namespace): better no pid than a wrong one. */
static pid_t holder_pid(int fd)
{
    for (int i = 0; i < PID_TRIES; i++) {
        pid_t pid = read_pid(fd);
        if (pid > 0 && (kill(pid, 0) == 0 || errno == EPERM))
            return pid;
        nanosleep(&(struct timespec){ .tv_nsec = 5000000 }, NULL);
    }
    return 0;
}

int hl_mapstore_lock(const char *path, pid_t *holder, char *why)
{
    if (holder)
        *holder = 0;
    if (!path) {
        errno = EINVAL;
        fail(HL_ERR_ARG, why, path, "lock: no path");
        return -1;
    }
    char name[PATH_MAX];
    if ((size_t)snprintf(name, sizeof name, "%s" HL_MAPSTORE_LOCK_SUFFIX, path) >= sizeof name) {
        errno = ENAMETOOLONG;
        fail(HL_ERR_OS, why, path, "cannot lock: the path is too long");
        return -1;
    }
    /* O_NOFOLLOW: a symlink planted at PATH.lock must not make us create or truncate
     * another file; O_NONBLOCK: a FIFO there must not hang the start. */
    int fd;
    HL_FILEIO_RETRY(fd, open(name, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644));
    if (fd < 0 && errno == EACCES)  /* another user's lock file: flock needs no write */
        HL_FILEIO_RETRY(fd, open(name, O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK));
    if (fd < 0) {
        fail(HL_ERR_OS, why, path, "cannot open its lock file %s: %s", name, strerror(errno));
        return -1;
    }
    struct stat sb;
    if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        hl_fileio_close_quietly(fd);
        errno = EINVAL;
        fail(HL_ERR_OS, why, path, "its lock file %s is not a regular file", name);
        return -1;
    }
    int r;
    HL_FILEIO_RETRY(r, flock(fd, LOCK_EX | LOCK_NB));
    if (r != 0) {
        int err = errno;
        pid_t pid = err == EWOULDBLOCK ? holder_pid(fd) : 0;
        hl_fileio_close_quietly(fd);
        if (holder)
            *holder = pid;
        errno = err;
        if (err != EWOULDBLOCK)
            fail(HL_ERR_OS, why, path, "cannot lock %s: %s", name, strerror(err));
        else if (pid > 0)
            fail(HL_ERR_OS, why, path, "in use by pid %ld (lock %s)", (long)pid, name);
        else
            fail(HL_ERR_OS, why, path, "in use by another process (lock %s)", name);
        return -1;
    }
    /* The pid goes in before the old text is cut to its length, so that a reader sees one
     * pid or the other, never an empty file (but a new one's). A failure here (a file
     * opened read-only) keeps the lock: the lock is what counts; the pid only names the
     * holder. */
    char text[24];
    int n = snprintf(text, sizeof text, "%ld\n", (long)getpid());
    ssize_t w;
    HL_FILEIO_RETRY(w, pwrite(fd, text, (size_t)n, 0));
    if (w == n) {
        HL_FILEIO_RETRY(r, ftruncate(fd, n));
    }
    if (why)
        why[0] = '\0';
    return fd;
}

void hl_mapstore_unlock(int fd)
{
    if (fd < 0)
        return;
    /* emptied while still held, so no later holder's pid is cut */
    int r;
    HL_FILEIO_RETRY(r, ftruncate(fd, 0));
    (void)r;
    hl_fileio_close_quietly(fd);
}
