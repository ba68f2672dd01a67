/*
 * stamp.h - the console's requests as they leave (private to tools/console): a seq from
 * the wall clock, the MAC when a key is given, the bus encoding. Pure apart from
 * libsodium (the MAC; hl_auth_init first); the clock is the caller's (sender.c).
 *
 * Destinations and STOP commands share one seq: the wall clock in microseconds (as
 * houghloc-goto stamps its requests, so that the console and the command-line clients
 * share the daemon's increasing seq), above the last one even if the clock stepped back.
 * A STOP is signed like a destination when the console has a key, although the daemon
 * takes a STOP whatever its MAC and seq (houghloc_command_t.lcm).
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_STAMP_H
#define HOUGHLOC_TOOLS_CONSOLE_STAMP_H

#include <stddef.h>
#include <stdint.h>

#include "houghloc/auth.h"
#include "houghloc/bus.h"

/* Room for either encoded request. */
#define STAMP_MAX_BYTES \
    (HL_BUS_DESTINATION_BYTES > HL_BUS_COMMAND_BYTES ? HL_BUS_DESTINATION_BYTES \
                                                     : HL_BUS_COMMAND_BYTES)

/** The seq of a request made at @p now_us after one stamped @p last_seq: the clock, or
 *  last_seq + 1 when the clock is not above it (never below 1). */
int64_t stamp_seq(int64_t now_us, int64_t last_seq);

/**
 * Stamps @p d (x, y and heading filled by the caller) with utime @p now_us and @p seq,
 * signs it with @p key (NULL: the MAC all zeros) for the channels of @p prefix (auth.h;
 * "" for none) and encodes it into @p buf.
 * @return the encoded length, or -1 when it does not encode (a field out of range,
 *         @p cap too small).
 */
int stamp_destination(hl_bus_destination_t *d, int64_t now_us, int64_t seq,
                      const hl_auth_key_t *key, const char *prefix, uint8_t *buf, size_t cap);

/**
 * Writes into @p c the STOP command made at @p now_us with @p seq (kind
 * HL_BUS_COMMAND_STOP, pose zero), signed with @p key (NULL: the MAC all zeros) for
 * @p prefix, and
 * encodes it into @p buf. @return the encoded length, or -1 as stamp_destination.
 */
int stamp_stop(hl_bus_command_t *c, int64_t now_us, int64_t seq, const hl_auth_key_t *key,
               const char *prefix, uint8_t *buf, size_t cap);

#endif
