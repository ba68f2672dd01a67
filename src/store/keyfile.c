/* keyfile.c - loading the request-signing key (see keyfile.h). */
#include "houghloc/keyfile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <sodium.h>

static hl_status_t refuse(char *why, hl_status_t st, const char *path, const char *what)
{
    if (why)
        snprintf(why, HL_KEYFILE_WHY_LEN, "key file %s: %s", path, what);
    return st;
}

/* systemd's credentials folder ($CREDENTIALS_DIRECTORY, private to the service) may grant
 * the service's group read access through an ACL where it cannot use ramfs: allow that
 * there, and nowhere else. */
static bool in_credentials(const char *path)
{
    const char *dir = getenv("CREDENTIALS_DIRECTORY");
    size_t n = dir ? strlen(dir) : 0;
    return n > 0 && strncmp(path, dir, n) == 0 && path[n] == '/' && !strstr(path + n, "..");
}

/* Checks the open file, not the path, so that nothing can be swapped in between. */
static hl_status_t check_file(int fd, const char *path, char *why)
{
    struct stat st;
    if (fstat(fd, &st) != 0)
        return refuse(why, HL_ERR_OS, path, strerror(errno));
    if (S_ISDIR(st.st_mode))
        return refuse(why, HL_ERR_RANGE, path, "is a directory, not a key file");
    if (!S_ISREG(st.st_mode))
        return refuse(why, HL_ERR_RANGE, path,
                      "not a regular file (a FIFO, a device or a socket)");
    if (st.st_mode & (in_credentials(path) ? 027 : 077)) {
        if (why)
            snprintf(why, HL_KEYFILE_WHY_LEN,
                     "key file %s: mode %04o lets group or others read or write the key: "
                     "run chmod 600 %s",
                     path, (unsigned)(st.st_mode & 07777), path);
        return HL_ERR_RANGE;
    }
    if (st.st_size > HL_KEYFILE_MAX_BYTES) {
        if (why)
            snprintf(why, HL_KEYFILE_WHY_LEN,
                     "key file %s: larger than %d bytes (%lld bytes); a key file holds 64 "
                     "hexadecimal digits and a newline",
                     path, HL_KEYFILE_MAX_BYTES, (long long)st.st_size);
        return HL_ERR_RANGE;
    }
    return HL_OK;
}

/* Reads at most cap bytes; *len > HL_KEYFILE_MAX_BYTES means the file grew meanwhile. */
static hl_status_t read_all(int fd, char *buf, size_t cap, size_t *len)
{
    *len = 0;
    while (*len < cap) {
        ssize_t n = read(fd, buf + *len, cap - *len);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            return HL_ERR_OS;
        if (n == 0)
            break;
        *len += (size_t)n;
    }
    return HL_OK;
}

hl_status_t hl_keyfile_load(const char *path, hl_auth_key_t *key, char *why)
{
    if (!path || !key) {
        if (why)
            snprintf(why, HL_KEYFILE_WHY_LEN, "key file: no path");
        return HL_ERR_ARG;
    }
    /* O_NONBLOCK: a FIFO must not hang the open; it is refused by check_file. */
    int fd = open(path, O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
    if (fd < 0) {
        int err = errno;
        hl_status_t st = refuse(why, HL_ERR_OS, path,
                                err == ELOOP ? "is a symbolic link; name the key file itself"
                                             : strerror(err));
        errno = err;
        return st;
    }
    char buf[HL_KEYFILE_MAX_BYTES + 1];
    size_t len = 0;
    hl_status_t st = check_file(fd, path, why);
    if (st == HL_OK && read_all(fd, buf, sizeof buf, &len) != HL_OK)
        st = refuse(why, HL_ERR_OS, path, strerror(errno));
    int err = errno;
    close(fd);
    if (st == HL_OK && len > HL_KEYFILE_MAX_BYTES) {
        st = HL_ERR_RANGE;
        if (why)
            snprintf(why, HL_KEYFILE_WHY_LEN, "key file %s: larger than %d bytes (it grew "
                     "while being read)", path, HL_KEYFILE_MAX_BYTES);
    }
    if (st == HL_OK) {
        char reason[HL_BUS_WHY_LEN];
        hl_auth_key_t k;
        if (hl_auth_parse_key(buf, len, &k, reason))
            *key = k;
        else
            st = refuse(why, HL_ERR_PARSE, path, reason);
        sodium_memzero(&k, sizeof k);
    }
    sodium_memzero(buf, sizeof buf);
    errno = err;
    return st;
}
