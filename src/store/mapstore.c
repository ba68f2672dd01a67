/*
 * mapstore.c - the map file (mapstore.h; layout and crash analysis in docs/manual/mapfile.md).
 *
 * Both directions stream through fixed buffers on the stack: no allocation, whatever
 * the map's size. Every number is written byte by byte in little-endian order, so the
 * file is the same on every host and the header needs no padding.
 */
#include "houghloc/mapstore.h"

#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "fileio.h"

static const uint8_t MAGIC[8] = { 'H', 'L', 'M', 'A', 'P', '\r', '\n', 0x1a };

enum {
    HDR_LEN = 97,       /* header bytes, version 2 (offsets in docs/manual/mapfile.md) */
    HDR_LEN_V1 = 93,    /* ... version 1: the map version in 4 bytes, not 8 */
    HDR_PREFIX = 16,    /* magic, format version, header bytes: where the versions agree */
    VEC_LEN = 12,       /* x i32, y i32, normal u16, range u16 */
    CRC_LEN = 4,
    IO_LEN = 4092,      /* the stream buffer: 341 whole vectors */
    ASIDE_MAX = 1000,   /* move_aside gives up after PATH.bad-1000 (.old-1000) */
};

_Static_assert(HDR_LEN == HL_MAPSTORE_HEADER_BYTES && HDR_LEN_V1 == HL_MAPSTORE_V1_HEADER_BYTES,
               "mapstore.h's header sizes");

/* The header's fields after the first four, at their version 2 offsets. Version 1 held the
 * map version in 4 bytes: every field after it sits 4 bytes earlier there (v1_shift). */
enum {
    OFF_MAP_VERSION = 24,
    OFF_STARTED = 32,
    OFF_POSE = 33,
    OFF_ODOM = 43,
    OFF_PEAK_AVG = 53,
    OFF_RNG_STATE = 57,
    OFF_RNG_INC = 65,
    OFF_REQUEST_SEQ = 73,
    OFF_SCAN_UTIME = 81,
    OFF_SCANS = 89,
};

/* ---- messages ------------------------------------------------------------------------ */

/* "PATH: text" in @p why (may be NULL), one line (hl_fileio_why). @return @p st. */
static hl_status_t __attribute__((format(printf, 4, 5)))
fail(hl_status_t st, char *why, const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    hl_fileio_why(why, HL_MAPSTORE_WHY_LEN, path ? path : "(null)", fmt, ap);
    va_end(ap);
    return st;
}

/* Success: an empty reason. */
static hl_status_t done(char *why)
{
    if (why)
        why[0] = '\0';
    return HL_OK;
}

/* ---- little-endian fields ------------------------------------------------------------ */

static void put(uint8_t *b, uint64_t v, int bytes)
{
    for (int i = 0; i < bytes; i++)
        b[i] = (uint8_t)(v >> (8 * i));
}

static uint64_t get(const uint8_t *b, int bytes)
{
    uint64_t v = 0;
    for (int i = 0; i < bytes; i++)
        v |= (uint64_t)b[i] << (8 * i);
    return v;
}

/* A pose as x i32, y i32, theta u16 (10 bytes). A vector is laid out as a pose (x, y,
 * normal) and its range u16 (12 bytes). Two's complement: the casts keep every bit. */
static void put_pose(uint8_t *b, hl_pose_t p)
{
    put(b, (uint32_t)p.x_mm, 4);
    put(b + 4, (uint32_t)p.y_mm, 4);
    put(b + 8, p.theta, 2);
}

static hl_pose_t get_pose(const uint8_t *b)
{
    return (hl_pose_t){ (hl_mm_t)(uint32_t)get(b, 4), (hl_mm_t)(uint32_t)get(b + 4, 4),
                        (hl_bam_t)get(b + 8, 2) };
}

/* The header, always of version 2; the offsets are the table in docs/manual/mapfile.md. */
static void put_header(uint8_t *h, const hl_mapfile_t *m)
{
    memcpy(h, MAGIC, sizeof MAGIC);
    put(h + 8, HL_MAPSTORE_VERSION, 4);
    put(h + 12, HDR_LEN, 4);
    put(h + 16, m->capacity, 4);
    put(h + 20, m->count, 4);
    put(h + OFF_MAP_VERSION, m->state.map_version, 8);
    h[OFF_STARTED] = m->state.started ? 1 : 0;
    put_pose(h + OFF_POSE, m->state.pose);
    put_pose(h + OFF_ODOM, m->state.odom);
    put(h + OFF_PEAK_AVG, m->state.peak_avg, 4);
    put(h + OFF_RNG_STATE, m->state.cull_rng.state, 8);
    put(h + OFF_RNG_INC, m->state.cull_rng.inc, 8);
    put(h + OFF_REQUEST_SEQ, (uint64_t)m->last_request_seq, 8);
    put(h + OFF_SCAN_UTIME, (uint64_t)m->last_scan_utime, 8);
    put(h + OFF_SCANS, m->scans, 8);
}

void hl_mapstore_header(const hl_mapfile_t *m, uint8_t out[HL_MAPSTORE_HEADER_BYTES])
{
    put_header(out, m);
}

/* How much earlier than in version 2 a field after the map version sits in a header of
 * format @p format. */
static int v1_shift(uint32_t format)
{
    return format == 1 ? 4 : 0;
}

/* The started byte of a header of format @p format. */
static uint8_t get_started(const uint8_t *h, uint32_t format)
{
    return h[OFF_STARTED - v1_shift(format)];
}

/* Reads every field but the magic, version and header length (checked by the caller) of a
 * header of format @p format (1 or 2); version 1's map version is widened. */
static void get_header(const uint8_t *h, uint32_t format, hl_mapfile_t *m)
{
    int d = v1_shift(format);
    m->format = format;
    m->capacity = (uint32_t)get(h + 16, 4);
    m->count = (uint32_t)get(h + 20, 4);
    m->state.map_version = get(h + OFF_MAP_VERSION, 8 - d);
    m->state.started = get_started(h, format) != 0;
    m->state.pose = get_pose(h + OFF_POSE - d);
    m->state.odom = get_pose(h + OFF_ODOM - d);
    m->state.peak_avg = (uint32_t)get(h + OFF_PEAK_AVG - d, 4);
    m->state.cull_rng.state = get(h + OFF_RNG_STATE - d, 8);
    m->state.cull_rng.inc = get(h + OFF_RNG_INC - d, 8);
    m->last_request_seq = (int64_t)get(h + OFF_REQUEST_SEQ - d, 8);
    m->last_scan_utime = (int64_t)get(h + OFF_SCAN_UTIME - d, 8);
    m->scans = get(h + OFF_SCANS - d, 8);
}

/* The ranges a loadable file keeps, shared by save (never write what load refuses) and
 * load. The started byte is checked separately on load (a bool cannot hold 2). */
static const char *header_error(const hl_mapfile_t *m)
{
    if (m->capacity < 1 || m->capacity > HL_MAP_MAX_CAPACITY)
        return "capacity out of 1..HL_MAP_MAX_CAPACITY";
    if (m->count > m->capacity)
        return "more vectors than the capacity";
    /* versions stop there (count.h); above it, MAP could not carry them */
    if (m->state.map_version > (uint64_t)HL_COUNT_MAX)
        return "map version above 2^63 - 1";
    if (!hl_pose_in_range(m->state.pose))
        return "pose out of range";
    if (!hl_pose_in_range(m->state.odom))
        return "odometry reference out of range";
    if ((m->state.cull_rng.inc & 1u) == 0)  /* hl_rng_seed always makes it odd */
        return "culling generator increment is even";
    /* message times and request numbers are never negative (the codecs refuse them), so
     * a negative one is corruption, and it could not go out on MAP */
    if (m->last_scan_utime < 0)
        return "last scan time negative";
    if (m->last_request_seq < 0)
        return "last request number negative";
    return NULL;
}

/* ---- saving -------------------------------------------------------------------------- */

/* Header, vectors and checksum into @p fd through one buffer. @return false with errno. */
static bool write_map(int fd, const hl_mapfile_t *m)
{
    uint8_t buf[IO_LEN];
    uLong crc = crc32(0L, Z_NULL, 0);
    put_header(buf, m);
    size_t n = HDR_LEN;
    for (uint32_t i = 0; i <= m->count; i++) {
        if (i == m->count || n + VEC_LEN > sizeof buf) {
            crc = crc32(crc, buf, (uInt)n);
            if (!hl_fileio_write_all(fd, buf, n))
                return false;
            n = 0;
        }
        if (i < m->count) {
            const hl_vector_t *v = &m->vectors[i];
            put_pose(buf + n, (hl_pose_t){ v->x_mm, v->y_mm, v->normal });
            put(buf + n + 10, v->range_mm, 2);
            n += VEC_LEN;
        }
    }
    put(buf, crc, 4);
    return hl_fileio_write_all(fd, buf, CRC_LEN);
}

static bool write_map_cb(int fd, const void *m)
{
    return write_map(fd, m);
}

hl_status_t hl_mapstore_save(const char *path, const hl_mapfile_t *m, char *why)
{
    if (!path || !m || (!m->vectors && m->count > 0))
        return fail(HL_ERR_ARG, why, path, "save: no path or no map");
    /* Never write a file that load would refuse. */
    const char *bad = header_error(m);
    for (uint32_t i = 0; !bad && i < m->count; i++)
        if (!hl_vector_in_range(&m->vectors[i]))
            bad = "a vector is out of range";
    if (bad)
        return fail(HL_ERR_RANGE, why, path, "not saved: %s", bad);
    char reason[HL_MAPSTORE_WHY_LEN];
    if (!hl_fileio_replace(path, write_map_cb, m, reason, sizeof reason))
        return fail(HL_ERR_OS, why, path, "%s", reason);
    return done(why);
}

/* ---- loading ------------------------------------------------------------------------- */

/* Everything after open: the fd is the caller's to close. */
static hl_status_t load_fd(int fd, const char *path, hl_mapfile_t *out, char *why)
{
    struct stat sb;
    if (fstat(fd, &sb) != 0)
        return fail(HL_ERR_OS, why, path, "cannot stat: %s", strerror(errno));
    if (!S_ISREG(sb.st_mode))
        return fail(HL_ERR_PARSE, why, path, "not a regular file");
    long long size = (long long)sb.st_size;
    uint8_t hdr[HDR_LEN], buf[IO_LEN];
    /* The first bytes say the format, and so the header's length: read no further yet. */
    ssize_t got = hl_fileio_read_full(fd, hdr, HDR_PREFIX);
    if (got < 0)
        return fail(HL_ERR_OS, why, path, "read failed: %s", strerror(errno));
    size_t have = (size_t)got;
    if (memcmp(hdr, MAGIC, have < sizeof MAGIC ? have : sizeof MAGIC) != 0)
        return fail(HL_ERR_PARSE, why, path, "not a houghloc map file (no HLMAP magic)");
    uint32_t format = have >= 12 ? (uint32_t)get(hdr + 8, 4) : HL_MAPSTORE_VERSION;
    if (format != 1 && format != HL_MAPSTORE_VERSION)
        return fail(HL_ERR_PARSE, why, path,
                    "map file format version %" PRIu32 "; this program reads versions 1 "
                    "and %u", format, HL_MAPSTORE_VERSION);
    int hdr_len = format == 1 ? HDR_LEN_V1 : HDR_LEN;
    if (have == HDR_PREFIX) {
        got = hl_fileio_read_full(fd, hdr + HDR_PREFIX, (size_t)hdr_len - HDR_PREFIX);
        if (got < 0)
            return fail(HL_ERR_OS, why, path, "read failed: %s", strerror(errno));
        have += (size_t)got;
    }
    if (have < (size_t)hdr_len)
        return fail(HL_ERR_PARSE, why, path,
                    "truncated: %zu bytes, shorter than the %d-byte header", have, hdr_len);
    if (get(hdr + 12, 4) != (uint64_t)hdr_len)
        return fail(HL_ERR_PARSE, why, path, "header length %" PRIu32 ", version %" PRIu32
                    " has %d", (uint32_t)get(hdr + 12, 4), format, hdr_len);
    hl_mapfile_t m = { .vectors = out->vectors, .max_vectors = out->max_vectors };
    get_header(hdr, format, &m);
    long long expect = hdr_len + (long long)m.count * VEC_LEN + CRC_LEN;
    if (size != expect)
        return fail(HL_ERR_PARSE, why, path,
                    "%s: %lld bytes where a map of %" PRIu32 " vectors has %lld",
                    size < expect ? "truncated" : "trailing bytes", size, m.count, expect);
    /* The body streams through the checksum into the caller's storage when it fits;
     * the vectors' ranges are checked after the checksum. */
    bool store = m.count <= m.max_vectors;
    uLong crc = crc32(crc32(0L, Z_NULL, 0), hdr, (uInt)hdr_len);
    for (uint32_t k, n = 0; n < m.count; n += k) {
        k = m.count - n < IO_LEN / VEC_LEN ? m.count - n : IO_LEN / VEC_LEN;
        got = hl_fileio_read_full(fd, buf, (size_t)k * VEC_LEN);
        if (got < 0)
            return fail(HL_ERR_OS, why, path, "read failed: %s", strerror(errno));
        if ((size_t)got < (size_t)k * VEC_LEN)
            return fail(HL_ERR_PARSE, why, path, "truncated while being read");
        crc = crc32(crc, buf, (uInt)got);
        for (uint32_t i = 0; store && i < k; i++) {
            hl_pose_t p = get_pose(buf + (size_t)i * VEC_LEN);
            m.vectors[n + i] = (hl_vector_t){ p.x_mm, p.y_mm, p.theta,
                                              (uint16_t)get(buf + i * VEC_LEN + 10, 2) };
        }
    }
    got = hl_fileio_read_full(fd, buf, CRC_LEN + 1);  /* one byte more: the file must end here */
    if (got < 0)
        return fail(HL_ERR_OS, why, path, "read failed: %s", strerror(errno));
    if (got != CRC_LEN)
        return fail(HL_ERR_PARSE, why, path, "changed while being read");
    if (get(buf, 4) != (uint32_t)crc)
        return fail(HL_ERR_PARSE, why, path,
                    "checksum mismatch (stored %08" PRIx32 ", computed %08" PRIx32 ")",
                    (uint32_t)get(buf, 4), (uint32_t)crc);

    /* Intact: now every field's range. */
    const char *bad = get_started(hdr, format) > 1 ? "the started byte is not 0 or 1"
                                                    : header_error(&m);
    if (bad)
        return fail(HL_ERR_RANGE, why, path, "%s", bad);
    if (!store) {
        out->needed = m.count;  /* so that the caller can say what capacity it takes */
        return fail(HL_ERR_CAPACITY, why, path,
                    "holds %" PRIu32 " vectors, more than the %" PRIu32 " this map takes",
                    m.count, m.max_vectors);
    }
    for (uint32_t i = 0; i < m.count; i++)
        if (!hl_vector_in_range(&m.vectors[i]))
            return fail(HL_ERR_RANGE, why, path, "vector %" PRIu32 " out of range", i);
    *out = m;
    return done(why);
}

hl_status_t hl_mapstore_load(const char *path, hl_mapfile_t *out, char *why)
{
    if (!path || !out || (!out->vectors && out->max_vectors > 0))
        return fail(HL_ERR_ARG, why, path, "load: no path or no storage");
    int fd;
    /* O_NONBLOCK: a FIFO at PATH must not hang the start; no effect on a regular file. */
    HL_FILEIO_RETRY(fd, open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK));
    if (fd < 0)
        return fail(HL_ERR_OS, why, path, "cannot open: %s", strerror(errno));
    hl_status_t st = load_fd(fd, path, out, why);
    hl_fileio_close_quietly(fd);
    return st;
}

/* ---- moving a file aside -------------------------------------------------------------- */

hl_status_t hl_mapstore_move_aside_as(const char *path, const char *kind, char *moved_to,
                                      size_t cap, char *why)
{
    if (moved_to && cap > 0)
        moved_to[0] = '\0';
    if (!path)
        return fail(HL_ERR_ARG, why, path, "move aside: no path");
    if (!kind || !kind[0] || strlen(kind) > 16 || strchr(kind, '/'))
        return fail(HL_ERR_ARG, why, path, "move aside: a bad suffix");
    char name[PATH_MAX];
    for (int n = 1; n <= ASIDE_MAX; n++) {
        if ((size_t)snprintf(name, sizeof name, "%s.%s-%d", path, kind, n) >= sizeof name) {
            errno = ENAMETOOLONG;
            return fail(HL_ERR_OS, why, path, "cannot move aside: the path is too long");
        }
        /* link() fails with EEXIST where rename() would replace, so an older .KIND-N is
         * never overwritten, even by a concurrent mover; then the old name goes. */
        if (link(path, name) != 0) {
            if (errno == EEXIST)
                continue;
            return fail(HL_ERR_OS, why, path, "cannot move aside to %s: %s", name,
                        strerror(errno));
        }
        if (unlink(path) != 0) {
            int saved = errno;
            unlink(name);
            errno = saved;
            return fail(HL_ERR_OS, why, path, "cannot move aside (unlink failed): %s",
                        strerror(saved));
        }
        if (moved_to && cap > 0)
            snprintf(moved_to, cap, "%s", name);
        if (!hl_fileio_sync_folder(path))
            return fail(HL_ERR_OS, why, path,
                        "moved to %s, but syncing its folder failed: %s", name,
                        strerror(errno));
        return done(why);
    }
    errno = EEXIST;
    return fail(HL_ERR_OS, why, path, "cannot move aside: .%s-1 to .%s-%d all exist", kind,
                kind, ASIDE_MAX);
}

hl_status_t hl_mapstore_move_aside(const char *path, char *moved_to, size_t cap, char *why)
{
    return hl_mapstore_move_aside_as(path, "bad", moved_to, cap, why);
}
