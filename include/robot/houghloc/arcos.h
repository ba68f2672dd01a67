/*
 * arcos.h - the ARCOS packet codec: bytes in, structs out, and back (docs/manual/arcos.md).
 *
 * ARCOS (AROS, P2OS before it) is the client-server protocol of the Pioneer family. Both
 * directions use one frame:
 *
 *     0xFA 0xFB | count | payload (count - 2 bytes) | checksum (2 bytes)
 *
 * count is 3..249 (at least one payload byte). The first payload byte is the command
 * number (client -> robot) or the packet type (robot -> client). Integers inside the
 * payload are little-endian; the checksum is big-endian: the payload's bytes taken in
 * pairs as (first << 8 | second), summed modulo 2^16, an odd last byte XORed into the
 * low byte. A client command is the command number, then optionally an argument: 0x3B
 * and a 16-bit magnitude for a positive integer, 0x1B and the magnitude of a negative
 * one, 0x2B and a length-prefixed string.
 *
 * This module is pure: no I/O, no allocation, no clock, no global state. The daemon uses
 * the client side (command encoders, the streaming parser, the SIP decoder, the SYNC2
 * reply), the simulated robot the server side (command decoder, SIP and SYNC2 encoders).
 * Everything from the wire is validated; nothing is read past a payload's end.
 */
#ifndef HOUGHLOC_ARCOS_H
#define HOUGHLOC_ARCOS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc/fixed.h"
#include "houghloc/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- framing ------------------------------------------------------------------------ */

#define HL_ARCOS_HDR0 0xFAu
#define HL_ARCOS_HDR1 0xFBu
#define HL_ARCOS_COUNT_MIN 3u    /* one payload byte and the checksum */
#define HL_ARCOS_COUNT_MAX 249u  /* the manuals' maximum byte count */
#define HL_ARCOS_PAYLOAD_MAX (HL_ARCOS_COUNT_MAX - 2u)  /* 247 */
#define HL_ARCOS_PACKET_MAX (HL_ARCOS_COUNT_MAX + 3u)   /* 252 bytes on the wire */
/* ARCOS ignores a client command whose byte count exceeds 204 (Pioneer 3 manual). */
#define HL_ARCOS_CMD_COUNT_MAX 204u

/** One packet's payload, as the parser delivers it: data[0] is the command number or the
 *  packet type. */
typedef struct hl_arcos_packet {
    uint8_t len;                         /* 1 .. HL_ARCOS_PAYLOAD_MAX */
    uint8_t data[HL_ARCOS_PAYLOAD_MAX];
} hl_arcos_packet_t;

/** The ARCOS checksum of @p n payload bytes (see the top of this file). */
uint16_t hl_arcos_checksum(const uint8_t *payload, size_t n);

/**
 * Frames @p n payload bytes (1..HL_ARCOS_PAYLOAD_MAX) into @p buf: header, count,
 * payload, checksum; *len = n + 5.
 * @return HL_OK; HL_ERR_ARG for NULL or n out of range; HL_ERR_CAPACITY if cap < n + 5.
 */
hl_status_t hl_arcos_frame(uint8_t *buf, size_t cap, const uint8_t *payload, size_t n,
                           size_t *len);

/* ---- streaming parser --------------------------------------------------------------- */

/**
 * Reassembles packets from a byte stream cut anywhere (one byte at a time works). It
 * holds at most one candidate packet. Garbage before a header is skipped; a candidate
 * whose count is out of range or whose checksum fails is dropped one byte at a time, so
 * the search restarts at the byte after its 0xFA and a real packet inside the rejected
 * span is still found. Every byte fed ends up in exactly one of: a delivered packet,
 * garbage_bytes, or the pending buffer (fill).
 */
typedef struct hl_arcos_parser {
    uint8_t buf[HL_ARCOS_PACKET_MAX];
    uint16_t fill;           /* bytes of the pending candidate */
    uint64_t packets;        /* packets delivered */
    uint64_t garbage_bytes;  /* bytes skipped: outside any packet, or of rejected ones */
    uint64_t bad_checksums;  /* candidates rejected for their checksum */
    uint64_t bad_lengths;    /* candidates rejected for a count outside 3..249 */
} hl_arcos_parser_t;

/** Empties the parser and zeroes its counters. */
void hl_arcos_parser_init(hl_arcos_parser_t *p);

/** Drops a pending partial packet (after a reconnection, say), keeping the counters; the
 *  dropped bytes are not counted as garbage. */
void hl_arcos_parser_discard(hl_arcos_parser_t *p);

/**
 * Feeds up to @p n bytes and returns at most one packet. Bytes taken into the parser
 * count as consumed even when they stay pending; bytes kept after a rejected candidate
 * are examined again before new input, so call again (with the rest of the input, or
 * n = 0) until HL_ERR_EMPTY:
 *
 *     size_t off = 0, used;
 *     while (hl_arcos_parse(p, in + off, n - off, &used, &pkt) == HL_OK) {
 *         off += used;
 *         handle(&pkt);
 *     }
 *
 * @p in may be NULL when n == 0.
 * @return HL_OK with *out set and *consumed <= n; HL_ERR_EMPTY when all n bytes were
 *         consumed without completing a packet (*consumed = n); HL_ERR_ARG for NULL.
 */
hl_status_t hl_arcos_parse(hl_arcos_parser_t *p, const uint8_t *in, size_t n,
                           size_t *consumed, hl_arcos_packet_t *out);

/* ---- client commands ---------------------------------------------------------------- */

/* Command numbers of the supported subset (docs/manual/arcos.md has the table). SYNC0..2 and
 * PULSE/OPEN/CLOSE share 0..2: before a connection they are the handshake. */
enum {
    HL_ARCOS_SYNC0 = 0,
    HL_ARCOS_SYNC1 = 1,
    HL_ARCOS_SYNC2 = 2,
    HL_ARCOS_PULSE = 0,       /* none: resets the server's watchdog */
    HL_ARCOS_OPEN = 1,        /* none: starts the servers and the SIP stream */
    HL_ARCOS_CLOSE = 2,       /* none: closes the connection */
    HL_ARCOS_POLLING = 3,     /* string: sonar firing sequence, transducers 1..32 */
    HL_ARCOS_ENABLE = 4,      /* int: 1 motors on, 0 off */
    HL_ARCOS_SETA = 5,        /* int: translational acceleration (+) / deceleration (-), mm/s^2 */
    HL_ARCOS_SETV = 6,        /* int: maximum translational velocity, mm/s */
    HL_ARCOS_SETO = 7,        /* none: odometry to 0, 0, 0 */
    HL_ARCOS_MOVE = 8,        /* int: translate this many mm forward (+) / back (-) */
    HL_ARCOS_SETRV = 10,      /* int: maximum rotational velocity, deg/s */
    HL_ARCOS_VEL = 11,        /* int: translational velocity, mm/s */
    HL_ARCOS_HEAD = 12,       /* int: turn to this absolute heading, deg (+ = ccw) */
    HL_ARCOS_DHEAD = 13,      /* int: turn by this many deg relative to the heading */
    HL_ARCOS_RVEL = 21,       /* int: rotational velocity, deg/s (+ = ccw) */
    HL_ARCOS_SETRA = 23,      /* int: rotational acceleration (+) / deceleration (-), deg/s^2 */
    HL_ARCOS_SONAR = 28,      /* int: bit 0 on/off; bits 1-3 array 1..4, 0 = all arrays */
    HL_ARCOS_STOP = 29,       /* none: stop, motors stay enabled */
    HL_ARCOS_SONARCYCLE = 48, /* int: sonar cycle time, 2..120 ms */
    /* Not ARCOS: houghloc-sim's lockstep clock (houghloc-sim --lockstep). In lockstep the
     * simulator sends the next SIP only once the client has sent STEP for the last one,
     * so robot time runs at the pace the client has dealt with it, never ahead of it. A
     * real robot ignores an unknown command number. */
    HL_ARCOS_STEP = 250,      /* none: advance one SIP period */
};

/* The argument type byte after the command number. */
#define HL_ARCOS_ARGTYPE_POS 0x3Bu
#define HL_ARCOS_ARGTYPE_NEG 0x1Bu
#define HL_ARCOS_ARGTYPE_STR 0x2Bu

/* An integer argument is a sign and a 16-bit magnitude. */
#define HL_ARCOS_INT_MAX 65535
/* A string argument: ARIA's limit, 200 bytes less the length prefix. */
#define HL_ARCOS_STR_MAX 199u

typedef enum hl_arcos_arg {
    HL_ARCOS_ARG_NONE = 0,
    HL_ARCOS_ARG_INT = 1,
    HL_ARCOS_ARG_STR = 2,
} hl_arcos_arg_t;

typedef struct hl_arcos_cmd {
    uint8_t number;
    uint8_t arg_kind;   /* hl_arcos_arg_t */
    int32_t arg;        /* HL_ARCOS_ARG_INT: -65535 .. 65535 */
    uint8_t str_len;    /* HL_ARCOS_ARG_STR: 0 .. HL_ARCOS_STR_MAX */
    uint8_t str[HL_ARCOS_STR_MAX];
} hl_arcos_cmd_t;

/** What the supported subset allows for one command number. */
typedef struct hl_arcos_cmd_spec {
    uint8_t number;
    uint8_t arg_kind;   /* hl_arcos_arg_t */
    int32_t min, max;   /* integer range, or string length range */
    const char *name;
} hl_arcos_cmd_spec_t;

/** The supported subset's entry for @p number, or NULL if it is not supported. */
const hl_arcos_cmd_spec_t *hl_arcos_spec_of(uint8_t number);

/**
 * Encodes @p cmd as a framed packet. Only the supported subset, with the argument kind
 * and range its spec gives (a string command's bytes are checked by the spec too: 1..32
 * for POLLING).
 * @return HL_OK and *len; HL_ERR_ARG for NULL, an unsupported number or a wrong argument;
 *         HL_ERR_CAPACITY when @p cap is too small (HL_ARCOS_PACKET_MAX always suffices).
 */
hl_status_t hl_arcos_encode_cmd(uint8_t *buf, size_t cap, const hl_arcos_cmd_t *cmd,
                                size_t *len);
/** hl_arcos_encode_cmd for a command without an argument (SYNCn, PULSE, OPEN, ...). */
hl_status_t hl_arcos_encode_none(uint8_t *buf, size_t cap, uint8_t number, size_t *len);
/** hl_arcos_encode_cmd for a command with an integer argument. */
hl_status_t hl_arcos_encode_int(uint8_t *buf, size_t cap, uint8_t number, int32_t arg,
                                size_t *len);
/** hl_arcos_encode_cmd for a command with a string argument of @p n bytes. */
hl_status_t hl_arcos_encode_str(uint8_t *buf, size_t cap, uint8_t number, const uint8_t *s,
                                size_t n, size_t *len);

/**
 * Decodes a client command (server side). The bytes must be well formed: a command
 * number alone, or followed by 0x3B/0x1B and exactly two bytes, or by 0x2B, a length and
 * that many bytes (NUL padding after them is accepted: ARIA's comStr sends one); count
 * at most HL_ARCOS_CMD_COUNT_MAX. *cmd is filled whenever they are, so an unsupported
 * command can still be logged.
 * @return HL_OK; HL_ERR_PARSE for malformed bytes; HL_ERR_RANGE for a well-formed command
 *         outside the supported subset (unknown number, wrong argument kind or range). A
 *         command of the subset that takes no argument but carries an integer one is
 *         accepted (ARIA sends OPEN and CLOSE with 1). HL_ERR_ARG for NULL.
 */
hl_status_t hl_arcos_decode_cmd(const hl_arcos_packet_t *pkt, hl_arcos_cmd_t *cmd);

/* ---- server information packets (SIP) ----------------------------------------------- */

#define HL_ARCOS_SIP_STOPPED 0x32u  /* standard SIP, motors stopped */
#define HL_ARCOS_SIP_MOVING 0x33u   /* standard SIP, robot moving */
#define HL_ARCOS_SIP_FIXED 20u      /* bytes from the type to the sonar count */
#define HL_ARCOS_SONAR_MAX 32u      /* readings per SIP; transducers are numbered 0..31 */

/* stall_bumpers bits. */
#define HL_ARCOS_STALL_LEFT 0x0001u
#define HL_ARCOS_STALL_RIGHT 0x0100u
#define HL_ARCOS_BUMPERS_1(sb) (((sb) >> 1) & 0x7Fu)  /* first bumper I/O, bits 1-7 */
#define HL_ARCOS_BUMPERS_2(sb) (((sb) >> 9) & 0x7Fu)  /* second bumper I/O, bits 9-15 */
/* flags bits. */
#define HL_ARCOS_FLAG_MOTORS 0x0001u  /* motors enabled */
#define HL_ARCOS_FLAG_SONAR 0x001Eu   /* bits 1-4: sonar arrays 1-4 enabled */
#define HL_ARCOS_FLAG_STOP 0x0020u    /* STOP button pressed */
#define HL_ARCOS_FLAG_ESTALL 0x0040u  /* E_STALL engaged */

typedef struct hl_arcos_sonar {
    uint8_t transducer;  /* 0 .. 31 */
    uint16_t range;      /* raw units: x range_um / 1000 for mm */
} hl_arcos_sonar_t;

/** The standard SIP in raw units, as sent (conversions: hl_arcos_conv_t). */
typedef struct hl_arcos_sip {
    uint8_t type;          /* HL_ARCOS_SIP_STOPPED or HL_ARCOS_SIP_MOVING */
    uint16_t x, y;         /* position; only the low 15 bits count (hl_arcos_odom_unwrap) */
    int16_t th;            /* heading, angle units */
    int16_t vel_left;      /* wheel velocities, velocity units */
    int16_t vel_right;
    uint8_t battery;       /* tenths of a volt */
    uint16_t stall_bumpers;
    int16_t control;       /* heading setpoint, angle units */
    uint16_t flags;
    uint8_t compass;       /* compass accessory, 2-degree units */
    uint8_t sonar_count;
    hl_arcos_sonar_t sonar[HL_ARCOS_SONAR_MAX];
    uint8_t extra_len;     /* bytes after the readings (gripper, I/O, ...), not decoded */
} hl_arcos_sip_t;

/** True if @p pkt is a standard SIP by its type byte. */
bool hl_arcos_is_sip(const hl_arcos_packet_t *pkt);

/**
 * Decodes a standard SIP. Fields after the sonar readings are counted in extra_len and
 * otherwise ignored.
 * @return HL_OK; HL_ERR_PARSE for a type other than 0x32/0x33, a payload shorter than
 *         the fixed part or than the readings it announces, more than 32 readings or a
 *         transducer number above 31; HL_ERR_ARG for NULL.
 */
hl_status_t hl_arcos_decode_sip(const hl_arcos_packet_t *pkt, hl_arcos_sip_t *sip);

/**
 * Encodes @p sip as a framed packet (server side): exactly the bytes
 * hl_arcos_decode_sip reads, then extra_len zero bytes.
 * @return HL_OK and *len; HL_ERR_ARG for NULL, a bad type, more than 32 readings, a
 *         transducer above 31 or a payload over 247 bytes; HL_ERR_CAPACITY if @p cap is
 *         too small.
 */
hl_status_t hl_arcos_encode_sip(uint8_t *buf, size_t cap, const hl_arcos_sip_t *sip,
                                size_t *len);

/* ---- the SYNC handshake ------------------------------------------------------------- */

/* Room for each identification string, NUL included. */
#define HL_ARCOS_ID_MAX 64u

/** What the robot says about itself after SYNC2: its name, class ("Pioneer") and
 *  subclass ("p3dx", say), each printable ASCII. */
typedef struct hl_arcos_robot_id {
    char name[HL_ARCOS_ID_MAX];
    char cls[HL_ARCOS_ID_MAX];
    char subclass[HL_ARCOS_ID_MAX];
} hl_arcos_robot_id_t;

/** True if @p pkt is the server's echo of SYNC0, SYNC1 or SYNC2 (@p sync): the single
 *  payload byte @p sync. */
bool hl_arcos_is_sync_echo(const hl_arcos_packet_t *pkt, uint8_t sync);

/**
 * Decodes the reply to SYNC2: 0x02, then the name, class and subclass, each a
 * NUL-terminated string. Bytes after the third NUL are ignored.
 * @return HL_OK; HL_ERR_PARSE for another type, a missing NUL, a string that is not
 *         printable ASCII or longer than HL_ARCOS_ID_MAX - 1; HL_ERR_ARG for NULL.
 */
hl_status_t hl_arcos_decode_sync2(const hl_arcos_packet_t *pkt, hl_arcos_robot_id_t *id);

/**
 * Encodes the reply to SYNC2 (server side) as a framed packet.
 * @return HL_OK and *len; HL_ERR_ARG for NULL or a string that is unterminated within
 *         HL_ARCOS_ID_MAX or not printable ASCII; HL_ERR_CAPACITY if @p cap is too small.
 */
hl_status_t hl_arcos_encode_sync2(uint8_t *buf, size_t cap, const hl_arcos_robot_id_t *id,
                                  size_t *len);

/* ---- units and odometry ------------------------------------------------------------- */

/**
 * A robot profile's conversion factors, in integers: ARIA's DistConvFactor,
 * VelConvFactor and RangeConvFactor in micrometres (per second) per unit, and its
 * AngleConvFactor as the units in one turn (AngleConvFactor = 2 pi / units_per_turn).
 */
typedef struct hl_arcos_conv {
    uint32_t dist_um;               /* x, y: mm = raw * dist_um / 1000 */
    uint32_t vel_um_s;              /* vel_left, vel_right: mm/s = raw * vel_um_s / 1000 */
    uint32_t range_um;              /* sonar range: mm = raw * range_um / 1000 */
    uint32_t angle_units_per_turn;  /* th, control */
} hl_arcos_conv_t;

/* Pioneer 2 and 3 with AROS/ARCOS firmware (ARIA's p2*.p and p3*.p parameter files):
 * DistConvFactor 1, VelConvFactor 1, RangeConvFactor 1, AngleConvFactor 0.001534 rad
 * (2 pi / 4096). */
#define HL_ARCOS_CONV_PIONEER { 1000u, 1000u, 1000u, 4096u }

/** A heading in angle units as a binary angle (65536 per turn), rounded to nearest.
 *  Returns 0 if units_per_turn is 0. */
hl_bam_t hl_arcos_angle_to_bam(const hl_arcos_conv_t *conv, int64_t units);

/**
 * Odometry made continuous across SIPs. x and y wrap at 2^15 units (ARIA keeps only
 * their low 15 bits), the heading at one turn; between two SIPs the robot moves far
 * less than half of either, so each step is taken modulo the wrap into [-half, half).
 * The first SIP sets the start; after a SETO, start again (hl_arcos_odom_init).
 */
typedef struct hl_arcos_odom {
    bool started;
    uint16_t last_x, last_y;        /* 15-bit values of the previous SIP */
    int16_t last_th;
    uint32_t angle_units_per_turn;  /* 0: the heading wraps at 2^16 */
    int64_t x, y, th;               /* unwrapped, raw units */
} hl_arcos_odom_t;

/** Starts an unwrapper for a heading of @p angle_units_per_turn (<= 65536; 0 = 65536). */
void hl_arcos_odom_init(hl_arcos_odom_t *o, uint32_t angle_units_per_turn);

/**
 * Adds one SIP's position and heading.
 * @return HL_OK; HL_ERR_ARG for NULL or angle_units_per_turn > 65536.
 */
hl_status_t hl_arcos_odom_unwrap(hl_arcos_odom_t *o, const hl_arcos_sip_t *sip);

#ifdef __cplusplus
}
#endif
#endif
