/*
 * auth.h - message authentication for DESTINATION and COMMAND (libsodium's crypto_auth,
 * HMAC-SHA-512-256 with a 32-byte key).
 *
 * The MAC covers the whole message as the bus encodes it (bus.h: fingerprint hash and
 * every field) with the mac field set to all zero bytes, so no field can be changed or
 * moved between message types without breaking it. Freshness is the caller's business:
 * the daemon accepts a request only if its seq is above the last accepted one.
 */
#ifndef HOUGHLOC_AUTH_H
#define HOUGHLOC_AUTH_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/bus.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_AUTH_KEY_BYTES 32

typedef struct hl_auth_key {
    uint8_t bytes[HL_AUTH_KEY_BYTES];
} hl_auth_key_t;

/** Initializes libsodium; call once before the others. @return false if it cannot. */
bool hl_auth_init(void);

/** Fills d->mac. @return false if the message does not encode (a field out of range). */
bool hl_auth_sign_destination(const hl_auth_key_t *key, hl_bus_destination_t *d);
bool hl_auth_sign_command(const hl_auth_key_t *key, hl_bus_command_t *c);

/** @return true when the MAC is right (constant-time comparison). */
bool hl_auth_check_destination(const hl_auth_key_t *key, const hl_bus_destination_t *d);
bool hl_auth_check_command(const hl_auth_key_t *key, const hl_bus_command_t *c);

/**
 * Parses a key file's text: exactly 64 hexadecimal digits, optionally followed by a
 * newline (`head -c 32 /dev/urandom | xxd -p -c 64` makes one).
 * @return false with a one-line reason in @p why (HL_BUS_WHY_LEN bytes).
 */
bool hl_auth_parse_key(const char *text, size_t len, hl_auth_key_t *out, char *why);

#ifdef __cplusplus
}
#endif
#endif
