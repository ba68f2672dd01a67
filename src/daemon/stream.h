/* stream.h - the order of one sensor stream that arrives over the network (SONAR or
 * ODOMETRY from a replay or an external driver), kept so that no single message can
 * stop localization.
 *
 * Each message carries a time (utime) and, for SONAR, a sequence number. A message is
 * in order when both move forward by a plausible step from the last one taken: at most
 * HL_STREAM_MAX_SEQ_STEP numbers (a gap is lost scans, counted) and at most
 * HL_STREAM_MAX_TIME_STEP_US of time. Any other message (behind, repeated, or far ahead:
 * a restarted publisher, a clock stepped back or forward, a forged or corrupt value) is
 * not taken. Such messages are held as a candidate run instead; once
 * HL_STREAM_CONFIRM of them follow one another in order, the stream re-synchronizes to
 * the run and takes its last message. A message in order with the stream clears the
 * candidate run, so a lone outlier (one huge seq or utime) is dropped and the real
 * stream goes on untouched, and a source that restarted or a clock that stepped loses
 * HL_STREAM_CONFIRM - 1 messages. A source that only sends messages out of order with
 * each other is never taken. docs/manual/channels.md says the rule for users.
 *
 * Pure logic, no I/O: the cycle decides what a verdict does.
 */
#ifndef HOUGHLOC_DAEMON_STREAM_H
#define HOUGHLOC_DAEMON_STREAM_H

#include <stdbool.h>
#include <stdint.h>

#define HL_STREAM_MAX_SEQ_STEP 1000
/* an hour: a robot parked and restarted within it goes on at once */
#define HL_STREAM_MAX_TIME_STEP_US (3600LL * 1000000)
#define HL_STREAM_CONFIRM 3

typedef struct hl_stream_mark {
    int64_t seq;        /* ignored for a stream without sequence numbers */
    int64_t utime;
} hl_stream_mark_t;

typedef struct hl_stream {
    bool has_seq;               /* SONAR: yes; ODOMETRY: utime only */
    bool started;
    hl_stream_mark_t last;      /* the last message taken */
    hl_stream_mark_t candidate; /* the last message of the candidate run */
    int candidate_len;          /* 0: no run */
} hl_stream_t;

typedef enum hl_stream_verdict {
    HL_STREAM_TAKE,     /* in order: take it */
    HL_STREAM_RESYNC,   /* completes a candidate run: take it, the stream follows it now */
    HL_STREAM_HOLD,     /* out of order: not taken, held in a candidate run */
} hl_stream_verdict_t;

void hl_stream_init(hl_stream_t *s, bool has_seq);

/** The verdict on message @p m, and the stream moved on by it. */
hl_stream_verdict_t hl_stream_offer(hl_stream_t *s, hl_stream_mark_t m);

/** @return whether @p b follows @p a by a plausible step (both moving forward). */
bool hl_stream_follows(const hl_stream_t *s, hl_stream_mark_t a, hl_stream_mark_t b);

#endif
