/*
 * gen_seeds.c - writes the binary seeds of tests/fuzz/corpus/ with the project's own
 * encoders and from its own logs (tests/fuzz/make_seeds.sh runs it; the seeds are
 * committed, so this runs only when they are remade).
 *
 *   gen_seeds encode CORPUS          ARCOS packets and streams (arcos, rlink), LCM
 *                                    messages of every type (bus_*) and map files
 *                                    (mapstore, both format versions), made by the
 *                                    encoders
 *   gen_seeds log CORPUS LOG         from an LCM log: the first messages of each channel
 *                                    (bus_*) and heads of the log itself (logcheck)
 *   gen_seeds head LOG N OUT         the first N events of LOG into OUT (an input for a
 *                                    short houghlocd replay)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "houghloc/arcos.h"
#include "houghloc/auth.h"
#include "houghloc/bus.h"
#include "houghloc/logcheck.h"
#include "houghloc/mapstore.h"

#define EVENT_HDR 28

static const char *corpus;

static void put(const char *target, const char *name, const void *data, size_t n)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s/%s", corpus, target, name);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, n, f) != n || fclose(f) != 0) {
        fprintf(stderr, "gen_seeds: cannot write %s\n", path);
        exit(1);
    }
}

/* ---- ARCOS ---------------------------------------------------------------------------- */

typedef struct stream {
    uint8_t b[4096];
    size_t n;
} stream_t;

static void add(stream_t *s, const uint8_t *p, size_t n)
{
    memcpy(s->b + s->n, p, n);
    s->n += n;
}

static void add_sync(stream_t *s, uint8_t sync)
{
    uint8_t f[HL_ARCOS_PACKET_MAX];
    size_t n = 0;
    hl_arcos_frame(f, sizeof f, &sync, 1, &n);
    add(s, f, n);
}

static void add_id(stream_t *s)
{
    hl_arcos_robot_id_t id = { "houghloc-sim", "Pioneer", "p3dx" };
    uint8_t f[HL_ARCOS_PACKET_MAX];
    size_t n = 0;
    hl_arcos_encode_sync2(f, sizeof f, &id, &n);
    add(s, f, n);
}

/* A SIP of a robot at (x, y) turning to heading th, with @p count sonar readings. */
static void add_sip(stream_t *s, uint16_t x, uint16_t y, int16_t th, uint8_t count, bool moving)
{
    hl_arcos_sip_t sip = { .type = moving ? HL_ARCOS_SIP_MOVING : HL_ARCOS_SIP_STOPPED,
                           .x = x, .y = y, .th = th, .vel_left = moving ? 200 : 0,
                           .vel_right = moving ? 210 : 0, .battery = 125,
                           .flags = HL_ARCOS_FLAG_MOTORS | 0x2, .sonar_count = count };
    for (uint8_t i = 0; i < count; i++)
        sip.sonar[i] = (hl_arcos_sonar_t){ (uint8_t)((i * 5) % 16), (uint16_t)(400 + 137 * i) };
    uint8_t f[HL_ARCOS_PACKET_MAX];
    size_t n = 0;
    hl_arcos_encode_sip(f, sizeof f, &sip, &n);
    add(s, f, n);
}

static void add_cmd(stream_t *s, uint8_t number, bool has_arg, int32_t arg)
{
    uint8_t f[HL_ARCOS_PACKET_MAX];
    size_t n = 0;
    if (has_arg)
        hl_arcos_encode_int(f, sizeof f, number, arg, &n);
    else
        hl_arcos_encode_none(f, sizeof f, number, &n);
    add(s, f, n);
}

static void put_stream(const char *target, const char *name, const stream_t *s)
{
    put(target, name, s->b, s->n);
}

static void encode_arcos(void)
{
    stream_t s = { .n = 0 };
    add_sync(&s, 0);
    add_sync(&s, 1);
    add_id(&s);
    put_stream("rlink", "handshake", &s);
    add_sip(&s, 1000, 2000, 0, 8, false);
    add_sip(&s, 1010, 2000, 12, 0, true);
    add_sip(&s, 1050, 2003, 40, 16, true);
    put_stream("rlink", "connection", &s);
    put_stream("arcos", "connection", &s);

    stream_t stale = { .n = 0 };   /* a robot still streaming from an earlier client */
    add_sip(&stale, 32760, 5, -2000, 4, false);
    add_sip(&stale, 3, 7, 2047, 4, true);
    add_sync(&stale, 0);
    add_sync(&stale, 1);
    add_id(&stale);
    add_sip(&stale, 9, 9, 4095, 32, false);
    put_stream("rlink", "stale-connection", &stale);

    stream_t noisy = { .n = 0 };   /* garbage, a bad checksum, a bad count, then a packet */
    static const uint8_t junk[] = { 0x00, 0xFA, 0x17, 0xFA, 0xFB, 0x02, 0xFA, 0xFB, 0xFF };
    add(&noisy, junk, sizeof junk);
    add_sync(&noisy, 0);
    noisy.b[noisy.n - 1] ^= 0x55;
    add_sync(&noisy, 0);
    add_sync(&noisy, 1);
    add_id(&noisy);
    add_sip(&noisy, 100, 100, 100, 2, false);
    put_stream("rlink", "noisy", &noisy);
    put_stream("arcos", "noisy", &noisy);

    stream_t cmds = { .n = 0 };    /* the client side: what houghlocd sends */
    add_cmd(&cmds, HL_ARCOS_SYNC0, false, 0);
    add_cmd(&cmds, HL_ARCOS_OPEN, false, 0);
    add_cmd(&cmds, HL_ARCOS_ENABLE, true, 1);
    add_cmd(&cmds, HL_ARCOS_SONAR, true, 1);
    add_cmd(&cmds, HL_ARCOS_VEL, true, -250);
    add_cmd(&cmds, HL_ARCOS_HEAD, true, 90);
    add_cmd(&cmds, HL_ARCOS_SETO, false, 0);
    add_cmd(&cmds, HL_ARCOS_SONARCYCLE, true, 40);
    static const uint8_t order[] = { 1, 2, 3, 4, 5, 6, 7, 8 };
    uint8_t f[HL_ARCOS_PACKET_MAX];
    size_t n = 0;
    hl_arcos_encode_str(f, sizeof f, HL_ARCOS_POLLING, order, sizeof order, &n);
    add(&cmds, f, n);
    add_cmd(&cmds, HL_ARCOS_STOP, false, 0);
    add_cmd(&cmds, HL_ARCOS_CLOSE, false, 0);
    put_stream("arcos", "commands", &cmds);

    stream_t one = { .n = 0 };
    add_sip(&one, 0x7FFF, 0x8001, -1, 32, true);
    put_stream("arcos", "sip-full", &one);
    one.n = 0;
    add_id(&one);
    put_stream("arcos", "sync2", &one);
}

/* ---- LCM messages --------------------------------------------------------------------- */

static void put_msg(const char *target, const char *name, const uint8_t *buf, int n)
{
    if (n < 0) {
        fprintf(stderr, "gen_seeds: %s %s does not encode\n", target, name);
        exit(1);
    }
    put(target, name, buf, (size_t)n);
}

static void encode_bus(void)
{
    static uint8_t buf[HL_BUS_SCAN_MAX_BYTES];
    hl_auth_key_t key;
    for (int i = 0; i < HL_AUTH_KEY_BYTES; i++)
        key.bytes[i] = (uint8_t)(i * 7 + 1);
    if (!hl_auth_init())
        exit(1);

    hl_bus_destination_t d = { .utime = 1700000000000000, .seq = 1700000000000001,
                               .x_mm = 2500, .y_mm = -1200 };
    hl_auth_sign_destination(&key, "", &d);
    put_msg("bus_destination", "signed", buf, hl_bus_encode_destination(&d, buf, sizeof buf));
    d = (hl_bus_destination_t){ .utime = 5, .seq = 2, .x_mm = -HL_COORD_MAX_MM,
                                .y_mm = HL_COORD_MAX_MM, .has_heading = true,
                                .heading = 49152 };
    put_msg("bus_destination", "unsigned-heading", buf,
            hl_bus_encode_destination(&d, buf, sizeof buf));

    hl_bus_command_t c = { .utime = 1700000000000000, .seq = 7,
                           .kind = HL_BUS_COMMAND_SET_POSE, .pose = { 1200, 3400, 16384 } };
    hl_auth_sign_command(&key, "", &c);
    put_msg("bus_command", "set-pose", buf, hl_bus_encode_command(&c, buf, sizeof buf));
    c = (hl_bus_command_t){ .utime = 0, .seq = 8, .kind = HL_BUS_COMMAND_SAVE };
    put_msg("bus_command", "save", buf, hl_bus_encode_command(&c, buf, sizeof buf));
    c.kind = HL_BUS_COMMAND_RELOCALIZE;
    put_msg("bus_command", "relocalize", buf, hl_bus_encode_command(&c, buf, sizeof buf));

    hl_bus_reply_t r = { .utime = 12, .seq = 7, .result = HL_BUS_REPLY_ACCEPTED,
                         .message = "" };
    put_msg("bus_reply", "accepted", buf, hl_bus_encode_reply(&r, buf, sizeof buf));
    r.result = HL_BUS_REPLY_REJECTED_FENCE;
    snprintf(r.message, sizeof r.message, "destination (25.000, -1.200) m is outside the fence");
    put_msg("bus_reply", "fence", buf, hl_bus_encode_reply(&r, buf, sizeof buf));

    hl_bus_status_t st = { .utime = 99, .state = HL_BUS_STATE_MOVING, .destination_seq = 3,
                           .scans = 40, .accepted = 38, .rejected_wild = 1,
                           .odometry_only = 1, .bad_packets = 2, .map_vectors = 812,
                           .map_version = 40, .saves = 1, .pose = { -300, 4000, 1000 },
                           .compute_median_us = 2100, .compute_p99_us = 5400,
                           .compute_samples = 40 };
    snprintf(st.last_error, sizeof st.last_error, "robot link: no packet for 2000 ms");
    put_msg("bus_status", "moving", buf, hl_bus_encode_status(&st, buf, sizeof buf));
    /* counters past 32 bits, and at the largest they hold */
    st.scans = INT64_C(5000000000);
    st.accepted = st.scans - 2;
    st.bad_messages = (INT64_C(1) << 31) + 3;
    st.map_version = (INT64_C(1) << 32) + 40;
    st.rejected_requests = HL_COUNT_MAX;
    st.last_error[0] = '\0';
    put_msg("bus_status", "past-32-bits", buf, hl_bus_encode_status(&st, buf, sizeof buf));

    hl_vector_t v[3] = { { 100, 200, 0, 1500 }, { -4000, 4000, 32768, 32767 },
                         { HL_COORD_MAX_MM, -HL_COORD_MAX_MM, 65535, 0 } };
    hl_bus_map_t m = { .utime = 1, .version = 2, .capacity = 1500, .count = 3, .vectors = v };
    put_msg("bus_map", "three", buf, hl_bus_encode_map(&m, buf, sizeof buf));
    m.version = (INT64_C(1) << 32) + 2;
    put_msg("bus_map", "three-past-32-bits", buf, hl_bus_encode_map(&m, buf, sizeof buf));
    m.count = 0;
    m.version = HL_COUNT_MAX;
    put_msg("bus_map", "empty-last-version", buf, hl_bus_encode_map(&m, buf, sizeof buf));
    m.version = 2;
    put_msg("bus_map", "empty", buf, hl_bus_encode_map(&m, buf, sizeof buf));

    hl_bus_pose_t p = { .utime = 3, .scan_seq = 4, .pose = { 10, 20, 30 },
                        .status = 2, .confidence = 0.5f, .peak = 9, .second_peak = 3,
                        .votes = 120 };
    put_msg("bus_pose", "odometry-only", buf, hl_bus_encode_pose(&p, buf, sizeof buf));

    hl_bus_odometry_t o = { .utime = 4, .pose = { -1, -2, 65535 }, .velocity_mm_s = -300 };
    put_msg("bus_odometry", "reversing", buf, hl_bus_encode_odometry(&o, buf, sizeof buf));

    static hl_bus_scan_t s;
    s = (hl_bus_scan_t){ .utime = 8, .seq = 0, .odometry = { 5, 6, 7 } };
    put_msg("bus_scan", "no-readings", buf, hl_bus_encode_scan(&s, buf, sizeof buf));
    s.scan.count = 3;
    s.scan.readings[0] = (hl_reading_t){ 1200, 0, 0, true, 0 };
    s.scan.readings[1] = (hl_reading_t){ 0, 16384, -1, false, 0 };
    s.scan.readings[2] = (hl_reading_t){ HL_RANGE_MAX_MM, 49152, 127, true, 0 };
    put_msg("bus_scan", "three", buf, hl_bus_encode_scan(&s, buf, sizeof buf));
}

/* ---- map files ------------------------------------------------------------------------ */

/* Saves @p m as CORPUS/mapstore/NAME; with @p v1, rewritten in format version 1 (the map
 * version's low 4 bytes at offset 24, the header 4 bytes shorter, the CRC made again). */
static void put_mapfile(const char *name, const hl_mapfile_t *m, bool v1)
{
    char path[1024], why[HL_MAPSTORE_WHY_LEN];
    snprintf(path, sizeof path, "%s/mapstore/%s", corpus, name);
    if (hl_mapstore_save(path, m, why) != HL_OK) {
        fprintf(stderr, "gen_seeds: %s\n", why);
        exit(1);
    }
    if (!v1)
        return;
    static uint8_t b[HL_MAPSTORE_HEADER_BYTES + 12 * 64 + 4];
    FILE *f = fopen(path, "rb");
    size_t n = f ? fread(b, 1, sizeof b, f) : 0;
    if (f)
        fclose(f);
    if (n < HL_MAPSTORE_HEADER_BYTES + 4 || n == sizeof b)
        exit(1);
    b[8] = 1;
    b[12] = HL_MAPSTORE_V1_HEADER_BYTES;
    memmove(b + 28, b + 32, n - 32);
    n -= 4;
    uint32_t crc = (uint32_t)crc32(0L, b, (uInt)(n - 4));
    for (int i = 0; i < 4; i++)
        b[n - 4 + (size_t)i] = (uint8_t)(crc >> (8 * i));
    put("mapstore", name, b, n);
}

static void encode_mapfiles(void)
{
    hl_vector_t v[3] = { { 100, 200, 0, 1500 }, { -4000, 4000, 32768, 32767 },
                         { HL_COORD_MAX_MM, -HL_COORD_MAX_MM, 65535, 0 } };
    hl_mapfile_t m = {
        .state = { .started = true, .pose = { 1200, -300, 16384 }, .odom = { 5, 6, 7 },
                   .peak_avg = 2560, .map_version = (UINT64_C(1) << 32) + 3,
                   .cull_rng = { 0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL } },
        .capacity = 1500, .count = 3, .vectors = v, .last_request_seq = 7,
        .last_scan_utime = 1700000000000000LL, .scans = 90,
    };
    put_mapfile("three-past-32-bits.hlmap", &m, false);
    m.state.map_version = (uint64_t)HL_COUNT_MAX;
    m.count = 0;
    put_mapfile("empty-last-version.hlmap", &m, false);
    m.state.map_version = UINT32_MAX - 1;   /* the largest a version 1 file held, nearly */
    m.count = 3;
    put_mapfile("three-format-1.hlmap", &m, true);
}

/* ---- logs ----------------------------------------------------------------------------- */

static uint8_t *slurp(const char *path, size_t *n)
{
    char why[HL_LOG_WHY_LEN];
    if (hl_log_check(path, NULL, why) != HL_OK) {
        fprintf(stderr, "gen_seeds: %s\n", why);
        exit(1);
    }
    FILE *f = fopen(path, "rb");
    fseek(f, 0, SEEK_END);
    *n = (size_t)ftell(f);
    rewind(f);
    uint8_t *b = malloc(*n);
    if (!b || fread(b, 1, *n, f) != *n)
        exit(1);
    fclose(f);
    return b;
}

static uint32_t be32(const uint8_t *b)
{
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

/* Bytes of the first @p k events (all of them when the log is shorter). */
static size_t head_bytes(const uint8_t *b, size_t n, int k)
{
    size_t off = 0;
    for (int i = 0; i < k && off < n; i++)
        off += EVENT_HDR + be32(b + off + 20) + be32(b + off + 24);
    return off;
}

static const char *target_of(const char *channel)
{
    static const char *const map[][2] = {
        { "SONAR", "bus_scan" }, { "SONAR_TEST", "bus_scan" }, { "ODOMETRY", "bus_odometry" },
        { "POSE", "bus_pose" }, { "GROUND_TRUTH", "bus_pose" }, { "MAP", "bus_map" },
        { "STATUS", "bus_status" }, { "REPLY", "bus_reply" },
    };
    for (size_t i = 0; i < sizeof map / sizeof map[0]; i++)
        if (strcmp(channel, map[i][0]) == 0)
            return map[i][1];
    return NULL;
}

static void from_log(const char *path)
{
    size_t n = 0;
    uint8_t *b = slurp(path, &n);
    const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    char name[512], stem[128];
    snprintf(stem, sizeof stem, "%.*s", (int)strcspn(base, "."), base);
    char seen[16][64];
    int count[16] = { 0 }, nseen = 0;
    for (size_t off = 0; off < n;) {
        uint32_t cl = be32(b + off + 20), dl = be32(b + off + 24);
        char channel[256];
        snprintf(channel, sizeof channel, "%.*s", (int)cl, (const char *)b + off + EVENT_HDR);
        int i = 0;
        while (i < nseen && strcmp(seen[i], channel) != 0)
            i++;
        if (i == nseen && nseen < 16)
            snprintf(seen[nseen++], sizeof seen[0], "%.63s", channel);
        /* the first two of each channel, and none bigger than 8 KiB (a whole MAP) */
        const char *target = target_of(channel);
        if (target && i < nseen && count[i] < 2 && dl <= 8192) {
            snprintf(name, sizeof name, "%s-%s-%d", stem, channel, count[i]++);
            put(target, name, b + off + EVENT_HDR + cl, dl);
        }
        off += EVENT_HDR + cl + dl;
    }
    static const int heads[] = { 1, 4, 12 };
    for (size_t i = 0; i < sizeof heads / sizeof heads[0]; i++) {
        size_t h = head_bytes(b, n, heads[i]);
        snprintf(name, sizeof name, "%s-head%d", stem, heads[i]);
        if (h <= 8192)
            put("logcheck", name, b, h);
    }
    size_t h = head_bytes(b, n, 3);
    snprintf(name, sizeof name, "%s-cut", stem);     /* the fourth event cut short */
    put("logcheck", name, b, h + 40 < n ? h + 40 : n);
    free(b);
}

static void head(const char *path, int k, const char *out)
{
    size_t n = 0;
    uint8_t *b = slurp(path, &n);
    FILE *f = fopen(out, "wb");
    size_t h = head_bytes(b, n, k);
    if (!f || fwrite(b, 1, h, f) != h || fclose(f) != 0)
        exit(1);
    free(b);
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "encode") == 0) {
        corpus = argv[2];
        encode_arcos();
        encode_bus();
        encode_mapfiles();
    } else if (argc == 4 && strcmp(argv[1], "log") == 0) {
        corpus = argv[2];
        from_log(argv[3]);
    } else if (argc == 5 && strcmp(argv[1], "head") == 0) {
        head(argv[2], atoi(argv[3]), argv[4]);
    } else {
        fprintf(stderr, "usage: gen_seeds encode CORPUS | log CORPUS LOG | head LOG N OUT\n");
        return 2;
    }
    return 0;
}
