/*
 * flood_msg.h - malformed messages for houghlocd's input channels (private to
 * tools/lab/trials): what hl-flood publishes.
 *
 * Each message is made for one input channel (SONAR, ODOMETRY, DESTINATION, COMMAND) in
 * one of six kinds, and is checked with that channel's own decoder (houghloc/bus.h)
 * before it is handed out: only bytes the daemon must refuse leave the generator, so a
 * flood can change the daemon's counters but never its POSE stream. Everything is a
 * function of the seed.
 */
#ifndef HOUGHLOC_TOOLS_TRIALS_FLOOD_MSG_H
#define HOUGHLOC_TOOLS_TRIALS_FLOOD_MSG_H

#include <stddef.h>
#include <stdint.h>

#include "houghloc/rng.h"

/* The channels the daemon reads from LCM without a robot. */
typedef enum flood_input {
    FLOOD_SONAR,
    FLOOD_ODOMETRY,
    FLOOD_DESTINATION,
    FLOOD_COMMAND,
    FLOOD_INPUTS
} flood_input_t;

typedef enum flood_kind {
    FLOOD_RANDOM,       /* random bytes of a random length, 0..FLOOD_RANDOM_MAX */
    FLOOD_TRUNCATED,    /* a real encoding of the channel's type, cut short */
    FLOOD_FINGERPRINT,  /* a real encoding with one bit of its fingerprint flipped */
    FLOOD_WRONG_TYPE,   /* a real encoding of another message type */
    FLOOD_OVERLONG,     /* a real encoding followed by 1..16 extra bytes */
    FLOOD_BAD_FIELD,    /* a real encoding with one field out of range (negative utime,
                           a boolean byte of 2, an unknown command kind) */
    FLOOD_KINDS
} flood_kind_t;

#define FLOOD_RANDOM_MAX 700
#define FLOOD_MSG_MAX 1024      /* every message made fits in this many bytes */

/** The base channel name of @p in ("SONAR", ...); "?" when out of range. */
const char *flood_input_name(flood_input_t in);
/** A lower-case name of @p k ("random", "truncated", ...); "?" when out of range. */
const char *flood_kind_name(flood_kind_t k);

/**
 * Makes one malformed message for @p in into @p buf (FLOOD_MSG_MAX bytes), of a kind
 * drawn from @p rng (stored in @p kind).
 * @return its length (0..FLOOD_MSG_MAX; 0 is a legal empty message); -1 when no message
 *         that the channel's decoder refuses could be made in a few draws (a generator
 *         bug: the caller reports it rather than publish a message the daemon might take).
 */
int flood_make(hl_rng_t *rng, flood_input_t in, uint8_t *buf, flood_kind_t *kind);

/**
 * Makes a well-formed, unsigned SAVE request (COMMAND) with @p seq into @p buf
 * (FLOOD_MSG_MAX bytes): what a daemon without a key takes and answers (hl-flood --kind
 * save, the save-flood trial). @return its length, -1 if it does not encode.
 */
int flood_make_save(int64_t seq, uint8_t *buf);

#endif
