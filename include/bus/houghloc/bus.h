/*
 * bus.h - LCM messages <-> houghloc structs, validating every field that arrives.
 *
 * One codec per message type of lcmtypes/ (scan, odometry, pose, map, status,
 * destination, command, reply). Every codec works both ways:
 *
 *   int hl_bus_encode_X(const hl_bus_X_t *in, void *buf, size_t cap);
 *       writes the LCM encoding (fingerprint hash first, big-endian, exactly what the
 *       lcm-gen code writes) into the caller's buffer and returns its length, or -1 when
 *       @p cap is too small or a field is outside its range. Never allocates.
 *
 *   hl_status_t hl_bus_decode_X(const void *data, size_t len, hl_bus_X_t *out, char *why);
 *       decodes bytes as received (an lcm_recv_buf_t's data, an event log entry) without
 *       trusting them and without a heap allocation: HL_OK, or HL_ERR_PARSE (truncated,
 *       trailing bytes, wrong fingerprint, a string whose length field is below 1 or
 *       whose NUL is missing or not last) / HL_ERR_RANGE (a count or field outside its
 *       range, NaN or infinite, a boolean byte other than 0 or 1, a string longer than
 *       HL_BUS_TEXT_MAX - 1 characters or holding a control character) / HL_ERR_ARG
 *       (@p data or @p out NULL) with a one-line reason in @p why naming the message and
 *       the field (HL_BUS_WHY_LEN bytes; may be NULL). On failure *out is unspecified but
 *       holds no allocation.
 *
 * Both directions check the same ranges, so whatever encodes decodes, and whatever
 * decodes re-encodes to the same bytes (except a scan's embedded odometry extras, see
 * hl_bus_scan_t). Every utime is >= 0. The fingerprint of each type is lcm-gen's, taken
 * from the generated code, so a changed .lcm file cannot desynchronize the codecs.
 *
 * Only src/bus sees the generated LCM code; everything else goes through this header.
 * Channel names are the base names below; a deployment may put a prefix in front of
 * all of them (hl_bus_channel) so that several robots share one network.
 */
#ifndef HOUGHLOC_BUS_H
#define HOUGHLOC_BUS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc/map.h"
#include "houghloc/scan.h"
#include "houghloc/slam.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_CHANNEL_SONAR "SONAR"
#define HL_CHANNEL_ODOMETRY "ODOMETRY"
#define HL_CHANNEL_POSE "POSE"
#define HL_CHANNEL_MAP "MAP"
#define HL_CHANNEL_STATUS "STATUS"
#define HL_CHANNEL_DESTINATION "DESTINATION"
#define HL_CHANNEL_COMMAND "COMMAND"
#define HL_CHANNEL_REPLY "REPLY"
#define HL_CHANNEL_GROUND_TRUTH "GROUND_TRUTH"
#define HL_CHANNEL_PATH "PATH"

#define HL_BUS_WHY_LEN 128
#define HL_BUS_CHANNEL_MAX 64       /* a channel name with its prefix, with the NUL */
#define HL_BUS_PREFIX_MAX 32        /* a channel prefix, without the NUL */
#define HL_BUS_TEXT_MAX 160         /* status last_error / reply message, with the NUL */
#define HL_BUS_MAC_BYTES 32

/**
 * Writes @p prefix followed by @p base into @p out (HL_BUS_CHANNEL_MAX bytes).
 * @p prefix may be NULL or "" (no prefix); @p base and @p out must not be NULL.
 * @return false (out untouched) when the prefix is longer than HL_BUS_PREFIX_MAX, the
 *         base is empty, the name does not fit in HL_BUS_CHANNEL_MAX - 1 characters, or
 *         either holds a character other than letters, digits, '_', '-', '.' and '/'.
 */
bool hl_bus_channel(const char *prefix, const char *base, char *out);

/* ---- SONAR: one sounding ---------------------------------------------------------- */

/** An odometry sample as it travels on ODOMETRY (and inside every scan). */
typedef struct hl_bus_odometry {
    int64_t utime;
    hl_pose_t pose;             /* in the odometry frame */
    int16_t velocity_mm_s;
    bool stopped;
} hl_bus_odometry_t;

/**
 * A scan as it travels on SONAR. Every reading's range_mm is 0..HL_RANGE_MAX_MM, valid
 * or not (hl_scan_add guarantees it), and its transducer -1..127; seq >= 0.
 * scan_t embeds a whole odometry_t; only its pose is kept here. The encoder writes the
 * scan's utime, velocity 0 and stopped true around it; the decoder checks those fields
 * (odometry utime >= 0, stopped 0 or 1) and drops them.
 */
typedef struct hl_bus_scan {
    int64_t utime;
    int32_t seq;
    hl_pose_t odometry;         /* the base's pose when the scan completed */
    hl_scan_t scan;
} hl_bus_scan_t;

/** Largest encoded scan (HL_SCAN_MAX_READINGS readings); a nested struct has no hash. */
#define HL_BUS_SCAN_MAX_BYTES (8 + 8 + 4 + 21 + 2 + 8 * HL_SCAN_MAX_READINGS)

hl_status_t hl_bus_decode_scan(const void *data, size_t len, hl_bus_scan_t *out, char *why);
int hl_bus_encode_scan(const hl_bus_scan_t *in, void *buf, size_t cap);

/* ---- ODOMETRY ---------------------------------------------------------------------- */

#define HL_BUS_ODOMETRY_BYTES (8 + 8 + 4 + 4 + 2 + 2 + 1)
hl_status_t hl_bus_decode_odometry(const void *data, size_t len, hl_bus_odometry_t *out,
                                   char *why);
int hl_bus_encode_odometry(const hl_bus_odometry_t *in, void *buf, size_t cap);

/* ---- POSE (and GROUND_TRUTH) ------------------------------------------------------- */

/* POSE's status on the wire (lcmtypes/houghloc_pose_t.lcm). */
typedef enum hl_bus_pose_status {
    HL_BUS_POSE_ACCEPTED = 0,
    HL_BUS_POSE_REJECTED_WILD = 1,
    HL_BUS_POSE_ODOMETRY_ONLY = 2,
    HL_BUS_POSE_RELOCALIZED = 3,
    HL_BUS_POSE_LOST = 4,
} hl_bus_pose_status_t;

/** The wire's status for the tracker's (slam.h): the one place the two meet. */
int8_t hl_bus_pose_status(hl_slam_status_t status);

typedef struct hl_bus_pose {
    int64_t utime;
    int32_t scan_seq;
    hl_pose_t pose;
    int8_t status;              /* hl_bus_pose_status_t */
    float confidence;           /* 0..1 */
    int32_t peak;               /* >= 0 */
    int32_t second_peak;        /* >= 0 */
    int32_t votes;              /* >= 0 */
    float search_score;         /* 0..1: the global search's answer ... */
    hl_pose_t runner_up;        /* ... its runner-up, position within +-HL_COORD_MAX_MM */
    float runner_up_score;      /* 0..1 */
} hl_bus_pose_t;                /* scan_seq >= 0; position within +-HL_COORD_MAX_MM */

#define HL_BUS_POSE_BYTES (8 + 8 + 4 + 4 + 4 + 2 + 1 + 4 + 4 + 4 + 4 + 4 + 4 + 4 + 2 + 4)
hl_status_t hl_bus_decode_pose(const void *data, size_t len, hl_bus_pose_t *out, char *why);
int hl_bus_encode_pose(const hl_bus_pose_t *in, void *buf, size_t cap);

/* ---- MAP --------------------------------------------------------------------------- */

/** Each vector's position is within +-HL_COORD_MAX_MM, its range 0..HL_RANGE_MAX_MM. */
typedef struct hl_bus_map {
    int64_t utime;
    int64_t version;            /* >= 0 (64-bit: it never wraps, count.h) */
    int32_t capacity;           /* 1..HL_MAP_MAX_CAPACITY */
    uint32_t count;             /* 0..capacity */
    hl_vector_t *vectors;       /* encode: count vectors to send; decode: caller's
                                   storage for at most max_vectors */
    uint32_t max_vectors;       /* decode only: the storage's size; more is HL_ERR_RANGE */
} hl_bus_map_t;

/** Encoded size of a map of @p count vectors: 32 + 12 * count. */
size_t hl_bus_map_bytes(uint32_t count);
/** Decode: nvectors above out->max_vectors is HL_ERR_RANGE; vectors NULL with
 *  nvectors > 0 is HL_ERR_ARG. utime, version, capacity, count are written on success. */
hl_status_t hl_bus_decode_map(const void *data, size_t len, hl_bus_map_t *out, char *why);
int hl_bus_encode_map(const hl_bus_map_t *in, void *buf, size_t cap);

/* ---- STATUS ------------------------------------------------------------------------ */

typedef struct hl_bus_status {
    int64_t utime;
    int8_t state;               /* HL_BUS_STATE_* */
    int64_t destination_seq;    /* -1 when none, else > 0 */
    /* the counters: >= 0, 64-bit so that they never wrap (count.h) */
    int64_t scans, accepted, rejected_wild, odometry_only;
    int64_t relocalized, lost;  /* scans = accepted + ... + odometry_only + these two */
    int64_t bad_packets, bad_messages, rejected_requests;
    int32_t map_vectors;        /* 0..HL_MAP_MAX_CAPACITY: a size, not a counter */
    int64_t map_version, saves;
    hl_pose_t pose;             /* current estimate, within +-HL_COORD_MAX_MM */
    int32_t compute_median_us, compute_p99_us, compute_samples;    /* >= 0 */
    char last_error[HL_BUS_TEXT_MAX];   /* one line: NUL-terminated, no control char */
} hl_bus_status_t;

enum {
    HL_BUS_STATE_STARTING = 0,
    HL_BUS_STATE_SOUNDING = 1,
    HL_BUS_STATE_LOCALIZING = 2,
    HL_BUS_STATE_MOVING = 3,
    HL_BUS_STATE_IDLE = 4,
    HL_BUS_STATE_FAULT = 5,
    HL_BUS_STATE_STOPPING = 6,
    HL_BUS_STATE_LOST = 7,
};

#define HL_BUS_STATUS_MAX_BYTES (8 + 8 + 1 + 8 + 8 * 11 + 4 + 4 + 4 + 2 + 4 * 3 + 4 + \
                                 HL_BUS_TEXT_MAX)
hl_status_t hl_bus_decode_status(const void *data, size_t len, hl_bus_status_t *out,
                                 char *why);
int hl_bus_encode_status(const hl_bus_status_t *in, void *buf, size_t cap);

/* ---- PATH -------------------------------------------------------------------------- */

#define HL_BUS_PATH_MAX_POINTS 64

/** The planned way to a destination: npoints 0 (none) .. HL_BUS_PATH_MAX_POINTS, each
 *  within +-HL_COORD_MAX_MM. */
typedef struct hl_bus_path {
    int64_t utime;
    int64_t destination_seq;    /* -1 when none, else > 0 */
    int32_t npoints;
    int32_t x_mm[HL_BUS_PATH_MAX_POINTS], y_mm[HL_BUS_PATH_MAX_POINTS];
} hl_bus_path_t;

#define HL_BUS_PATH_MAX_BYTES (8 + 8 + 8 + 4 + 8 * HL_BUS_PATH_MAX_POINTS)
hl_status_t hl_bus_decode_path(const void *data, size_t len, hl_bus_path_t *out, char *why);
int hl_bus_encode_path(const hl_bus_path_t *in, void *buf, size_t cap);

/* ---- DESTINATION, COMMAND, REPLY ------------------------------------------------- */

typedef struct hl_bus_destination {
    int64_t utime;
    int64_t seq;                /* > 0 */
    int32_t x_mm, y_mm;         /* within +-HL_COORD_MAX_MM */
    bool has_heading;
    hl_bam_t heading;
    uint8_t mac[HL_BUS_MAC_BYTES];
} hl_bus_destination_t;

#define HL_BUS_DESTINATION_BYTES (8 + 8 + 8 + 4 + 4 + 1 + 2 + HL_BUS_MAC_BYTES)
hl_status_t hl_bus_decode_destination(const void *data, size_t len,
                                      hl_bus_destination_t *out, char *why);
int hl_bus_encode_destination(const hl_bus_destination_t *in, void *buf, size_t cap);

enum {
    HL_BUS_COMMAND_SET_POSE = 1,
    HL_BUS_COMMAND_SAVE = 2,
    HL_BUS_COMMAND_RELOCALIZE = 3,
    HL_BUS_COMMAND_STOP = 4,    /* never refused: no MAC needed, any seq (command_t.lcm) */
};

typedef struct hl_bus_command {
    int64_t utime;
    int64_t seq;                /* > 0 */
    int8_t kind;                /* HL_BUS_COMMAND_* */
    hl_pose_t pose;             /* SET_POSE; position within +-HL_COORD_MAX_MM (checked
                                   for every kind: send zeros when unused) */
    uint8_t mac[HL_BUS_MAC_BYTES];
} hl_bus_command_t;

#define HL_BUS_COMMAND_BYTES (8 + 8 + 8 + 1 + 4 + 4 + 2 + HL_BUS_MAC_BYTES)
hl_status_t hl_bus_decode_command(const void *data, size_t len, hl_bus_command_t *out,
                                  char *why);
int hl_bus_encode_command(const hl_bus_command_t *in, void *buf, size_t cap);

enum {
    HL_BUS_REPLY_ACCEPTED = 0,
    HL_BUS_REPLY_ARRIVED = 1,
    HL_BUS_REPLY_REJECTED_FENCE = 2,
    HL_BUS_REPLY_REJECTED_AUTH = 3,
    HL_BUS_REPLY_REJECTED_REPLAY = 4,
    HL_BUS_REPLY_NO_ROBOT = 5,
    HL_BUS_REPLY_FAILED = 6,
    HL_BUS_REPLY_REJECTED_INVALID = 7,
};

/* The message of a NO_ROBOT that will not change: the daemon has no robot link
 * configured. Any other NO_ROBOT means the link is not up yet, and a client may ask
 * again. */
#define HL_BUS_NO_ROBOT_UNCONFIGURED "no robot link is configured (robot.link)"

typedef struct hl_bus_reply {
    int64_t utime;
    int64_t seq;                /* the request's, as it came: any value */
    int8_t result;              /* HL_BUS_REPLY_* */
    char message[HL_BUS_TEXT_MAX];      /* as status last_error */
    uint8_t mac[HL_BUS_MAC_BYTES];      /* auth.h; all zero when unsigned */
} hl_bus_reply_t;

#define HL_BUS_REPLY_MAX_BYTES (8 + 8 + 8 + 1 + 4 + HL_BUS_TEXT_MAX + HL_BUS_MAC_BYTES)
/** The constant's name, e.g. "REJECTED_FENCE"; "?" for an unknown value. */
const char *hl_bus_reply_name(int8_t result);
hl_status_t hl_bus_decode_reply(const void *data, size_t len, hl_bus_reply_t *out, char *why);
int hl_bus_encode_reply(const hl_bus_reply_t *in, void *buf, size_t cap);

#ifdef __cplusplus
}
#endif
#endif
