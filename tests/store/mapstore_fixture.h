/* mapstore_fixture.h - what the map file's tests share: a temporary folder, a sample map,
 * byte-level access to the file (little-endian fields, the crc fixed after a change). */
#ifndef HOUGHLOC_TESTS_MAPSTORE_FIXTURE_H
#define HOUGHLOC_TESTS_MAPSTORE_FIXTURE_H

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

#include "houghloc/mapstore.h"

#define HDR 97              /* the header, format version 2 */
#define HDR_V1 93           /* ... version 1: the map version in 4 bytes */
#define BIG 16384

typedef struct fixture {
    char dir[64];
    char path[128];         /* dir/map.hlmap */
    char tmp[140];          /* path.tmp */
    hl_vector_t *a, *b;     /* BIG vectors each: to save, to load into */
} fixture_t;

static inline int setup(void **state)
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
static inline void remove_tree(const char *dir)
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
        if (snprintf(p, sizeof p, "%s/%s", dir, e->d_name) >= (int)sizeof p)
            continue;   /* cannot be: the test's own short names */
        if (unlink(p) != 0)
            remove_tree(p);
    }
    closedir(d);
    rmdir(dir);
}

static inline int teardown(void **state)
{
    fixture_t *f = *state;
    remove_tree(f->dir);
    free(f->a);
    free(f->b);
    free(f);
    return 0;
}

/* ---- helpers ------------------------------------------------------------------------- */

static inline long file_size(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 ? (long)sb.st_size : -1;
}

static inline size_t read_bytes(const char *path, uint8_t *buf, size_t cap)
{
    FILE *fp = fopen(path, "rb");
    assert_non_null(fp);
    size_t n = fread(buf, 1, cap, fp);
    fclose(fp);
    return n;
}

static inline void write_bytes(const char *path, const uint8_t *buf, size_t n)
{
    FILE *fp = fopen(path, "wb");
    assert_non_null(fp);
    assert_int_equal(fwrite(buf, 1, n, fp), n);
    assert_int_equal(fclose(fp), 0);
}

static inline uint64_t le(const uint8_t *b, int bytes)
{
    uint64_t v = 0;
    for (int i = 0; i < bytes; i++)
        v |= (uint64_t)b[i] << (8 * i);
    return v;
}

static inline void put_le(uint8_t *b, uint64_t v, int bytes)
{
    for (int i = 0; i < bytes; i++)
        b[i] = (uint8_t)(v >> (8 * i));
}

/* Rewrites the trailing checksum of a file image of @p n bytes. */
static inline void fix_crc(uint8_t *buf, size_t n)
{
    put_le(buf + n - 4, crc32(0L, buf, (uInt)(n - 4)), 4);
}

/* A map file with every field set to something recognisable. */
static inline hl_mapfile_t sample(hl_vector_t *v, uint32_t count, uint32_t capacity)
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
                   .map_version = 0x123456789abULL,     /* past 32 bits */
                   .cull_rng = { 0x0123456789abcdefULL, 0xfedcba9876543211ULL } },
        .capacity = capacity, .count = count, .vectors = v,
        .last_request_seq = INT64_MAX - 5, .last_scan_utime = 1700000000123456LL,
        .scans = 0x8000000000000001ULL,
    };
    return m;
}

static inline void assert_same(const hl_mapfile_t *a, const hl_mapfile_t *b)
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

/* Rewrites the version 2 file image @p buf of @p n bytes in place as the same map in
 * format version 1 (its map version cut to its low 32 bits; the header 4 bytes shorter).
 * @return the image's new length. */
static inline size_t to_v1(uint8_t *buf, size_t n)
{
    put_le(buf + 8, 1, 4);
    put_le(buf + 12, HDR_V1, 4);
    memmove(buf + 28, buf + 32, n - 32);
    n -= 4;
    fix_crc(buf, n);
    return n;
}

/* A reason: one line that starts with "PATH: ". */
static inline void assert_reason(const char *why, const char *path)
{
    size_t n = strlen(path);
    assert_true(strncmp(why, path, n) == 0 && why[n] == ':' && why[n + 1] == ' ');
    assert_true(strlen(why) > n + 2);
    assert_null(strchr(why, '\n'));
}

static inline hl_status_t load_into(fixture_t *f, hl_mapfile_t *out, uint32_t max, char *why)
{
    memset(out, 0, sizeof *out);
    out->count = 777;   /* a sentinel: a refused load leaves it */
    out->vectors = f->b;
    out->max_vectors = max;
    return hl_mapstore_load(f->path, out, why);
}

/* ---- tests --------------------------------------------------------------------------- */

/* Every field at the offset docs/manual/mapfile.md gives, and back. */

#endif
