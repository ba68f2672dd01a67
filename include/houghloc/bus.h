/*
 * bus.h - LCM messages <-> core structs, with validation of every field that arrives.
 *
 * Channel names are fixed here so every program agrees. Decoders take the bytes as
 * received (an lcm_recv_buf_t's data, or an event log entry) and never trust them:
 * a message that is truncated, has a bad hash, a count out of range or a field outside
 * the fixed-point ranges is rejected with a one-line reason, and nothing is allocated
 * that could leak.
 */
#ifndef HOUGHLOC_BUS_H
#define HOUGHLOC_BUS_H

#include <stddef.h>
#include <stdint.h>

#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_CHANNEL_SONAR "SONAR"
#define HL_CHANNEL_ODOMETRY "ODOMETRY"
#define HL_CHANNEL_POSE "POSE"
#define HL_CHANNEL_MAP "MAP"
#define HL_CHANNEL_STATUS "STATUS"
#define HL_CHANNEL_DESTINATION "DESTINATION"
#define HL_CHANNEL_GROUND_TRUTH "GROUND_TRUTH"

#define HL_BUS_WHY_LEN 128

/** A sonar scan as it travels on SONAR. */
typedef struct hl_bus_scan {
    int64_t utime;
    int32_t seq;
    hl_pose_t odometry;     /* the base's pose when the scan completed */
    hl_scan_t scan;
} hl_bus_scan_t;

/** A pose as it travels on POSE or GROUND_TRUTH. */
typedef struct hl_bus_pose {
    int64_t utime;
    int32_t scan_seq;
    hl_pose_t pose;
    int8_t status;
} hl_bus_pose_t;

/**
 * Decodes a houghloc_scan_t.
 * @param[out] why  filled with a one-line reason on failure (HL_BUS_WHY_LEN bytes).
 * @return HL_OK, or HL_ERR_PARSE (malformed bytes) / HL_ERR_RANGE (a field out of range).
 */
hl_status_t hl_bus_decode_scan(const void *data, size_t len, hl_bus_scan_t *out, char *why);

/** Decodes a houghloc_pose_t. Same contract as hl_bus_decode_scan. */
hl_status_t hl_bus_decode_pose(const void *data, size_t len, hl_bus_pose_t *out, char *why);

/**
 * Encodes @p in as a houghloc_scan_t into @p buf (@p cap bytes).
 * @return bytes written, or -1 if the buffer is too small or the scan is invalid.
 */
int hl_bus_encode_scan(const hl_bus_scan_t *in, void *buf, size_t cap);

#ifdef __cplusplus
}
#endif
#endif
