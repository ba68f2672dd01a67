/*
 * sender.h - the console's DESTINATION and STOP messages (private to tools/console):
 * stamped with a seq from the wall clock (stamp.h: as houghloc-goto does, so that the
 * console and the command-line clients share the daemon's increasing seq), signed with
 * the daemon's key when one was given (the key is loaded once, by the store's keyfile
 * loader, and never leaves this module), encoded by the bus codec and published on the
 * console's own LCM instance, without waiting: the answer comes back on REPLY like any
 * other. Nothing here limits how often a STOP may leave.
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_SENDER_H
#define HOUGHLOC_TOOLS_CONSOLE_SENDER_H

#include <stdbool.h>
#include <stdint.h>

#include <lcm/lcm.h>

#include "houghloc/auth.h"
#include "houghloc/bus.h"
#include "houghloc/keyfile.h"

#define SENDER_KEPT 64      /* seqs remembered, to tell the console's replies apart */

typedef struct sender {
    lcm_t *lcm;
    char channel[HL_BUS_CHANNEL_MAX];           /* DESTINATION, with the prefix */
    char command_channel[HL_BUS_CHANNEL_MAX];   /* COMMAND, with the prefix */
    char prefix[HL_BUS_PREFIX_MAX + 1];         /* which every MAC covers (auth.h) */
    bool has_key;
    hl_auth_key_t key;
    int64_t last_seq;
    int64_t mine[SENDER_KEPT];
    unsigned next;
    unsigned long sent, stops;
} sender_t;

/**
 * Prepares to publish on @p prefix + DESTINATION and COMMAND with @p lcm, loading the key file
 * @p key_file (NULL: unsigned).
 * @return HL_OK, or the key file loader's status with one line in @p why
 *         (HL_KEYFILE_WHY_LEN bytes).
 */
hl_status_t sender_init(sender_t *s, lcm_t *lcm, const char *prefix, const char *key_file,
                        char *why);

/**
 * Stamps (utime, seq), signs and publishes @p d (x, y and heading filled by the caller).
 * @return HL_OK; HL_ERR_RANGE when it does not encode; HL_ERR_OS when LCM refuses it.
 */
hl_status_t sender_send(sender_t *s, hl_bus_destination_t *d);

/**
 * Stamps, signs (with the key, when there is one) and publishes one STOP command on
 * COMMAND; @p c receives what was sent. @return as sender_send.
 */
hl_status_t sender_stop(sender_t *s, hl_bus_command_t *c);

/**
 * Whether REPLY @p r may be shown as the daemon's: always without a key; with one, only
 * when its MAC is right for the key and the prefix (a forged REPLY, or the answer of a
 * daemon without the key, is not).
 */
bool sender_reply_authentic(const sender_t *s, const hl_bus_reply_t *r);

/** @return true when @p seq is one of the last SENDER_KEPT the console sent. */
bool sender_is_mine(const sender_t *s, int64_t seq);

/** Wipes the key. */
void sender_free(sender_t *s);

#endif
