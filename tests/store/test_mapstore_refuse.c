/* Tests for src/store/mapstore.c's refusals: every truncation and every single-bit flip,
 * a wrong magic or version, each range check behind a good checksum, more vectors than
 * the caller holds. */
#include "mapstore_fixture.h"

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
    /* and of the same map in format version 1 */
    size_t n1 = to_v1(buf, sizeof buf);
    for (size_t n = 0; n < n1; n++) {
        write_bytes(f->path, buf, n);
        assert_int_equal(load_into(f, &got, BIG, why), HL_ERR_PARSE);
        assert_int_equal(got.count, 777);
    }
    write_bytes(f->path, buf, n1);
    assert_int_equal(load_into(f, &got, BIG, why), HL_OK);
    assert_int_equal(got.format, 1);
}

/* Each of the 1000 single-bit flips of a two-vector file is refused. */
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
    put_le(buf + 8, 3, 4);
    fix_crc(buf, sizeof buf);
    write_bytes(f->path, buf, sizeof buf);
    assert_int_equal(load_into(f, &got, BIG, why), HL_ERR_PARSE);
    snprintf(want, sizeof want,
             "%s: map file format version 3; this program reads versions 1 and 2", f->path);
    assert_string_equal(why, want);
    assert_int_equal(got.count, 777);
    put_le(buf + 8, 0, 4);
    fix_crc(buf, sizeof buf);
    write_bytes(f->path, buf, sizeof buf);
    assert_int_equal(load_into(f, &got, BIG, why), HL_ERR_PARSE);

    /* a version 2 file that says version 1 (or the reverse) is refused whole: its header
     * length is the other's */
    put_le(buf + 8, 1, 4);
    fix_crc(buf, sizeof buf);
    write_bytes(f->path, buf, sizeof buf);
    assert_int_equal(load_into(f, &got, BIG, why), HL_ERR_PARSE);
    assert_non_null(strstr(why, "header length 97, version 1 has 93"));
    put_le(buf + 8, 2, 4);
    size_t n1 = to_v1(buf, sizeof buf);
    put_le(buf + 8, 2, 4);
    fix_crc(buf, n1);
    write_bytes(f->path, buf, n1);
    assert_int_equal(load_into(f, &got, BIG, why), HL_ERR_PARSE);
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
        { 32, 1, 2, HL_ERR_RANGE },                             /* started */
        { 33, 4, (uint32_t)(HL_COORD_MAX_MM + 1), HL_ERR_RANGE },   /* pose x */
        { 37, 4, (uint32_t)(-HL_COORD_MAX_MM - 1), HL_ERR_RANGE },  /* pose y */
        { 43, 4, 0x80000000u, HL_ERR_RANGE },                   /* odometry x */
        { 47, 4, (uint32_t)(HL_COORD_MAX_MM + 1), HL_ERR_RANGE },   /* odometry y */
        { 16, 4, 0, HL_ERR_RANGE },                             /* capacity 0 */
        { 16, 4, 1, HL_ERR_RANGE },                             /* count 2 > capacity 1 */
        { 16, 4, HL_MAP_MAX_CAPACITY + 1, HL_ERR_RANGE },       /* capacity */
        { 24, 8, 0x8000000000000000ULL, HL_ERR_RANGE },         /* map version > 2^63 - 1 */
        { 24, 8, 0xffffffffffffffffULL, HL_ERR_RANGE },         /* map version */
        { 65, 8, 0xfedcba9876543210ULL, HL_ERR_RANGE },         /* an even increment */
        { 73, 8, 0x8000000000000000ULL, HL_ERR_RANGE },         /* last request seq < 0 */
        { 81, 8, 0xffffffffffffffffULL, HL_ERR_RANGE },         /* last scan time -1 */
        { HDR, 4, (uint32_t)(HL_COORD_MAX_MM + 1), HL_ERR_RANGE },  /* vector 0 x */
        { HDR + 12 + 4, 4, (uint32_t)INT32_MIN, HL_ERR_RANGE },     /* vector 1 y */
        { HDR + 12 + 10, 2, HL_RANGE_MAX_MM + 1, HL_ERR_RANGE },    /* vector 1 range */
        { 12, 4, HDR + 1, HL_ERR_PARSE },                       /* header length */
        { 12, 4, HDR_V1, HL_ERR_PARSE },                        /* version 1's length */
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_every_truncation_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_every_bit_flip_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_wrong_magic_and_version, setup, teardown),
        cmocka_unit_test_setup_teardown(test_ranges_checked, setup, teardown),
        cmocka_unit_test_setup_teardown(test_count_over_max_vectors, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
