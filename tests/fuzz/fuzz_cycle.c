/*
 * fuzz_cycle.c - sequences of messages through the daemon's cycle (src/daemon/cycle.h):
 * scans and odometry with arbitrary seq and utime (in order, stepped, repeated, far ahead
 * or behind), destinations and commands with arbitrary seq and kind, raw bytes on any
 * input channel, timer ticks (the wall clock request seqs are held to) and saves that
 * succeed or fail, and a request state file that can or cannot be written, in any order.
 *
 * What cycle.h and stream.h promise, checked on every input:
 *   - everything the cycle publishes decodes (POSE, MAP, STATUS, REPLY, PATH): no counter,
 *     time or text it emits can leave the range its own decoder accepts;
 *   - no sequence stops localization for more than a few scans: after it, a source that
 *     sends HL_STREAM_CONFIRM + TAIL_TAKEN scans and odometry in order with each other
 *     (from a seq and time the input picks) has at least TAIL_TAKEN of its scans answered
 *     on POSE, and its last odometry taken.
 *
 * The input is read as operations (struct op_reader): one byte picks the operation, the
 * bytes after it its fields; a short input reads as zeros, so every byte string is a
 * valid sequence.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cycle.h"
#include "fuzz.h"
#include "log.h"
#include "stream.h"

#define MAX_OPS 48              /* per input: keeps an execution short */
#define MAX_READINGS 16         /* per fuzzed scan: a sonar ring */
#define TAIL_TAKEN 5            /* tail scans that must be answered */
#define TAIL_SCANS (HL_STREAM_CONFIRM - 1 + TAIL_TAKEN)
#define TAIL_STEP_US 100000     /* 10 scans a second */
#define MAP_VECTORS 4096        /* decode storage: above the capacity params_from sets */

typedef struct op_reader {
    const uint8_t *p;
    size_t left;
} op_reader_t;

static uint64_t take(op_reader_t *r, int bytes)
{
    uint64_t v = 0;
    for (int i = 0; i < bytes; i++) {
        v = v << 8 | (r->left ? *r->p : 0u);
        if (r->left) {
            r->p++;
            r->left--;
        }
    }
    return v;
}

/* What the fuzzed sequence and the checks share. */
typedef struct run {
    hl_cycle_t *cycle;
    int64_t wall_us;            /* the caller's wall clock, moved by ticks */
    int64_t mono_us;            /* the monotonic clock the cycle reads */
    int32_t scan_seq;           /* the fuzzed streams' last values, so that */
    int64_t scan_utime;         /* small steps from them can be asked for */
    int64_t odometry_utime;
    int32_t tail_first_seq;     /* the tail: POSE answers to seqs from here on ... */
    size_t tail_poses;          /* ... counted here */
    bool in_tail;
    bool keep_fails;            /* the request state cannot be written */
    hl_bus_map_t map;           /* decode storage for MAP */
    uint8_t buf[HL_BUS_SCAN_MAX_BYTES];
} run_t;

static int64_t mono_clock(void *ctx)
{
    run_t *r = ctx;
    return r->mono_us += 7;
}

static int64_t wall_clock(void *ctx)
{
    const run_t *r = ctx;
    return r->wall_us;
}

/* The request state file: written, or not (a full disk), as the input says. */
static bool keep_seq(void *ctx, int64_t seq, char *why, size_t cap)
{
    const run_t *r = ctx;
    FUZZ_CHECK(seq > 0);
    if (r->keep_fails)
        snprintf(why, cap, "disk full (fuzzed)");
    return !r->keep_fails;
}

/* Every message out must decode with its own channel's decoder. */
static void emitted(void *ctx, hl_chan_t ch, const void *data, size_t len)
{
    run_t *r = ctx;
    char why[HL_BUS_WHY_LEN] = "";
    hl_status_t st = HL_OK;
    switch (ch) {
    case HL_CH_POSE: {
        hl_bus_pose_t p;
        st = hl_bus_decode_pose(data, len, &p, why);
        if (st == HL_OK && r->in_tail && p.scan_seq >= r->tail_first_seq)
            r->tail_poses++;
        break;
    }
    case HL_CH_MAP:
        r->map.max_vectors = MAP_VECTORS;
        st = hl_bus_decode_map(data, len, &r->map, why);
        break;
    case HL_CH_STATUS: {
        hl_bus_status_t s;
        st = hl_bus_decode_status(data, len, &s, why);
        break;
    }
    case HL_CH_REPLY: {
        hl_bus_reply_t rep;
        st = hl_bus_decode_reply(data, len, &rep, why);
        break;
    }
    case HL_CH_PATH: {
        hl_bus_path_t path;
        st = hl_bus_decode_path(data, len, &path, why);
        break;
    }
    default:
        FUZZ_CHECK(!"the cycle emits on output channels only");
    }
    if (st != HL_OK)
        fprintf(stderr, "the cycle emitted an undecodable %s: %s\n", hl_chan_name(ch), why);
    FUZZ_CHECK(st == HL_OK);
}

static void feed(run_t *r, hl_chan_t ch, const void *data, int len)
{
    FUZZ_CHECK(len > 0);    /* the encoders take every value the operations make */
    hl_cycle_on_message(r->cycle, ch, data, (size_t)len, r->wall_us);
}

static hl_pose_t small_pose(op_reader_t *in)
{
    return (hl_pose_t){ (int16_t)take(in, 2), (int16_t)take(in, 2), (hl_bam_t)take(in, 2) };
}

/* A scan's or odometry's seq and utime: a small step from the stream's last (the common
 * case, in order or a little behind) or any value at all. */
static int64_t pick_utime(op_reader_t *in, uint8_t flags, int64_t last)
{
    if (flags & 1u)
        return (int64_t)(take(in, 8) >> 1);         /* anything >= 0 */
    int64_t t;
    if (__builtin_add_overflow(last, (int16_t)take(in, 2) * 1000LL, &t))
        return INT64_MAX;       /* only from the top: last >= 0 */
    return t < 0 ? 0 : t;
}

static void op_scan(run_t *r, op_reader_t *in)
{
    uint8_t flags = (uint8_t)take(in, 1);
    hl_bus_scan_t *m = malloc(sizeof *m);       /* 12 KiB: off the stack */
    FUZZ_CHECK(m != NULL);
    int64_t seq = flags & 2u ? (int64_t)(take(in, 4) & 0x7fffffffu)
                             : r->scan_seq + (int64_t)(int8_t)take(in, 1);
    m->seq = (int32_t)(seq < 0 ? 0 : seq > INT32_MAX ? INT32_MAX : seq);
    m->utime = pick_utime(in, flags, r->scan_utime);
    m->odometry = small_pose(in);
    hl_scan_clear(&m->scan);
    unsigned n = (unsigned)take(in, 1) % (MAX_READINGS + 1);
    for (unsigned i = 0; i < n; i++) {
        int32_t range = 300 + 20 * (int32_t)take(in, 1);
        hl_scan_add(&m->scan, (hl_bam_t)(i * 4096u), range, (int8_t)i, range < 5000);
    }
    r->scan_seq = m->seq;
    r->scan_utime = m->utime;
    feed(r, HL_CH_SONAR, r->buf, hl_bus_encode_scan(m, r->buf, sizeof r->buf));
    free(m);
}

static void op_odometry(run_t *r, op_reader_t *in)
{
    uint8_t flags = (uint8_t)take(in, 1);
    hl_bus_odometry_t o = { .utime = pick_utime(in, flags, r->odometry_utime),
                            .pose = small_pose(in), .velocity_mm_s = (int16_t)take(in, 2),
                            .stopped = flags & 2u };
    r->odometry_utime = o.utime;
    feed(r, HL_CH_ODOMETRY, r->buf, hl_bus_encode_odometry(&o, r->buf, sizeof r->buf));
}

/* A request's seq: any positive 64-bit value. */
static int64_t pick_request_seq(op_reader_t *in)
{
    int64_t seq = (int64_t)(take(in, 8) >> 1);
    return seq > 0 ? seq : 1;
}

static void op_destination(run_t *r, op_reader_t *in)
{
    hl_bus_destination_t d = { .utime = (int64_t)(take(in, 8) >> 1) };
    d.seq = pick_request_seq(in);
    d.x_mm = (int16_t)take(in, 2);
    d.y_mm = (int16_t)take(in, 2);
    d.has_heading = take(in, 1) & 1u;
    feed(r, HL_CH_DESTINATION, r->buf, hl_bus_encode_destination(&d, r->buf, sizeof r->buf));
}

static void op_command(run_t *r, op_reader_t *in)
{
    hl_bus_command_t c = { .utime = (int64_t)(take(in, 8) >> 1) };
    c.seq = pick_request_seq(in);
    c.kind = (int8_t)(1 + take(in, 1) % 4);     /* SET_POSE, SAVE, RELOCALIZE, STOP */
    c.pose = small_pose(in);
    feed(r, HL_CH_COMMAND, r->buf, hl_bus_encode_command(&c, r->buf, sizeof r->buf));
}

/* Bytes as they came, on any input channel: mostly refused by the decoders. */
static void op_raw(run_t *r, op_reader_t *in)
{
    hl_chan_t ch = (hl_chan_t)(take(in, 1) % 4);
    size_t n = (size_t)take(in, 1);
    n = n < in->left ? n : in->left;
    hl_cycle_on_message(r->cycle, ch, in->p, n, r->wall_us);
    in->p += n;
    in->left -= n;
}

/* What the loop does around a save: the file's outcome is the input's. */
static void op_save(run_t *r, op_reader_t *in)
{
    uint8_t outcome = (uint8_t)take(in, 1) % 3;
    if (!hl_cycle_save_due(r->cycle))
        return;
    hl_mapfile_t snap;
    hl_cycle_snapshot(r->cycle, &snap);
    FUZZ_CHECK(snap.count <= snap.capacity);
    if (outcome == 2)
        hl_cycle_save_unchanged(r->cycle);
    else
        hl_cycle_saved(r->cycle, outcome == 1, outcome == 1 ? "" : "disk full (fuzzed)");
}

static void op_tick(run_t *r, op_reader_t *in)
{
    uint16_t t = (uint16_t)take(in, 2);
    r->keep_fails = t & 1u;
    r->wall_us += (int64_t)t * 1000;
    hl_cycle_tick(r->cycle, r->wall_us);
}

/* A source in order with itself from a seq and time the input picks; its odometry
 * between the scans. */
static void tail(run_t *r, op_reader_t *in)
{
    int32_t seq = (int32_t)(take(in, 4) % (uint32_t)(INT32_MAX - TAIL_SCANS));
    int64_t utime = (int64_t)(take(in, 8) >> 2);
    hl_bus_scan_t *m = calloc(1, sizeof *m);
    FUZZ_CHECK(m != NULL);
    hl_bus_odometry_t o = { .stopped = true };
    r->in_tail = true;
    r->tail_first_seq = seq + HL_STREAM_CONFIRM - 1;
    for (int k = 0; k < TAIL_SCANS; k++) {
        m->seq = seq + k;
        m->utime = utime + k * TAIL_STEP_US;
        m->odometry = (hl_pose_t){ 100 * k, -50 * k, (hl_bam_t)(300 * k) };
        hl_scan_clear(&m->scan);
        for (unsigned i = 0; i < MAX_READINGS; i++)
            hl_scan_add(&m->scan, (hl_bam_t)(i * 4096u), 1500 + 10 * (int32_t)i, (int8_t)i,
                        true);
        feed(r, HL_CH_SONAR, r->buf, hl_bus_encode_scan(m, r->buf, sizeof r->buf));
        o.utime = m->utime + TAIL_STEP_US / 2;
        o.pose = (hl_pose_t){ 100 * k + 50, -50 * k - 25, (hl_bam_t)(300 * k + 150) };
        feed(r, HL_CH_ODOMETRY, r->buf, hl_bus_encode_odometry(&o, r->buf, sizeof r->buf));
    }
    free(m);
    if (r->tail_poses < TAIL_TAKEN)
        fprintf(stderr, "after the sequence, %zu of %d scans in order were answered\n",
                r->tail_poses, TAIL_SCANS);
    FUZZ_CHECK(r->tail_poses >= TAIL_TAKEN);
    hl_pose_t odo;
    FUZZ_CHECK(hl_cycle_odometry(r->cycle, &odo));
    FUZZ_CHECK(odo.x_mm == o.pose.x_mm && odo.y_mm == o.pose.y_mm && odo.theta == o.pose.theta);
}

/* Parameters from the first byte: with or without a key, saves counted or asked,
 * MAP held back by time or by bytes, or not. */
static hl_cycle_params_t params_from(uint8_t b)
{
    hl_cycle_params_t p = { .save_every = b & 1u ? 3 : 0, .map_period_ms = b & 2u ? 1000 : 0,
                            .map_input_ratio = b & 4u ? 2 : 0, .idle_after_ms = 500,
                            .compute_window = 1 + (b >> 4) };
    hl_params_default(&p.params);  /* the tracker alone, its capacity reached within a few scans */
    if (hl_params_set(&p.params, "slam.lost_after", "0") != HL_OK ||
        hl_params_set(&p.params, "slam.search_every", "0") != HL_OK ||
        hl_params_set(&p.params, "slam.map_capacity", "200") != HL_OK)
        abort();
    hl_fence_rect(&p.fence, -10000, -10000, 10000, 10000);
    p.authenticate = b & 8u;
    p.max_ahead_us = b & 32u ? 300 * 1000000LL : 0;
    for (int i = 0; i < HL_AUTH_KEY_BYTES; i++)
        p.key.bytes[i] = (uint8_t)(i + 1);
    return p;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    op_reader_t in = { data, size };
    hl_log_set_level(HL_LOG_ERR);  /* the faults it logs are the point, not news */
    run_t *r = calloc(1, sizeof *r);
    FUZZ_CHECK(r != NULL);
    r->map.vectors = malloc(MAP_VECTORS * sizeof *r->map.vectors);
    FUZZ_CHECK(r->map.vectors != NULL);
    r->wall_us = 1000000;
    hl_cycle_params_t p = params_from((uint8_t)take(&in, 1));
    hl_cycle_io_t io = { .emit = emitted, .now_us = mono_clock, .wall_us = wall_clock,
                         .keep_seq = keep_seq, .ctx = r };
    r->cycle = hl_cycle_create(&p, &io);
    FUZZ_CHECK(r->cycle != NULL);
    for (int ops = 0; ops < MAX_OPS && in.left > 0; ops++) {
        switch (take(&in, 1) % 8) {
        case 0: case 1: op_scan(r, &in); break;
        case 2: op_odometry(r, &in); break;
        case 3: op_destination(r, &in); break;
        case 4: op_command(r, &in); break;
        case 5: op_raw(r, &in); break;
        case 6: op_save(r, &in); break;
        default: op_tick(r, &in); break;
        }
    }
    tail(r, &in);
    hl_cycle_tick(r->cycle, r->wall_us + 1000000);
    hl_cycle_flush_map(r->cycle);
    hl_cycle_destroy(r->cycle);
    free(r->map.vectors);
    free(r);
    return 0;
}
