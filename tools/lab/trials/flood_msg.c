/* flood_msg.c - malformed messages for houghlocd's input channels (see flood_msg.h). */
#include "flood_msg.h"

#include <stdio.h>
#include <string.h>

#include "houghloc/bus.h"

/* Every message type of the bus; the first four are the inputs, in flood_input_t order. */
enum { T_SCAN, T_ODOMETRY, T_DESTINATION, T_COMMAND, T_POSE, T_STATUS, T_REPLY, T_MAP,
       N_TYPES };

#define SCAN_READINGS_MAX 64        /* keeps a scan's encoding well under FLOOD_MSG_MAX */
#define MAP_VECTORS_MAX 16

_Static_assert(43 + 8 * SCAN_READINGS_MAX + 16 <= FLOOD_MSG_MAX, "a scan must fit");
_Static_assert(28 + 12 * MAP_VECTORS_MAX + 16 <= FLOOD_MSG_MAX, "a map must fit");
_Static_assert(HL_BUS_STATUS_MAX_BYTES + 16 <= FLOOD_MSG_MAX, "a status must fit");

/* Large structs live here rather than on the stack; hl-flood is single-threaded. */
static hl_bus_scan_t scan_buf;

static const char *const input_names[FLOOD_INPUTS] = {
    HL_CHANNEL_SONAR, HL_CHANNEL_ODOMETRY, HL_CHANNEL_DESTINATION, HL_CHANNEL_COMMAND,
};
static const char *const kind_names[FLOOD_KINDS] = {
    "random", "truncated", "fingerprint", "wrong_type", "overlong", "bad_field",
};

const char *flood_input_name(flood_input_t in)
{
    return (unsigned)in < FLOOD_INPUTS ? input_names[in] : "?";
}

const char *flood_kind_name(flood_kind_t k)
{
    return (unsigned)k < FLOOD_KINDS ? kind_names[k] : "?";
}

/* ---- real encodings with random in-range fields ------------------------------------- */

static int32_t coord(hl_rng_t *r)
{
    return (int32_t)hl_rng_below(r, 40001) - 20000;   /* +-20 m: plausible, in range */
}

static hl_pose_t pose(hl_rng_t *r)
{
    return (hl_pose_t){ coord(r), coord(r), (hl_bam_t)hl_rng_next(r) };
}

static int64_t utime(hl_rng_t *r)
{
    return (int64_t)hl_rng_below(r, 1u << 30) * 1000;
}

static int encode_scan(hl_rng_t *r, uint8_t *buf)
{
    hl_bus_scan_t *s = &scan_buf;
    s->utime = utime(r);
    s->seq = (int32_t)hl_rng_below(r, 100000);
    s->odometry = pose(r);
    hl_scan_clear(&s->scan);
    uint32_t n = hl_rng_below(r, SCAN_READINGS_MAX + 1);
    for (uint32_t i = 0; i < n; i++)
        hl_scan_add(&s->scan, (hl_bam_t)hl_rng_next(r), (int32_t)hl_rng_below(r, 5000),
                    (int8_t)(i % 16), hl_rng_below(r, 8) != 0);
    return hl_bus_encode_scan(s, buf, FLOOD_MSG_MAX);
}

static int encode_odometry(hl_rng_t *r, uint8_t *buf)
{
    hl_bus_odometry_t o = { .utime = utime(r), .pose = pose(r),
                            .velocity_mm_s = (int16_t)hl_rng_below(r, 600),
                            .stopped = hl_rng_below(r, 2) != 0 };
    return hl_bus_encode_odometry(&o, buf, FLOOD_MSG_MAX);
}

static void fill_mac(hl_rng_t *r, uint8_t *mac)
{
    for (int i = 0; i < HL_BUS_MAC_BYTES; i++)
        mac[i] = (uint8_t)hl_rng_next(r);
}

static int encode_destination(hl_rng_t *r, uint8_t *buf)
{
    hl_bus_destination_t d = { .utime = utime(r), .seq = 1 + hl_rng_below(r, 1000000),
                               .x_mm = coord(r), .y_mm = coord(r),
                               .has_heading = hl_rng_below(r, 2) != 0,
                               .heading = (hl_bam_t)hl_rng_next(r) };
    fill_mac(r, d.mac);
    return hl_bus_encode_destination(&d, buf, FLOOD_MSG_MAX);
}

static int encode_command(hl_rng_t *r, uint8_t *buf)
{
    hl_bus_command_t c = { .utime = utime(r), .seq = 1 + hl_rng_below(r, 1000000),
                           .kind = (int8_t)(1 + hl_rng_below(r, 3)), .pose = pose(r) };
    fill_mac(r, c.mac);
    return hl_bus_encode_command(&c, buf, FLOOD_MSG_MAX);
}

static int encode_pose(hl_rng_t *r, uint8_t *buf)
{
    hl_bus_pose_t p = { .utime = utime(r), .scan_seq = (int32_t)hl_rng_below(r, 100000),
                        .pose = pose(r), .status = (int8_t)hl_rng_below(r, 3),
                        .confidence = (float)hl_rng_below(r, 101) / 100.0f,
                        .peak = (int32_t)hl_rng_below(r, 1000),
                        .second_peak = (int32_t)hl_rng_below(r, 1000),
                        .votes = (int32_t)hl_rng_below(r, 10000) };
    return hl_bus_encode_pose(&p, buf, FLOOD_MSG_MAX);
}

static int encode_status(hl_rng_t *r, uint8_t *buf)
{
    hl_bus_status_t s = { .utime = utime(r), .state = (int8_t)hl_rng_below(r, 7),
                          .destination_seq = -1, .scans = (int64_t)hl_rng_below(r, 1000),
                          .pose = pose(r) };
    snprintf(s.last_error, sizeof s.last_error, "flood %u", (unsigned)hl_rng_next(r));
    return hl_bus_encode_status(&s, buf, FLOOD_MSG_MAX);
}

static int encode_reply(hl_rng_t *r, uint8_t *buf)
{
    hl_bus_reply_t m = { .utime = utime(r), .seq = (int64_t)hl_rng_next(r),
                         .result = (int8_t)hl_rng_below(r, 8) };
    snprintf(m.message, sizeof m.message, "flood %u", (unsigned)hl_rng_next(r));
    return hl_bus_encode_reply(&m, buf, FLOOD_MSG_MAX);
}

static int encode_map(hl_rng_t *r, uint8_t *buf)
{
    hl_vector_t v[MAP_VECTORS_MAX];
    uint32_t n = hl_rng_below(r, MAP_VECTORS_MAX + 1);
    for (uint32_t i = 0; i < n; i++)
        v[i] = (hl_vector_t){ coord(r), coord(r), (hl_bam_t)hl_rng_next(r),
                              (uint16_t)hl_rng_below(r, 5000) };
    hl_bus_map_t m = { .utime = utime(r), .version = (int64_t)hl_rng_below(r, 1000),
                       .capacity = 1500, .count = n, .vectors = v };
    return hl_bus_encode_map(&m, buf, FLOOD_MSG_MAX);
}

static int encode(hl_rng_t *r, int type, uint8_t *buf)
{
    typedef int (*encoder_t)(hl_rng_t *, uint8_t *);
    static const encoder_t encoders[N_TYPES] = {
        encode_scan, encode_odometry, encode_destination, encode_command,
        encode_pose, encode_status, encode_reply, encode_map,
    };
    return encoders[type](r, buf);
}

/* ---- breaking them ------------------------------------------------------------------- */

/* The offset of a boolean or enumerated byte that the decoder range-checks, per input
 * (codec_scan.c and codec_request.c give the layouts); 0 for none. */
static size_t checked_byte(flood_input_t in)
{
    switch (in) {
    case FLOOD_SONAR: return 8 + 8 + 4 + 20;       /* embedded odometry.stopped */
    case FLOOD_ODOMETRY: return 8 + 8 + 4 + 4 + 2 + 2;  /* stopped */
    case FLOOD_DESTINATION: return 8 + 8 + 8 + 4 + 4;   /* has_heading */
    case FLOOD_COMMAND: return 8 + 8 + 8;               /* kind */
    default: return 0;
    }
}

static int make_once(hl_rng_t *r, flood_input_t in, uint8_t *buf, flood_kind_t k)
{
    int len;
    switch (k) {
    case FLOOD_RANDOM:
        len = (int)hl_rng_below(r, FLOOD_RANDOM_MAX + 1);
        for (int i = 0; i < len; i++)
            buf[i] = (uint8_t)hl_rng_next(r);
        return len;
    case FLOOD_TRUNCATED:
        len = encode(r, (int)in, buf);
        return len <= 0 ? len : (int)hl_rng_below(r, (uint32_t)len);
    case FLOOD_FINGERPRINT:
        len = encode(r, (int)in, buf);
        if (len >= 8)
            buf[hl_rng_below(r, 8)] ^= (uint8_t)(1u << hl_rng_below(r, 8));
        return len;
    case FLOOD_WRONG_TYPE: {
        int other = (int)hl_rng_below(r, N_TYPES - 1);
        return encode(r, other >= (int)in ? other + 1 : other, buf);
    }
    case FLOOD_OVERLONG: {
        len = encode(r, (int)in, buf);
        int extra = 1 + (int)hl_rng_below(r, 16);
        for (int i = 0; len > 0 && i < extra; i++)
            buf[len + i] = (uint8_t)hl_rng_next(r);
        return len > 0 ? len + extra : len;
    }
    default:    /* FLOOD_BAD_FIELD */
        len = encode(r, (int)in, buf);
        if (len <= (int)checked_byte(in))
            return -1;
        if (hl_rng_below(r, 2))
            buf[8] |= 0x80;     /* the utime that follows every fingerprint: negative */
        else
            buf[checked_byte(in)] = in == FLOOD_COMMAND ? (uint8_t)(4 + hl_rng_below(r, 250))
                                                        : (uint8_t)(2 + hl_rng_below(r, 254));
        return len;
    }
}

/* Would the daemon take it? Decoded with exactly the daemon's decoder of the channel. */
static bool decodes(flood_input_t in, const uint8_t *buf, size_t len)
{
    switch (in) {
    case FLOOD_SONAR: return hl_bus_decode_scan(buf, len, &scan_buf, NULL) == HL_OK;
    case FLOOD_ODOMETRY: {
        hl_bus_odometry_t o;
        return hl_bus_decode_odometry(buf, len, &o, NULL) == HL_OK;
    }
    case FLOOD_DESTINATION: {
        hl_bus_destination_t d;
        return hl_bus_decode_destination(buf, len, &d, NULL) == HL_OK;
    }
    default: {
        hl_bus_command_t c;
        return hl_bus_decode_command(buf, len, &c, NULL) == HL_OK;
    }
    }
}

int flood_make(hl_rng_t *rng, flood_input_t in, uint8_t *buf, flood_kind_t *kind)
{
    if ((unsigned)in >= FLOOD_INPUTS)
        return -1;
    *kind = (flood_kind_t)hl_rng_below(rng, FLOOD_KINDS);
    /* a random draw may, with a probability near 2^-64, carry the right fingerprint and
     * decode: draw again rather than publish it */
    for (int attempt = 0; attempt < 4; attempt++) {
        int len = make_once(rng, in, buf, *kind);
        if (len >= 0 && !decodes(in, buf, (size_t)len))
            return len;
    }
    return -1;
}

int flood_make_save(int64_t seq, uint8_t *buf)
{
    hl_bus_command_t c = { .utime = seq, .seq = seq, .kind = HL_BUS_COMMAND_SAVE };
    return hl_bus_encode_command(&c, buf, FLOOD_MSG_MAX);
}
