/*
 * forge_req.h - the requests of the Commands trial (private to tools/lab/trials): valid
 * DESTINATION and COMMAND messages signed with the daemon's key, and the bad ones an
 * attacker on the network could send, each with the REPLY result houghlocd must give.
 *
 * The generator keeps what the daemon keeps: the last seq it admitted, and the messages
 * it accepted (to replay them). A request's expectation follows the daemon's documented
 * order of checks (docs/manual/channels.md, "What is signed"): MAC first, then freshness,
 * then the geofence; a refused MAC or seq leaves the last admitted seq alone, a fence refusal
 * comes after the seq was taken.
 */
#ifndef HOUGHLOC_TOOLS_TRIALS_FORGE_REQ_H
#define HOUGHLOC_TOOLS_TRIALS_FORGE_REQ_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/auth.h"
#include "houghloc/bus.h"
#include "houghloc/rng.h"

typedef enum forge_kind {
    FORGE_VALID,        /* signed, fresh, inside the fence: accepted */
    FORGE_FORGED,       /* wrong key, a flipped MAC bit, or a field changed after signing */
    FORGE_REPLAYED,     /* the exact bytes of a request accepted before */
    FORGE_STALE,        /* signed with the right key, seq below the last accepted */
    FORGE_UNSIGNED,     /* an all-zero MAC */
    FORGE_FENCE,        /* a signed, fresh destination outside the fence */
    FORGE_KINDS
} forge_kind_t;

#define FORGE_MSG_MAX 128       /* a destination or command encoding fits */
#define FORGE_ACCEPTED_MAX 4096 /* accepted requests kept for replaying */

typedef struct forge_req {
    forge_kind_t kind;
    bool command;           /* on COMMAND, else on DESTINATION */
    const char *what;       /* e.g. "SET_POSE", "flipped MAC bit" */
    int64_t seq;            /* the seq the REPLY will carry */
    int8_t expect;          /* HL_BUS_REPLY_* the daemon must answer */
    bool waits_for_save;    /* a valid SAVE: answered once the map is written, which
                               houghlocd does at most once per 5 s for requests */
    int len;
    uint8_t bytes[FORGE_MSG_MAX];
} forge_req_t;

typedef struct forge {
    hl_auth_key_t key, wrong_key;
    char prefix[HL_BUS_PREFIX_MAX + 1];     /* the channel prefix the MACs are made for */
    hl_rng_t rng;
    int32_t fence_mm;       /* the daemon's fence holds the square +-fence_mm */
    int64_t last_seq;       /* the last seq the daemon admitted */
    int n_accepted;
    forge_req_t accepted[FORGE_ACCEPTED_MAX];
    int variant[FORGE_KINDS];   /* round-robin over each kind's variants */
} forge_t;

/** The kind's name ("valid", "forged", ...); "?" when out of range. */
const char *forge_kind_name(forge_kind_t k);

/**
 * Starts a generator: @p key is the daemon's; the wrong key differs from it in every byte;
 * @p prefix is the channel prefix MACs are made for (auth.h: the daemon's, or another
 * robot's to check that a request signed for one is refused by the other);
 * @p fence_m is the half side of a square the daemon's fence contains and beyond which
 * it refuses (10 for the default fence). @return false when libsodium cannot start.
 */
bool forge_init(forge_t *f, const hl_auth_key_t *key, const char *prefix, uint64_t seed,
                double fence_m);

/**
 * Makes the next request of @p kind into @p r (REPLAYED and STALE need an accepted request
 * before them; without one they fall back to a VALID request). The caller publishes it and
 * then reports the daemon's answer with forge_answered.
 */
void forge_make(forge_t *f, forge_kind_t kind, forge_req_t *r);

/** Takes the daemon's answer to @p r into the generator's state (the seq it admitted, the
 *  request to replay later). */
void forge_answered(forge_t *f, const forge_req_t *r, int8_t result);

#endif
