/*
 * access.h - who may use the console (private to tools/console): the per-run token, the
 * session cookie it is exchanged for, the Host and Origin checks, and the decision for
 * one request. Pure apart from libsodium (random bytes, a hash) and the token files.
 *
 * The model (docs/manual/houghloc-console.md, "Access"). The console signs what it
 * publishes with --key, so using it is as good as holding the key: only who has proven
 * that it read the token may use it, and the token goes only where the operator who
 * started the console can read (standard error, or a file of mode 0600: --token-out).
 *   - Every route needs a credential: the token as `Authorization: Bearer TOKEN` or
 *     X-Houghloc-Token (scripts), or the session cookie. The page carries no token.
 *   - The page's first load exchanges the token for the cookie: GET /?token=TOKEN is
 *     answered 303 to / with Set-Cookie NAME=SESSION; HttpOnly; SameSite=Strict; Path=/.
 *     The session is a hash of the token (the page's scripts cannot read the cookie,
 *     other sites' pages do not send it). NAME carries the port: cookies do not tell
 *     the ports of one host apart, and two consoles must not overwrite each other's.
 *   - A POST proven by the cookie must also come from this console's own page: its
 *     Origin header must name the address the request was sent to, as browsers send it
 *     on every POST. A page of another port of the same host is "same-site" to the
 *     cookie, but not the same origin. A POST proven by a header needs no Origin (a page
 *     of another origin cannot send the header without a CORS preflight, which this
 *     server never grants), but one it does carry must be this console's.
 *   - On a loopback bind, the Host header must name the loopback address with the bound
 *     port, which stops DNS rebinding.
 * Tokens and sessions are compared in constant time (sodium_memcmp).
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_ACCESS_H
#define HOUGHLOC_TOOLS_CONSOLE_ACCESS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc/status.h"

#define ACCESS_TOKEN_MIN 16
#define ACCESS_TOKEN_MAX 128
#define ACCESS_SESSION_LEN 32               /* hexadecimal digits */
#define ACCESS_FILE_MAX_BYTES 256
#define ACCESS_WHY_LEN 256
#define ACCESS_HEADER "X-Houghloc-Token"
#define ACCESS_SET_COOKIE_LEN 128

typedef struct access_policy {
    bool loopback;                      /* bound to a loopback address */
    uint16_t port;                      /* the bound port, for the Host check */
    char bound_host[64];                /* the address as given to --listen */
    char token[ACCESS_TOKEN_MAX + 1];
    size_t token_len;
    char cookie_name[24];               /* "houghloc_PORT" */
    char session[ACCESS_SESSION_LEN + 1];   /* the cookie's value */
} access_policy_t;

/* What a request asks, as the HTTP layer found it; NULL for anything absent. */
typedef struct access_request {
    bool changes_state;                 /* POST (anything but GET and HEAD) */
    bool page;                          /* GET or HEAD of "/": where ?token= is taken */
    const char *host;                   /* the Host header */
    const char *origin;                 /* the Origin header */
    const char *authorization;          /* the Authorization header, whole */
    const char *header_token;           /* X-Houghloc-Token */
    const char *cookie;                 /* the value of the cookie named cookie_name */
    const char *query_token;            /* ?token= */
} access_request_t;

typedef enum access_verdict {
    ACCESS_ALLOW = 0,
    ACCESS_EXCHANGE,        /* the page with the right ?token=: set the cookie, redirect */
    ACCESS_BAD_HOST,        /* 403: loopback bind, Host names another site */
    ACCESS_BAD_ORIGIN,      /* 403: a POST from a page of another origin */
    ACCESS_NEED_TOKEN,      /* 401: no credential at all */
    ACCESS_BAD_TOKEN,       /* 401: a token that is not this console's */
    ACCESS_BAD_COOKIE,      /* 401: a session cookie that is not this run's */
} access_verdict_t;

/**
 * Fills @p p: the bind (@p loopback, @p port, @p host as given to --listen), the token
 * (@p token, already valid), the cookie's name and the session derived from the token.
 * @return false when libsodium cannot start.
 */
bool access_policy_init(access_policy_t *p, bool loopback, uint16_t port, const char *host,
                        const char *token);

/** A fresh token: 16 random bytes (randombytes_buf) as 32 lowercase hex digits.
 *  @param out ACCESS_TOKEN_MAX + 1 bytes. @return false when libsodium cannot start. */
bool access_token_generate(char *out);

/**
 * Checks a token's text: ACCESS_TOKEN_MIN..ACCESS_TOKEN_MAX characters, each a letter,
 * a digit, '-', '_', '.' or '~' (those a URL carries unescaped).
 */
bool access_token_valid(const char *s, size_t len);

/**
 * Reads a token file: a regular file of at most ACCESS_FILE_MAX_BYTES, not readable or
 * writable by group or others (the token is a password), holding one valid token and
 * optionally one newline.
 * @param[out] out  ACCESS_TOKEN_MAX + 1 bytes, written only on success.
 * @param[out] why  one line naming the file and the fault (ACCESS_WHY_LEN bytes).
 * @return HL_OK, HL_ERR_OS (cannot open or read), HL_ERR_RANGE (not regular, too large,
 *         open to others), HL_ERR_PARSE (not a token).
 */
hl_status_t access_token_load(const char *path, char *out, char *why);

/**
 * Writes @p token and a newline to @p path, mode 0600: into a new file beside it, then
 * renamed over it, so that no one who opened an older file there reads the new token.
 * @param[out] why  one line naming the file and the fault (ACCESS_WHY_LEN bytes).
 * @return HL_OK, or HL_ERR_OS.
 */
hl_status_t access_token_save(const char *path, const char *token, char *why);

/** @return true when @p given (may be NULL) is the policy's token, in constant time
 *          for a given length. */
bool access_token_matches(const access_policy_t *p, const char *given);

/** @return true when @p host (may be NULL) is acceptable under the policy. */
bool access_host_ok(const access_policy_t *p, const char *host);

/**
 * The verdict for one request, in this order: the Host; the ?token= of the page
 * (EXCHANGE or BAD_TOKEN); a token in a header (Authorization: Bearer, or
 * X-Houghloc-Token); the cookie; else NEED_TOKEN. A POST's Origin, when it has one or
 * is proven by the cookie, must be "http://" followed by its Host.
 */
access_verdict_t access_decide(const access_policy_t *p, const access_request_t *r);

/** The HTTP status of a verdict (200 for ALLOW, 303 for EXCHANGE). */
unsigned access_status(access_verdict_t v);
/** The one-line reason a verdict refuses (for ALLOW and EXCHANGE, a description). */
const char *access_reason(access_verdict_t v);

/** The Set-Cookie value of the exchange into @p out (ACCESS_SET_COOKIE_LEN bytes). */
void access_set_cookie(const access_policy_t *p, char *out);

#endif
