/*
 * auth.h - message authentication for DESTINATION, COMMAND and REPLY (libsodium's
 * crypto_auth, HMAC-SHA-512-256 with a 32-byte key).
 *
 * The MAC covers, in order: the channel prefix's length (one byte, 0..HL_BUS_PREFIX_MAX)
 * and its bytes (lcm.prefix / --prefix: "" for none), then the whole message as the bus
 * encodes it (bus.h: fingerprint hash and every field) with the mac field set to all zero
 * bytes. So no field can be changed or moved between message types, and a message signed
 * for one robot's channels (prefix "robot1/") is refused by a robot on another prefix
 * that shares the key. Freshness is the caller's business: the daemon accepts a request
 * only if its seq is above the last accepted one and not far ahead of its clock, and a
 * client takes a REPLY only for the seq it sent.
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

/**
 * Fills the message's mac for the channels of @p prefix (not NULL; "" for none).
 * @return false if the message does not encode (a field out of range), the prefix is
 *         longer than HL_BUS_PREFIX_MAX, or an argument is NULL (mac then unchanged).
 */
bool hl_auth_sign_destination(const hl_auth_key_t *key, const char *prefix,
                              hl_bus_destination_t *d);
bool hl_auth_sign_command(const hl_auth_key_t *key, const char *prefix, hl_bus_command_t *c);
bool hl_auth_sign_reply(const hl_auth_key_t *key, const char *prefix, hl_bus_reply_t *r);

/** @return true when the MAC is right for @p prefix (constant-time comparison); false
 *          for an all-zero MAC (unsigned), a wrong one, or a bad argument. */
bool hl_auth_check_destination(const hl_auth_key_t *key, const char *prefix,
                               const hl_bus_destination_t *d);
bool hl_auth_check_command(const hl_auth_key_t *key, const char *prefix,
                           const hl_bus_command_t *c);
bool hl_auth_check_reply(const hl_auth_key_t *key, const char *prefix, const hl_bus_reply_t *r);

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
