/* Tests for src/store/mapstore.c: the map file's layout byte by byte, round trips, saves
 * that fail leave no temporary file and the old map whole, moving a bad file aside. What a
 * bad file is refused for: test_mapstore_refuse.c. */
#include "mapstore_fixture.h"

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
    assert_int_equal(le(buf + 8, 4), 2);
    assert_int_equal(le(buf + 12, 4), HDR);
    assert_int_equal(le(buf + 16, 4), 1500);
    assert_int_equal(le(buf + 20, 4), 3);
    assert_true(le(buf + 24, 8) == 0x123456789abULL);     /* past 32 bits, whole */
    assert_int_equal(buf[32], 1);
    assert_int_equal((int32_t)le(buf + 33, 4), -HL_COORD_MAX_MM);
    assert_int_equal((int32_t)le(buf + 37, 4), HL_COORD_MAX_MM);
    assert_int_equal(le(buf + 41, 2), 65535);
    assert_int_equal((int32_t)le(buf + 43, 4), 123456);
    assert_int_equal((int32_t)le(buf + 47, 4), -654321);
    assert_int_equal(le(buf + 51, 2), 4321);
    assert_int_equal(le(buf + 53, 4), 0xfedcba98u);
    assert_true(le(buf + 57, 8) == 0x0123456789abcdefULL);
    assert_true(le(buf + 65, 8) == 0xfedcba9876543211ULL);
    assert_true((int64_t)le(buf + 73, 8) == INT64_MAX - 5);
    assert_true((int64_t)le(buf + 81, 8) == 1700000000123456LL);
    assert_true(le(buf + 89, 8) == 0x8000000000000001ULL);
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
    assert_int_equal(got.format, 2);
    assert_ptr_equal(got.vectors, f->b);
    assert_int_equal(got.max_vectors, BIG);
    assert_int_equal(file_size(f->tmp), -1);
}

/* The largest map version there is (versions stop there, count.h) round-trips; one
 * above it is never written. */
static void test_version_limit(void **state)
{
    fixture_t *f = *state;
    hl_mapfile_t m = sample(f->a, 2, 10), got;
    char why[HL_MAPSTORE_WHY_LEN];
    m.state.map_version = (uint64_t)HL_COUNT_MAX;
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
    assert_int_equal(load_into(f, &got, BIG, why), HL_OK);
    assert_true(got.state.map_version == (uint64_t)INT64_MAX);
    m.state.map_version = (uint64_t)HL_COUNT_MAX + 1;
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_ERR_RANGE);
    assert_reason(why, f->path);
    assert_non_null(strstr(why, "map version"));
}

/* A file of format version 1 (the map version in 4 bytes, every later field 4 bytes
 * earlier) still loads, its version widened, and the next save writes version 2. */
static void test_version_1_loads(void **state)
{
    fixture_t *f = *state;
    hl_mapfile_t m = sample(f->a, 3, 1500), got;
    m.state.map_version = 0xfffffffeu;     /* the largest a version 1 file held, nearly */
    char why[HL_MAPSTORE_WHY_LEN];
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
    uint8_t buf[HDR + 3 * 12 + 4];
    assert_int_equal(read_bytes(f->path, buf, sizeof buf), sizeof buf);
    size_t n = to_v1(buf, sizeof buf);
    assert_int_equal(n, HDR_V1 + 3 * 12 + 4);
    assert_int_equal(le(buf + 24, 4), 0xfffffffeu);
    assert_int_equal(buf[28], 1);           /* version 1's started byte */
    write_bytes(f->path, buf, n);
    assert_int_equal(load_into(f, &got, BIG, why), HL_OK);
    assert_string_equal(why, "");
    assert_int_equal(got.format, 1);
    assert_same(&m, &got);
    /* ... and it goes on past 32 bits, in version 2 */
    got.state.map_version += 3;
    assert_int_equal(hl_mapstore_save(f->path, &got, why), HL_OK);
    assert_int_equal(file_size(f->path), HDR + 3 * 12 + 4);
    hl_mapfile_t again;
    memset(f->a, 0, 3 * sizeof *f->a);
    memset(&again, 0, sizeof again);
    again.vectors = f->a;
    again.max_vectors = BIG;
    assert_int_equal(hl_mapstore_load(f->path, &again, why), HL_OK);
    assert_int_equal(again.format, 2);
    assert_true(again.state.map_version == 0x100000001ULL);
    assert_same(&got, &again);
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
        cmocka_unit_test_setup_teardown(test_version_limit, setup, teardown),
        cmocka_unit_test_setup_teardown(test_version_1_loads, setup, teardown),
        cmocka_unit_test_setup_teardown(test_round_trip_sizes, setup, teardown),
        cmocka_unit_test_setup_teardown(test_missing_file, setup, teardown),
        cmocka_unit_test_setup_teardown(test_save_fails_cleanly, setup, teardown),
        cmocka_unit_test_setup_teardown(test_save_replaces_whole, setup, teardown),
        cmocka_unit_test_setup_teardown(test_move_aside, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
