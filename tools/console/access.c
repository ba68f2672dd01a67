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

bool access_policy_init(access_policy_t *p, bool loopback, uint16_t port, const char *host,
                        const char *token)
{
    *p = (access_policy_t){ .loopback = loopback, .port = port };
    snprintf(p->bound_host, sizeof p->bound_host, "%s", host);
    p->token_len = strnlen(token, ACCESS_TOKEN_MAX);
    memcpy(p->token, token, p->token_len);
    snprintf(p->cookie_name, sizeof p->cookie_name, "houghloc_%u", (unsigned)port);
    if (sodium_init() < 0)
        return false;
    /* The session is not the token itself: what the browser keeps is not what was
     * printed, yet the same token (--token-file) gives the same session after a restart. */
    static const char label[] = "houghloc-console session cookie";
    unsigned char h[ACCESS_SESSION_LEN / 2];
    crypto_generichash_state st;
    crypto_generichash_init(&st, NULL, 0, sizeof h);
    crypto_generichash_update(&st, (const unsigned char *)label, sizeof label);
    crypto_generichash_update(&st, (const unsigned char *)p->token, p->token_len);
    crypto_generichash_final(&st, h, sizeof h);
    sodium_bin2hex(p->session, sizeof p->session, h, sizeof h);
    sodium_memzero(h, sizeof h);
    return true;
}

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

/* A new, empty file of mode 0600 beside @p path (its name in @p tmp); @return its fd
 * or -1. */
static int temp_beside(const char *path, char *tmp, size_t cap)
{
    for (int attempt = 0; attempt < 8; attempt++) {
        unsigned char r[6];
        char hex[13];
        randombytes_buf(r, sizeof r);
        sodium_bin2hex(hex, sizeof hex, r, sizeof r);
        if ((size_t)snprintf(tmp, cap, "%s.%s.tmp", path, hex) >= cap) {
            errno = ENAMETOOLONG;
            return -1;
        }
        int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
        if (fd >= 0 || errno != EEXIST)
            return fd;
    }
    return -1;
}

hl_status_t access_token_save(const char *path, const char *token, char *why)
{
    if (sodium_init() < 0) {
        snprintf(why, ACCESS_WHY_LEN, "token file %s: libsodium does not initialize", path);
        return HL_ERR_OS;
    }
    char tmp[4096];
    int fd = temp_beside(path, tmp, sizeof tmp);
    if (fd < 0)
        return refuse(why, HL_ERR_OS, path, strerror(errno));
    size_t n = strlen(token);
    bool ok = fchmod(fd, 0600) == 0 && write(fd, token, n) == (ssize_t)n &&
              write(fd, "\n", 1) == 1 && fsync(fd) == 0;
    int err = errno;
    ok = close(fd) == 0 && ok;
    if (ok && rename(tmp, path) == 0)
        return HL_OK;
    err = ok ? errno : err;
    unlink(tmp);
    return refuse(why, HL_ERR_OS, path, strerror(err));
}

/* @return the token of "Bearer TOKEN" (the scheme in any case, spaces after it), or NULL. */
static const char *bearer(const char *authorization)
{
    if (!authorization || strncasecmp(authorization, "Bearer ", 7) != 0)
        return NULL;
    const char *t = authorization + 7;
    while (*t == ' ')
        t++;
    return t;
}

/* @return true when @p origin is "http://" followed by @p host (any case). */
static bool same_origin(const char *origin, const char *host)
{
    return origin && host && strncasecmp(origin, "http://", 7) == 0 &&
           strcasecmp(origin + 7, host) == 0;
}

access_verdict_t access_decide(const access_policy_t *p, const access_request_t *r)
{
    if (!access_host_ok(p, r->host))
        return ACCESS_BAD_HOST;
    if (r->page && r->query_token)
        return access_token_matches(p, r->query_token) ? ACCESS_EXCHANGE : ACCESS_BAD_TOKEN;
    if (r->changes_state && r->origin && !same_origin(r->origin, r->host))
        return ACCESS_BAD_ORIGIN;
    const char *given = bearer(r->authorization);
    if (!given)
        given = r->header_token;
    if (given)
        return access_token_matches(p, given) ? ACCESS_ALLOW : ACCESS_BAD_TOKEN;
    if (!r->cookie)
        return ACCESS_NEED_TOKEN;
    size_t n = strnlen(r->cookie, ACCESS_SESSION_LEN + 1);
    if (n != ACCESS_SESSION_LEN || sodium_memcmp(r->cookie, p->session, n) != 0)
        return ACCESS_BAD_COOKIE;
    /* a browser sends Origin with every POST: one without is not this console's page */
    if (r->changes_state && !r->origin)
        return ACCESS_BAD_ORIGIN;
    return ACCESS_ALLOW;
}

unsigned access_status(access_verdict_t v)
{
    switch (v) {
    case ACCESS_ALLOW: return 200;
    case ACCESS_EXCHANGE: return 303;
    case ACCESS_BAD_HOST:
    case ACCESS_BAD_ORIGIN: return 403;
    case ACCESS_NEED_TOKEN:
    case ACCESS_BAD_TOKEN:
    case ACCESS_BAD_COOKIE: return 401;
    }
    return 403;
}

const char *access_reason(access_verdict_t v)
{
    switch (v) {
    case ACCESS_ALLOW: return "allowed";
    case ACCESS_EXCHANGE: return "signed in: the session cookie is set";
    case ACCESS_BAD_HOST: return "the Host header does not name this console's address";
    case ACCESS_BAD_ORIGIN: return "the request does not come from this console's own page "
                                   "(its Origin header)";
    case ACCESS_NEED_TOKEN: return "sign in first: open the address with ?token= that "
                                   "houghloc-console printed at start (scripts: send "
                                   "Authorization: Bearer TOKEN)";
    case ACCESS_BAD_TOKEN: return "the token is wrong";
    case ACCESS_BAD_COOKIE: return "the session cookie is not this console's: open the "
                                   "address with ?token= printed at start again";
    }
    return "refused";
}

void access_set_cookie(const access_policy_t *p, char *out)
{
    snprintf(out, ACCESS_SET_COOKIE_LEN, "%s=%s; Path=/; HttpOnly; SameSite=Strict",
             p->cookie_name, p->session);
}
