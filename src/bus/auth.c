/* auth.c - MACs on DESTINATION, COMMAND and REPLY, and key parsing (see houghloc/auth.h). */
#include "houghloc/auth.h"

#include <stdio.h>
#include <string.h>

#include <sodium.h>

_Static_assert(HL_AUTH_KEY_BYTES == crypto_auth_KEYBYTES, "key size is crypto_auth's");
_Static_assert(HL_BUS_MAC_BYTES == crypto_auth_BYTES, "mac size is crypto_auth's");

/* The largest message signed here: a reply with the longest message. */
#define AUTH_MSG_BYTES                                                                      \
    (HL_BUS_REPLY_MAX_BYTES > HL_BUS_DESTINATION_BYTES                                       \
         ? (HL_BUS_REPLY_MAX_BYTES > HL_BUS_COMMAND_BYTES ? HL_BUS_REPLY_MAX_BYTES            \
                                                          : HL_BUS_COMMAND_BYTES)           \
         : HL_BUS_DESTINATION_BYTES)
/* The signed bytes: the prefix's length and bytes, then the message. */
#define AUTH_BUF_BYTES (1 + HL_BUS_PREFIX_MAX + AUTH_MSG_BYTES)

_Static_assert(HL_BUS_PREFIX_MAX <= 255, "the prefix's length is one byte");

bool hl_auth_init(void)
{
    return sodium_init() >= 0; /* 1 when already initialized: fine */
}

/* Writes the prefix part of the signed bytes. @return its length, or -1 when the prefix
 * is missing or too long. */
static int put_prefix(const char *prefix, uint8_t *buf)
{
    if (!prefix)
        return -1;
    size_t n = strnlen(prefix, HL_BUS_PREFIX_MAX + 1);
    if (n > HL_BUS_PREFIX_MAX)
        return -1;
    buf[0] = (uint8_t)n;
    memcpy(buf + 1, prefix, n);
    return (int)(1 + n);
}

/* The signed bytes of each message: the prefix, then the message encoded by the bus
 * with its mac all zero. @return their length, or -1. */
static int signed_destination(const char *prefix, const hl_bus_destination_t *d, uint8_t *buf)
{
    int head = put_prefix(prefix, buf);
    if (head < 0)
        return -1;
    hl_bus_destination_t z = *d;
    memset(z.mac, 0, sizeof z.mac);
    int len = hl_bus_encode_destination(&z, buf + head, AUTH_BUF_BYTES - (size_t)head);
    return len < 0 ? -1 : head + len;
}

static int signed_command(const char *prefix, const hl_bus_command_t *c, uint8_t *buf)
{
    int head = put_prefix(prefix, buf);
    if (head < 0)
        return -1;
    hl_bus_command_t z = *c;
    memset(z.mac, 0, sizeof z.mac);
    int len = hl_bus_encode_command(&z, buf + head, AUTH_BUF_BYTES - (size_t)head);
    return len < 0 ? -1 : head + len;
}

static int signed_reply(const char *prefix, const hl_bus_reply_t *r, uint8_t *buf)
{
    int head = put_prefix(prefix, buf);
    if (head < 0)
        return -1;
    hl_bus_reply_t z = *r;
    memset(z.mac, 0, sizeof z.mac);
    int len = hl_bus_encode_reply(&z, buf + head, AUTH_BUF_BYTES - (size_t)head);
    return len < 0 ? -1 : head + len;
}

static bool sign(const hl_auth_key_t *key, const uint8_t *buf, int len, uint8_t *mac)
{
    if (len < 0)
        return false;
    crypto_auth(mac, buf, (unsigned long long)len, key->bytes);
    return true;
}

/* crypto_auth_verify compares in constant time. An all-zero MAC is what an unsigned
 * sender sends: refused outright, so it never reaches the comparison at all. */
static bool check(const hl_auth_key_t *key, const uint8_t *buf, int len, const uint8_t *mac)
{
    return len >= 0 && sodium_is_zero(mac, HL_BUS_MAC_BYTES) != 1 &&
           crypto_auth_verify(mac, buf, (unsigned long long)len, key->bytes) == 0;
}

bool hl_auth_sign_destination(const hl_auth_key_t *key, const char *prefix,
                              hl_bus_destination_t *d)
{
    uint8_t buf[AUTH_BUF_BYTES];
    return key && d && sign(key, buf, signed_destination(prefix, d, buf), d->mac);
}

bool hl_auth_sign_command(const hl_auth_key_t *key, const char *prefix, hl_bus_command_t *c)
{
    uint8_t buf[AUTH_BUF_BYTES];
    return key && c && sign(key, buf, signed_command(prefix, c, buf), c->mac);
}

bool hl_auth_sign_reply(const hl_auth_key_t *key, const char *prefix, hl_bus_reply_t *r)
{
    uint8_t buf[AUTH_BUF_BYTES];
    return key && r && sign(key, buf, signed_reply(prefix, r, buf), r->mac);
}

bool hl_auth_check_destination(const hl_auth_key_t *key, const char *prefix,
                               const hl_bus_destination_t *d)
{
    uint8_t buf[AUTH_BUF_BYTES];
    return key && d && check(key, buf, signed_destination(prefix, d, buf), d->mac);
}

bool hl_auth_check_command(const hl_auth_key_t *key, const char *prefix,
                           const hl_bus_command_t *c)
{
    uint8_t buf[AUTH_BUF_BYTES];
    return key && c && check(key, buf, signed_command(prefix, c, buf), c->mac);
}

bool hl_auth_check_reply(const hl_auth_key_t *key, const char *prefix, const hl_bus_reply_t *r)
{
    uint8_t buf[AUTH_BUF_BYTES];
    return key && r && check(key, buf, signed_reply(prefix, r, buf), r->mac);
}

static bool refuse(char *why, const char *what)
{
    if (why)
        snprintf(why, HL_BUS_WHY_LEN, "%s", what);
    return false;
}

static bool refuse_count(char *why, size_t digits)
{
    if (why)
        snprintf(why, HL_BUS_WHY_LEN,
                 "key has %zu hexadecimal digits: it must have exactly 64", digits);
    return false;
}

static bool is_hex(char c)
{
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

/* The reasons name positions and counts, never the key's characters. */
bool hl_auth_parse_key(const char *text, size_t len, hl_auth_key_t *out, char *why)
{
    const size_t digits = 2 * HL_AUTH_KEY_BYTES;
    if (!text || !out)
        return refuse(why, "no key text");
    if (len == 0)
        return refuse(why, "key is empty: it must be 64 hexadecimal digits");
    for (size_t i = 0; i < len && i < digits; i++) {
        if (is_hex(text[i]))
            continue;
        if (text[i] == '\n' && i + 1 == len)
            return refuse_count(why, i);
        if (why)
            snprintf(why, HL_BUS_WHY_LEN,
                     "key has a character that is not a hexadecimal digit at byte %zu", i + 1);
        return false;
    }
    if (len < digits)
        return refuse_count(why, len);
    if (len > digits && !(len == digits + 1 && text[digits] == '\n')) {
        if (is_hex(text[digits]))
            return refuse(why, "key has more than 64 hexadecimal digits");
        return refuse(why, "key has extra bytes after its 64 hexadecimal digits "
                           "(only one final newline may follow)");
    }
    hl_auth_key_t k;
    size_t got = 0;
    if (sodium_hex2bin(k.bytes, sizeof k.bytes, text, digits, NULL, &got, NULL) != 0 ||
        got != sizeof k.bytes) {
        sodium_memzero(&k, sizeof k);
        return refuse(why, "key does not decode as hexadecimal");
    }
    /* An all-zero key is a placeholder in a template, not a secret. */
    if (sodium_is_zero(k.bytes, sizeof k.bytes)) {
        sodium_memzero(&k, sizeof k);
        return refuse(why, "key is all zeros: make a random one "
                           "(head -c 32 /dev/urandom | xxd -p -c 64)");
    }
    *out = k;
    sodium_memzero(&k, sizeof k);
    return true;
}
