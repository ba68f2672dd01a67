/* config_file.c - reading a configuration file whole, checked (config_file.h). */
#include "config_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "config.h"

#define WHY(...) snprintf(why, HL_CONFIG_WHY_LEN, __VA_ARGS__)
#define PATH_SHOWN "%.300s"     /* a bounded path, so that the reason fits */

static const char *kind_of(mode_t mode)
{
    return S_ISDIR(mode) ? "a directory" : S_ISFIFO(mode) ? "a FIFO"
           : S_ISCHR(mode) ? "a character device" : S_ISBLK(mode) ? "a block device"
           : S_ISSOCK(mode) ? "a socket" : "not a file";
}

/* /dev/null is the one device allowed: `--config /dev/null` is how the documentation
 * and the tests say "no file, the compiled-in defaults". */
static bool is_dev_null(const struct stat *st)
{
    struct stat null;
    return S_ISCHR(st->st_mode) && stat("/dev/null", &null) == 0 && S_ISCHR(null.st_mode) &&
           st->st_rdev == null.st_rdev;
}

/* Reads at most @p max + 1 bytes (one more tells that the file grew past @p max since the
 * check), the buffer grown as needed: a file's size may be 0 and its content not (/proc).
 * @return the bytes read, NUL-terminated, with *len; NULL with errno on an error. */
static char *read_bounded(int fd, off_t size_hint, size_t max, size_t *len)
{
    size_t cap = (size_t)size_hint < max ? (size_t)size_hint + 2 : max + 2;
    char *buf = malloc(cap);
    *len = 0;
    while (buf) {
        if (*len + 1 == cap) {
            if (*len > max)
                break;
            size_t bigger = cap * 2 < max + 2 ? cap * 2 : max + 2;
            char *b = realloc(buf, bigger);
            if (!b) {
                free(buf);
                return NULL;
            }
            buf = b;
            cap = bigger;
        }
        ssize_t n = read(fd, buf + *len, cap - 1 - *len);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0) {
            int err = errno;
            free(buf);
            errno = err;
            return NULL;
        }
        if (n == 0)
            break;
        *len += (size_t)n;
    }
    if (buf)
        buf[*len] = '\0';
    return buf;
}

/* The first NUL byte's line (1 is the first), 0 if none: libinih would end the line there
 * and misread the rest. */
static int nul_line(const char *text, size_t len)
{
    const char *nul = memchr(text, '\0', len);
    if (!nul)
        return 0;
    int line = 1;
    for (const char *s = text; s < nul; s++)
        line += *s == '\n';
    return line;
}

/* Checks the open file and reads it. @return the text, or NULL with why. */
static char *read_checked(int fd, const char *path, char *why)
{
    struct stat st;
    if (fstat(fd, &st) != 0)
        return WHY(PATH_SHOWN ": %s", path, strerror(errno)), NULL;
    if (is_dev_null(&st)) {
        char *empty = calloc(1, 1);
        if (!empty)
            WHY(PATH_SHOWN ": out of memory while reading", path);
        return empty;
    }
    if (!S_ISREG(st.st_mode))
        return WHY(PATH_SHOWN ": not a regular file (%s); a configuration file must be one",
                   path, kind_of(st.st_mode)), NULL;
    if (st.st_size > HL_CONFIG_FILE_MAX_BYTES)
        return WHY(PATH_SHOWN ": larger than %d bytes (%lld bytes), too large for a "
                   "configuration file", path, HL_CONFIG_FILE_MAX_BYTES,
                   (long long)st.st_size), NULL;
    size_t len;
    char *text = read_bounded(fd, st.st_size, HL_CONFIG_FILE_MAX_BYTES, &len);
    if (!text)
        return WHY(PATH_SHOWN ": read error: %s", path, strerror(errno)), NULL;
    if (len > HL_CONFIG_FILE_MAX_BYTES) {
        free(text);
        return WHY(PATH_SHOWN ": larger than %d bytes (it grew while being read), too large "
                   "for a configuration file", path, HL_CONFIG_FILE_MAX_BYTES), NULL;
    }
    int line = nul_line(text, len);
    if (line > 0) {
        free(text);
        return WHY(PATH_SHOWN ":%d: holds a NUL byte; a configuration file is text", path,
                   line), NULL;
    }
    return text;
}

hl_config_file_status_t hl_config_file_read(const char *path, char **text, char *why)
{
    *text = NULL;
    /* O_NONBLOCK: a FIFO must not hang the open (its fstat then refuses it); it changes
     * nothing for a regular file. O_NOCTTY: a terminal named by mistake does not become
     * the daemon's controlling terminal. */
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
    if (fd < 0) {
        int err = errno;
        WHY(PATH_SHOWN ": cannot open: %s", path, strerror(err));
        return err == ENOENT ? HL_CONFIG_FILE_MISSING : HL_CONFIG_FILE_BAD;
    }
    *text = read_checked(fd, path, why);
    close(fd);
    return *text ? HL_CONFIG_FILE_OK : HL_CONFIG_FILE_BAD;
}
