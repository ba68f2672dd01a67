/* Tests for src/daemon/mapstore.c: the map file's layout byte by byte, round trips, every
 * truncation and every single-bit flip refused, each range check behind a good checksum,
 * saves that fail leave no temporary file and the old map whole, moving a bad file aside. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "mapstore.h"

#define HDR 93
#define BIG 16384

typedef struct fixture {
    char dir[64];
    char path[128];         /* dir/map.hlmap */
    char tmp[140];          /* path.tmp */
    hl_vector_t *a, *b;     /* BIG vectors each: to save, to load into */
} fixture_t;

static int setup(void **state)
{
    fixture_t *f = calloc(1, sizeof *f);
    snprintf(f->dir, sizeof f->dir, "/tmp/hl-mapstore-XXXXXX");
    if (!mkdtemp(f->dir))
        return -1;
    snprintf(f->path, sizeof f->path, "%s/map.hlmap", f->dir);
    snprintf(f->tmp, sizeof f->tmp, "%s.tmp", f->path);
    f->a = calloc(BIG, sizeof *f->a);
    f->b = calloc(BIG, sizeof *f->b);
    *state = f;
    return 0;
}

/* Removes the folder, one level of subfolders deep. */
static void remove_tree(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    chmod(dir, 0700);
    struct dirent *e;
    char p[512];
    while ((e = readdir(d)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        if (unlink(p) != 0)
            remove_tree(p);
    }
    closedir(d);
    rmdir(dir);
}

static int teardown(void **state)
{
    fixture_t *f = *state;
    remove_tree(f->dir);
    free(f->a);
    free(f->b);
    free(f);
    return 0;
}

/* ---- helpers ------------------------------------------------------------------------- */

static long file_size(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 ? (long)sb.st_size : -1;
}

static size_t read_bytes(const char *path, uint8_t *buf, size_t cap)
{
    FILE *fp = fopen(path, "rb");
    assert_non_null(fp);
    size_t n = fread(buf, 1, cap, fp);
    fclose(fp);
    return n;
}

static void write_bytes(const char *path, const uint8_t *buf, size_t n)
{
    FILE *fp = fopen(path, "wb");
    assert_non_null(fp);
    assert_int_equal(fwrite(buf, 1, n, fp), n);
    assert_int_equal(fclose(fp), 0);
}

static uint64_t le(const uint8_t *b, int bytes)
{
    uint64_t v = 0;
    for (int i = 0; i < bytes; i++)
        v |= (uint64_t)b[i] << (8 * i);
    return v;
}

static void put_le(uint8_t *b, uint64_t v, int bytes)
{
    for (int i = 0; i < bytes; i++)
        b[i] = (uint8_t)(v >> (8 * i));
}

/* Rewrites the trailing checksum of a file image of @p n bytes. */
static void fix_crc(uint8_t *buf, size_t n)
{
    put_le(buf + n - 4, crc32(0L, buf, (uInt)(n - 4)), 4);
}

/* A map file with every field set to something recognisable. */
static hl_mapfile_t sample(hl_vector_t *v, uint32_t count, uint32_t capacity)
{
    hl_rng_t rng;
    hl_rng_seed(&rng, count + 17);
    for (uint32_t i = 0; i < count; i++)
        v[i] = (hl_vector_t){ (int32_t)hl_rng_below(&rng, 2 * HL_COORD_MAX_MM + 1) -
                                  HL_COORD_MAX_MM,
                              (int32_t)hl_rng_below(&rng, 2 * HL_COORD_MAX_MM + 1) -
                                  HL_COORD_MAX_MM,
                              (hl_bam_t)hl_rng_next(&rng),
                              (uint16_t)hl_rng_below(&rng, HL_RANGE_MAX_MM + 1) };
    hl_mapfile_t m = {
        .state = { .started = true, .pose = { -HL_COORD_MAX_MM, HL_COORD_MAX_MM, 65535 },
                   .odom = { 123456, -654321, 4321 }, .peak_avg = 0xfedcba98u,
                   .map_version = 0x89abcdefu,
                   .cull_rng = { 0x0123456789abcdefULL, 0xfedcba9876543211ULL } },
        .capacity = capacity, .count = count, .vectors = v,
        .last_request_seq = INT64_MIN + 5, .last_scan_utime = 1700000000123456LL,
        .scans = 0x8000000000000001ULL,
    };
    return m;
}

static void assert_same(const hl_mapfile_t *a, const hl_mapfile_t *b)
{
    assert_int_equal(a->state.started, b->state.started);
    assert_int_equal(a->state.pose.x_mm, b->state.pose.x_mm);
    assert_int_equal(a->state.pose.y_mm, b->state.pose.y_mm);
    assert_int_equal(a->state.pose.theta, b->state.pose.theta);
    assert_int_equal(a->state.odom.x_mm, b->state.odom.x_mm);
    assert_int_equal(a->state.odom.y_mm, b->state.odom.y_mm);
    assert_int_equal(a->state.odom.theta, b->state.odom.theta);
    assert_int_equal(a->state.peak_avg, b->state.peak_avg);
    assert_int_equal(a->state.map_version, b->state.map_version);
    assert_true(a->state.cull_rng.state == b->state.cull_rng.state);
    assert_true(a->state.cull_rng.inc == b->state.cull_rng.inc);
    assert_int_equal(a->capacity, b->capacity);
    assert_int_equal(a->count, b->count);
    assert_true(a->last_request_seq == b->last_request_seq);
    assert_true(a->last_scan_utime == b->last_scan_utime);
    assert_true(a->scans == b->scans);
    if (a->count)
        assert_memory_equal(a->vectors, b->vectors, a->count * sizeof(hl_vector_t));
}

/* A reason: one line that starts with "PATH: ". */
static void assert_reason(const char *why, const char *path)
{
    size_t n = strlen(path);
    assert_true(strncmp(why, path, n) == 0 && why[n] == ':' && why[n + 1] == ' ');
    assert_true(strlen(why) > n + 2);
    assert_null(strchr(why, '\n'));
}

static hl_status_t load_into(fixture_t *f, hl_mapfile_t *out, uint32_t max, char *why)
{
    memset(out, 0, sizeof *out);
    out->count = 777;   /* a sentinel: a refused load leaves it */
    out->vectors = f->b;
    out->max_vectors = max;
    return hl_mapstore_load(f->path, out, why);
}

/* ---- tests --------------------------------------------------------------------------- */

/* Every field at the offset docs/mapfile.md gives, and back. */
static void test_layout_and_round_trip(void **state)
{
    fixture_t *f = *state;
    hl_mapfile_t m = sample(f->a, 3, 1500), got;
    char why[HL_MAPSTORE_WHY_LEN] = "x";
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
    assert_string_equal(why, "");
    uint8_t buf[HDR + 3 * 12 + 4 + 1];
    assert_int_equal(read_bytes(f->path, buf, sizeof buf), HDR + 3 * 12 + 4);
    assert_memory_equal(buf, "HLMAP\r\n\x1a", 8);
    assert_int_equal(le(buf + 8, 4), 1);
    assert_int_equal(le(buf + 12, 4), HDR);
    assert_int_equal(le(buf + 16, 4), 1500);
    assert_int_equal(le(buf + 20, 4), 3);
    assert_int_equal(le(buf + 24, 4), 0x89abcdefu);
    assert_int_equal(buf[28], 1);
    assert_int_equal((int32_t)le(buf + 29, 4), -HL_COORD_MAX_MM);
    assert_int_equal((int32_t)le(buf + 33, 4), HL_COORD_MAX_MM);
    assert_int_equal(le(buf + 37, 2), 65535);
    assert_int_equal((int32_t)le(buf + 39, 4), 123456);
    assert_int_equal((int32_t)le(buf + 43, 4), -654321);
    assert_int_equal(le(buf + 47, 2), 4321);
    assert_int_equal(le(buf + 49, 4), 0xfedcba98u);
    assert_true(le(buf + 53, 8) == 0x0123456789abcdefULL);
    assert_true(le(buf + 61, 8) == 0xfedcba9876543211ULL);
    assert_true((int64_t)le(buf + 69, 8) == INT64_MIN + 5);
    assert_true((int64_t)le(buf + 77, 8) == 1700000000123456LL);
    assert_true(le(buf + 85, 8) == 0x8000000000000001ULL);
    for (int i = 0; i < 3; i++) {
        const uint8_t *v = buf + HDR + 12 * i;
        assert_int_equal((int32_t)le(v, 4), f->a[i].x_mm);
        assert_int_equal((int32_t)le(v + 4, 4), f->a[i].y_mm);
        assert_int_equal(le(v + 8, 2), f->a[i].normal);
        assert_int_equal(le(v + 10, 2), f->a[i].range_mm);
    }
    assert_int_equal(le(buf + HDR + 36, 4), crc32(0L, buf, HDR + 36));
    assert_int_equal(load_into(f, &got, BIG, why), HL_OK);
    assert_string_equal(why, "");
    assert_same(&m, &got);
    assert_ptr_equal(got.vectors, f->b);
    assert_int_equal(got.max_vectors, BIG);
    assert_int_equal(file_size(f->tmp), -1);
}

/* No vectors (and no storage), a full paper-sized map, the largest map the localizer
 * takes. */
static void test_round_trip_sizes(void **state)
{
    fixture_t *f = *state;
    const uint32_t counts[] = { 0, 1500, BIG }, caps[] = { 1500, 1500, BIG };
    for (int k = 0; k < 3; k++) {
        hl_mapfile_t m = sample(f->a, counts[k], caps[k]), got;
        m.state.started = k != 1;
        if (counts[k] == 0)
            m.vectors = NULL;
        char why[HL_MAPSTORE_WHY_LEN];
        assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
        assert_int_equal(file_size(f->path), HDR + 12 * counts[k] + 4);
        memset(f->b, 0xa5, BIG * sizeof *f->b);
        if (counts[k] == 0) {
            memset(&got, 0, sizeof got);
            assert_int_equal(hl_mapstore_load(f->path, &got, why), HL_OK);
            assert_null(got.vectors);
        } else {
            assert_int_equal(load_into(f, &got, counts[k], why), HL_OK);
        }
        assert_same(&m, &got);
    }
}

static void test_missing_file(void **state)
{
    fixture_t *f = *state;
    hl_mapfile_t got;
    char why[HL_MAPSTORE_WHY_LEN];
    errno = 0;
    assert_int_equal(load_into(f, &got, BIG, why), HL_ERR_OS);
    assert_int_equal(errno, ENOENT);
    assert_reason(why, f->path);
    assert_int_equal(got.count, 777);
}

/* Every prefix of a two-vector file, from empty to one byte short, is refused as
 * malformed, and nothing is returned. */
static void test_every_truncation_refused(void **state)
{
    fixture_t *f = *state;
    hl_mapfile_t m = sample(f->a, 2, 10), got;
    char why[HL_MAPSTORE_WHY_LEN];
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
    uint8_t buf[HDR + 24 + 4];
    assert_int_equal(read_bytes(f->path, buf, sizeof buf), sizeof buf);
    for (size_t n = 0; n < sizeof buf; n++) {
        write_bytes(f->path, buf, n);
        assert_int_equal(load_into(f, &got, BIG, why), HL_ERR_PARSE);
        assert_reason(why, f->path);
        assert_int_equal(got.count, 777);
    }
    write_bytes(f->path, buf, sizeof buf);
    assert_int_equal(load_into(f, &got, BIG, why), HL_OK);
}

/* Each of the 968 single-bit flips of a two-vector file is refused. */
static void test_every_bit_flip_refused(void **state)
{
    fixture_t *f = *state;
    hl_mapfile_t m = sample(f->a, 2, 10), got;
    char why[HL_MAPSTORE_WHY_LEN];
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
    uint8_t buf[HDR + 24 + 4];
    assert_int_equal(read_bytes(f->path, buf, sizeof buf), sizeof buf);
    for (size_t bit = 0; bit < 8 * sizeof buf; bit++) {
        buf[bit / 8] ^= (uint8_t)(1u << (bit % 8));
        write_bytes(f->path, buf, sizeof buf);
        hl_status_t st = load_into(f, &got, BIG, why);
        assert_true(st == HL_ERR_PARSE || st == HL_ERR_RANGE);
        assert_reason(why, f->path);
        assert_int_equal(got.count, 777);
        buf[bit / 8] ^= (uint8_t)(1u << (bit % 8));
    }
}

static void test_wrong_magic_and_version(void **state)
{
    fixture_t *f = *state;
    hl_mapfile_t m = sample(f->a, 2, 10), got;
    char why[HL_MAPSTORE_WHY_LEN], want[HL_MAPSTORE_WHY_LEN + 200];
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
    uint8_t buf[HDR + 24 + 4];
    read_bytes(f->path, buf, sizeof buf);
    buf[0] = 'h';   /* checksum made right: the magic alone refuses it */
    fix_crc(buf, sizeof buf);
    write_bytes(f->path, buf, sizeof buf);
    assert_int_equal(load_into(f, &got, BIG, why), HL_ERR_PARSE);
    snprintf(want, sizeof want, "%s: not a houghloc map file (no HLMAP magic)", f->path);
    assert_string_equal(why, want);
    write_bytes(f->path, (const uint8_t *)"x = 1\n", 6);
    assert_int_equal(load_into(f, &got, BIG, why), HL_ERR_PARSE);
    assert_string_equal(why, want);

    buf[0] = 'H';
    put_le(buf + 8, 2, 4);
    fix_crc(buf, sizeof buf);
    write_bytes(f->path, buf, sizeof buf);
    assert_int_equal(load_into(f, &got, BIG, why), HL_ERR_PARSE);
    snprintf(want, sizeof want, "%s: map file format version 2; this program reads version 1",
             f->path);
    assert_string_equal(why, want);
    assert_int_equal(got.count, 777);
}

/* Fields out of range behind a correct checksum: refused by the range checks. */
static void test_ranges_checked(void **state)
{
    fixture_t *f = *state;
    hl_mapfile_t m = sample(f->a, 2, 10), got;
    char why[HL_MAPSTORE_WHY_LEN];
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
    enum { N = HDR + 24 + 4 };
    uint8_t good[N], buf[N + 1];
    read_bytes(f->path, good, N);
    struct { size_t off; int bytes; uint64_t value; hl_status_t st; } cases[] = {
        { 28, 1, 2, HL_ERR_RANGE },                             /* started */
        { 29, 4, (uint32_t)(HL_COORD_MAX_MM + 1), HL_ERR_RANGE },   /* pose x */
        { 33, 4, (uint32_t)(-HL_COORD_MAX_MM - 1), HL_ERR_RANGE },  /* pose y */
        { 39, 4, 0x80000000u, HL_ERR_RANGE },                   /* odometry x */
        { 43, 4, (uint32_t)(HL_COORD_MAX_MM + 1), HL_ERR_RANGE },   /* odometry y */
        { 16, 4, 0, HL_ERR_RANGE },                             /* capacity 0 */
        { 16, 4, 1, HL_ERR_RANGE },                             /* count 2 > capacity 1 */
        { 16, 4, HL_MAP_MAX_CAPACITY + 1, HL_ERR_RANGE },       /* capacity */
        { 61, 8, 0xfedcba9876543210ULL, HL_ERR_RANGE },         /* an even increment */
        { HDR, 4, (uint32_t)(HL_COORD_MAX_MM + 1), HL_ERR_RANGE },  /* vector 0 x */
        { HDR + 12 + 4, 4, (uint32_t)INT32_MIN, HL_ERR_RANGE },     /* vector 1 y */
        { HDR + 12 + 10, 2, HL_RANGE_MAX_MM + 1, HL_ERR_RANGE },    /* vector 1 range */
        { 12, 4, HDR + 1, HL_ERR_PARSE },                       /* header length */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        memcpy(buf, good, N);
        put_le(buf + cases[i].off, cases[i].value, cases[i].bytes);
        fix_crc(buf, N);
        write_bytes(f->path, buf, N);
        assert_int_equal(load_into(f, &got, BIG, why), cases[i].st);
        assert_reason(why, f->path);
        assert_int_equal(got.count, 777);
    }
    /* one trailing byte */
    memcpy(buf, good, N);
    buf[N] = 0;
    write_bytes(f->path, buf, N + 1);
    assert_int_equal(load_into(f, &got, BIG, why), HL_ERR_PARSE);
    /* the good file loads, and save refuses what load would refuse */
    write_bytes(f->path, good, N);
    assert_int_equal(load_into(f, &got, BIG, why), HL_OK);
    m.count = 11;
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_ERR_RANGE);
    assert_reason(why, f->path);
    m.count = 2;
    f->a[1].range_mm = HL_RANGE_MAX_MM + 1;
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_ERR_RANGE);
    assert_int_equal(file_size(f->tmp), -1);
    assert_int_equal(load_into(f, &got, BIG, why), HL_OK);  /* still the good one */
}

/* More vectors than the caller's storage: HL_ERR_CAPACITY, and nothing is written past
 * the storage. */
static void test_count_over_max_vectors(void **state)
{
    fixture_t *f = *state;
    hl_mapfile_t m = sample(f->a, 5, 100), got;
    char why[HL_MAPSTORE_WHY_LEN];
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
    memset(f->b, 0x5a, 5 * sizeof *f->b);
    hl_vector_t canary = f->b[4];
    assert_int_equal(load_into(f, &got, 4, why), HL_ERR_CAPACITY);
    assert_reason(why, f->path);
    assert_non_null(strstr(why, "5 vectors"));
    assert_memory_equal(&f->b[4], &canary, sizeof canary);
    assert_int_equal(got.count, 777);
    assert_int_equal(load_into(f, &got, 5, why), HL_OK);
    assert_same(&m, &got);
}

/* A folder that does not exist; a target that is a folder (the rename fails after the
 * whole temporary file was written); a write that fails half-way (a file size limit).
 * Each fails with HL_ERR_OS, leaves no temporary file, and leaves the old map whole. */
static void test_save_fails_cleanly(void **state)
{
    fixture_t *f = *state;
    hl_mapfile_t m = sample(f->a, 1500, 1500), old = sample(f->b, 7, 100), got;
    char why[HL_MAPSTORE_WHY_LEN], p[200], t[220];

    snprintf(p, sizeof p, "%s/no-such-folder/map.hlmap", f->dir);
    errno = 0;
    assert_int_equal(hl_mapstore_save(p, &m, why), HL_ERR_OS);
    assert_int_equal(errno, ENOENT);
    assert_reason(why, p);

    snprintf(p, sizeof p, "%s/taken", f->dir);
    snprintf(t, sizeof t, "%s/inside", p);
    assert_int_equal(mkdir(p, 0700), 0);
    write_bytes(t, (const uint8_t *)"x", 1);
    assert_int_equal(hl_mapstore_save(p, &m, why), HL_ERR_OS);
    assert_reason(why, p);
    snprintf(t, sizeof t, "%s.tmp", p);
    assert_int_equal(file_size(t), -1);

    /* a folder we may not write in: only meaningful when not root */
    if (geteuid() != 0) {
        snprintf(p, sizeof p, "%s/ro", f->dir);
        assert_int_equal(mkdir(p, 0500), 0);
        snprintf(t, sizeof t, "%s/map.hlmap", p);
        errno = 0;
        assert_int_equal(hl_mapstore_save(t, &m, why), HL_ERR_OS);
        assert_int_equal(errno, EACCES);
    }

    /* the old map in place, then a save that cannot write past 4 KiB */
    assert_int_equal(hl_mapstore_save(f->path, &old, why), HL_OK);
    memcpy(f->a + 2000, f->b, 7 * sizeof *f->b);    /* keep the old vectors to compare */
    old.vectors = f->a + 2000;
    struct rlimit saved, small = { 4096, 4096 };
    assert_int_equal(getrlimit(RLIMIT_FSIZE, &saved), 0);
    small.rlim_max = saved.rlim_max;
    void (*was)(int) = signal(SIGXFSZ, SIG_IGN);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &small), 0);
    errno = 0;
    hl_status_t st = hl_mapstore_save(f->path, &m, why);
    int err = errno;
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &saved), 0);
    signal(SIGXFSZ, was);
    assert_int_equal(st, HL_ERR_OS);
    assert_int_equal(err, EFBIG);
    assert_reason(why, f->path);
    assert_int_equal(file_size(f->tmp), -1);
    assert_int_equal(load_into(f, &got, BIG, why), HL_OK);
    assert_same(&old, &got);
}

/* A save over an existing (larger) file, and over a stale temporary file left by a
 * crash: the result is exactly the new map. */
static void test_save_replaces_whole(void **state)
{
    fixture_t *f = *state;
    hl_mapfile_t big = sample(f->a, 1500, 1500), got;
    char why[HL_MAPSTORE_WHY_LEN];
    assert_int_equal(hl_mapstore_save(f->path, &big, why), HL_OK);
    hl_vector_t small_v[2];
    hl_mapfile_t small = sample(small_v, 2, 3);
    small.state.started = false;
    write_bytes(f->tmp, (const uint8_t *)"stale", 5);
    assert_int_equal(hl_mapstore_save(f->path, &small, why), HL_OK);
    assert_int_equal(file_size(f->path), HDR + 24 + 4);
    assert_int_equal(file_size(f->tmp), -1);
    assert_int_equal(load_into(f, &got, BIG, why), HL_OK);
    assert_same(&small, &got);
}

static void test_move_aside(void **state)
{
    fixture_t *f = *state;
    char why[HL_MAPSTORE_WHY_LEN], to[256], want[256], bad3[256];
    uint8_t buf[16];
    write_bytes(f->path, (const uint8_t *)"first", 5);
    assert_int_equal(hl_mapstore_move_aside(f->path, to, sizeof to, why), HL_OK);
    snprintf(want, sizeof want, "%s.bad-1", f->path);
    assert_string_equal(to, want);
    assert_int_equal(file_size(f->path), -1);
    assert_int_equal(read_bytes(want, buf, sizeof buf), 5);
    assert_memory_equal(buf, "first", 5);

    write_bytes(f->path, (const uint8_t *)"second", 6);
    assert_int_equal(hl_mapstore_move_aside(f->path, to, sizeof to, why), HL_OK);
    snprintf(want, sizeof want, "%s.bad-2", f->path);
    assert_string_equal(to, want);

    /* .bad-3 is taken by something else: it is skipped, not overwritten */
    snprintf(bad3, sizeof bad3, "%s.bad-3", f->path);
    write_bytes(bad3, (const uint8_t *)"keep", 4);
    write_bytes(f->path, (const uint8_t *)"third", 5);
    assert_int_equal(hl_mapstore_move_aside(f->path, NULL, 0, why), HL_OK);
    assert_int_equal(read_bytes(bad3, buf, sizeof buf), 4);
    assert_memory_equal(buf, "keep", 4);
    snprintf(want, sizeof want, "%s.bad-4", f->path);
    assert_int_equal(read_bytes(want, buf, sizeof buf), 5);
    assert_memory_equal(buf, "third", 5);
    snprintf(want, sizeof want, "%s.bad-1", f->path);
    assert_int_equal(read_bytes(want, buf, sizeof buf), 5);
    assert_memory_equal(buf, "first", 5);

    errno = 0;
    assert_int_equal(hl_mapstore_move_aside(f->path, to, sizeof to, why), HL_ERR_OS);
    assert_int_equal(errno, ENOENT);
    assert_reason(why, f->path);
    assert_string_equal(to, "");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_layout_and_round_trip, setup, teardown),
        cmocka_unit_test_setup_teardown(test_round_trip_sizes, setup, teardown),
        cmocka_unit_test_setup_teardown(test_missing_file, setup, teardown),
        cmocka_unit_test_setup_teardown(test_every_truncation_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_every_bit_flip_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_wrong_magic_and_version, setup, teardown),
        cmocka_unit_test_setup_teardown(test_ranges_checked, setup, teardown),
        cmocka_unit_test_setup_teardown(test_count_over_max_vectors, setup, teardown),
        cmocka_unit_test_setup_teardown(test_save_fails_cleanly, setup, teardown),
        cmocka_unit_test_setup_teardown(test_save_replaces_whole, setup, teardown),
        cmocka_unit_test_setup_teardown(test_move_aside, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
