/*
 * access.h - who may use the console (private to tools/console): the per-run token, the
 * Host check against DNS rebinding, and the decision for one request. Pure apart from
 * access_token_generate (libsodium's randombytes_buf) and access_token_load (a file).
 *
 * The model (docs/manual/houghloc-console.md, "Access"):
 *   - loopback bind (the default, 127.0.0.1): anyone on this host may view without a
 *     token, as anyone on it may already listen to the LCM group; the Host header must
 *     name the loopback address or localhost with the bound port, so that a web page
 *     whose name an attacker re-points at 127.0.0.1 (DNS rebinding) is refused;
 *   - any other bind (--listen): every request needs the token, in the
 *     X-Houghloc-Token header or as ?token= in the URL (the page's first load, and the
 *     event stream, as EventSource cannot set headers);
 *   - either way a state-changing request (POST) needs the token in the header: a
 *     custom header makes a browser ask the server first (CORS preflight), which this
 *     server never grants, so no other site can forge a click; never a cookie.
 * Tokens are compared in constant time (sodium_memcmp).
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_ACCESS_H
#define HOUGHLOC_TOOLS_CONSOLE_ACCESS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc/status.h"

#define ACCESS_TOKEN_MIN 16
#define ACCESS_TOKEN_MAX 128
#define ACCESS_FILE_MAX_BYTES 256
#define ACCESS_WHY_LEN 256
#define ACCESS_HEADER "X-Houghloc-Token"

typedef struct access_policy {
    bool loopback;                      /* bound to a loopback address */
    uint16_t port;                      /* the bound port, for the Host check */
    char bound_host[64];                /* the address as given to --listen */
    char token[ACCESS_TOKEN_MAX + 1];
    size_t token_len;
} access_policy_t;

/* What a request asks, as the HTTP layer found it; NULL for anything absent. */
typedef struct access_request {
    bool changes_state;                 /* POST */
    const char *host;                   /* the Host header */
    const char *header_token;           /* X-Houghloc-Token */
    const char *query_token;            /* ?token= */
} access_request_t;

typedef enum access_verdict {
    ACCESS_ALLOW = 0,
    ACCESS_BAD_HOST = 403,              /* loopback bind, Host names another site */
    ACCESS_NEED_TOKEN = 401,            /* token missing or wrong */
} access_verdict_t;

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

/** @return true when @p given (may be NULL) is the policy's token, in constant time
 *          for a given length. */
bool access_token_matches(const access_policy_t *p, const char *given);

/** @return true when @p host (may be NULL) is acceptable under the policy. */
bool access_host_ok(const access_policy_t *p, const char *host);

/** The verdict for one request (the order: Host, then token). */
access_verdict_t access_decide(const access_policy_t *p, const access_request_t *r);

#endif
