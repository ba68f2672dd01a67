/* access.c - the console's tokens, Host check and per-request verdict (access.h). */
#include "access.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include <sodium.h>

bool access_token_generate(char *out)
{
    if (sodium_init() < 0)
        return false;
    unsigned char raw[16];
    randombytes_buf(raw, sizeof raw);
    sodium_bin2hex(out, ACCESS_TOKEN_MAX + 1, raw, sizeof raw);
    sodium_memzero(raw, sizeof raw);
    return true;
}

bool access_token_valid(const char *s, size_t len)
{
    if (len < ACCESS_TOKEN_MIN || len > ACCESS_TOKEN_MAX)
        return false;
    for (size_t i = 0; i < len; i++) {
        char c = s[i];
        bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                  c == '-' || c == '_' || c == '.' || c == '~';
        if (!ok)
            return false;
    }
    return true;
}

static hl_status_t refuse(char *why, hl_status_t st, const char *path, const char *what)
{
    snprintf(why, ACCESS_WHY_LEN, "token file %s: %s", path, what);
    return st;
}

hl_status_t access_token_load(const char *path, char *out, char *why)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
    if (fd < 0)
        return refuse(why, HL_ERR_OS, path, strerror(errno));
    struct stat st;
    char buf[ACCESS_FILE_MAX_BYTES + 1];
    ssize_t n = -1;
    hl_status_t rc = HL_OK;
    if (fstat(fd, &st) != 0)
        rc = refuse(why, HL_ERR_OS, path, strerror(errno));
    else if (!S_ISREG(st.st_mode))
        rc = refuse(why, HL_ERR_RANGE, path, "is not a regular file");
    else if (st.st_mode & 077)
        rc = refuse(why, HL_ERR_RANGE, path,
                    "group or others may read or write it: run chmod 600 on it");
    else if ((n = read(fd, buf, sizeof buf)) < 0)
        rc = refuse(why, HL_ERR_OS, path, strerror(errno));
    else if (n > ACCESS_FILE_MAX_BYTES)
        rc = refuse(why, HL_ERR_RANGE, path, "is longer than 256 bytes");
    close(fd);
    if (rc != HL_OK)
        return rc;
    size_t len = (size_t)n;
    if (len > 0 && buf[len - 1] == '\n')
        len--;
    if (len > 0 && buf[len - 1] == '\r')
        len--;
    if (!access_token_valid(buf, len)) {
        sodium_memzero(buf, sizeof buf);
        return refuse(why, HL_ERR_PARSE, path,
                      "holds no token: 16 to 128 letters, digits, '-', '_', '.' or '~' "
                      "on one line");
    }
    memcpy(out, buf, len);
    out[len] = '\0';
    sodium_memzero(buf, sizeof buf);
    return HL_OK;
}

bool access_token_matches(const access_policy_t *p, const char *given)
{
    if (!given || p->token_len == 0)
        return false;
    /* The length is not the secret (every generated token has 32 characters); the bytes
     * are compared without an early exit. */
    size_t n = strnlen(given, ACCESS_TOKEN_MAX + 1);
    if (n != p->token_len)
        return false;
    return sodium_memcmp(given, p->token, n) == 0;
}

/* @return true when @p host is "NAME" followed by ":PORT", or NAME alone on port 80. */
static bool host_is(const char *host, const char *name, uint16_t port)
{
    size_t n = strlen(name);
    if (strncasecmp(host, name, n) != 0)
        return false;
    const char *rest = host + n;
    if (*rest == '\0')
        return port == 80;
    char want[8];
    snprintf(want, sizeof want, ":%u", (unsigned)port);
    return strcmp(rest, want) == 0;
}

bool access_host_ok(const access_policy_t *p, const char *host)
{
    if (!p->loopback)
        return true; /* the token guards it; the robot may have any name */
    if (!host)
        return false;
    static const char *const names[] = { "127.0.0.1", "localhost", "[::1]" };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (host_is(host, names[i], p->port))
            return true;
    return p->bound_host[0] && host_is(host, p->bound_host, p->port);
}

access_verdict_t access_decide(const access_policy_t *p, const access_request_t *r)
{
    if (!access_host_ok(p, r->host))
        return ACCESS_BAD_HOST;
    if (r->changes_state)
        return access_token_matches(p, r->header_token) ? ACCESS_ALLOW : ACCESS_NEED_TOKEN;
    if (p->loopback)
        return ACCESS_ALLOW;
    return access_token_matches(p, r->header_token) || access_token_matches(p, r->query_token)
               ? ACCESS_ALLOW
               : ACCESS_NEED_TOKEN;
}
