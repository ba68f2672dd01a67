/* Tests for src/store/seqfile.c: the request state file's format both ways, and every
 * file that is not one whole line refused (torn, altered, oversized, not a file). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "houghloc/seqfile.h"

typedef struct dir {
    char path[128], file[160];
} dir_t;

static int setup(void **state)
{
    static dir_t d;
    snprintf(d.path, sizeof d.path, "/tmp/hl-test-seqfile-%ld", (long)getpid());
    if (mkdir(d.path, 0700) != 0 && errno != EEXIST)
        return -1;
    snprintf(d.file, sizeof d.file, "%s/" HL_SEQFILE_NAME, d.path);
    *state = &d;
    return 0;
}

static int teardown(void **state)
{
    dir_t *d = *state;
    char tmp[200];
    snprintf(tmp, sizeof tmp, "%s.tmp", d->file);
    unlink(tmp);
    unlink(d->file);
    rmdir(d->path);
    return 0;
}

static void write_file(const char *path, const char *text, size_t len)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(text, 1, len, f), len);
    fclose(f);
}

static void test_round_trip(void **state)
{
    dir_t *d = *state;
    static const int64_t seqs[] = { 0, 1, 1700000000123456, INT64_MAX };
    for (size_t i = 0; i < sizeof seqs / sizeof seqs[0]; i++) {
        char why[HL_SEQFILE_WHY_LEN] = "x";
        assert_int_equal(hl_seqfile_save(d->file, seqs[i], why), HL_OK);
        assert_string_equal(why, "");
        int64_t got = -1;
        assert_int_equal(hl_seqfile_load(d->file, &got, why), HL_OK);
        assert_true(got == seqs[i]);
    }
    /* the text is what the header says, and no temporary is left behind */
    char text[HL_SEQFILE_MAX_BYTES + 1];
    assert_int_equal(hl_seqfile_format(1700000000123456, text, sizeof text),
                     (int)strlen("hlseq 1 1700000000123456 ") + 9);
    assert_memory_equal(text, "hlseq 1 1700000000123456 ", 25);
    assert_int_equal(text[strlen(text) - 1], '\n');
    char tmp[200];
    snprintf(tmp, sizeof tmp, "%s.tmp", d->file);
    assert_int_equal(access(tmp, F_OK), -1);
    assert_int_equal(hl_seqfile_format(-1, text, sizeof text), -1);
    assert_int_equal(hl_seqfile_format(1, text, 10), -1);
    assert_int_equal(hl_seqfile_save(d->file, -1, NULL), HL_ERR_ARG);
}

/* Everything but one whole, unaltered line is refused, with a reason naming the file. */
static void test_refused(void **state)
{
    dir_t *d = *state;
    char good[HL_SEQFILE_MAX_BYTES + 1];
    int n = hl_seqfile_format(1700000000123456, good, sizeof good);
    assert_true(n > 0);
    static const struct { const char *text; const char *reason; } bad[] = {
        { "", "empty" },
        { "garbage\n", "not a request state file" },
        { "hlseq 2 17 00000000\n", "format version '2'" },
        { "hlseq 1 17\n", "malformed" },
        { "hlseq 1 017 00000000\n", "not a decimal" },
        { "hlseq 1 -17 00000000\n", "not a decimal" },
        { "hlseq 1 9223372036854775808 00000000\n", "not a decimal" },
        { "hlseq 1 17 0000000g\n", "not 8 hexadecimal" },
        { "hlseq 1 17 00000000 \n", "malformed" },
        { "hlseq 1 17 00000000\n\n", "more than one line" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        write_file(d->file, bad[i].text, strlen(bad[i].text));
        int64_t got = 42;
        char why[HL_SEQFILE_WHY_LEN] = "";
        assert_int_equal(hl_seqfile_load(d->file, &got, why), HL_ERR_PARSE);
        assert_non_null(strstr(why, d->file));
        assert_non_null(strstr(why, bad[i].reason));
        assert_true(got == 42);
    }
    /* torn: every prefix of a good file (a crash mid-write without the rename) */
    for (int len = 0; len < n; len++) {
        write_file(d->file, good, (size_t)len);
        int64_t got;
        assert_int_equal(hl_seqfile_load(d->file, &got, NULL), HL_ERR_PARSE);
    }
    /* altered: any one byte changed (a digit of the seq most of all) */
    for (int i = 0; i < n; i++) {
        for (int bit = 0; bit < 8; bit++) {
            char m[HL_SEQFILE_MAX_BYTES + 1];
            memcpy(m, good, (size_t)n);
            m[i] ^= (char)(1 << bit);
            write_file(d->file, m, (size_t)n);
            int64_t got;
            assert_int_equal(hl_seqfile_load(d->file, &got, NULL), HL_ERR_PARSE);
        }
    }
    /* oversized: a good line with more after it, or a huge file */
    char big[4096];
    memset(big, '1', sizeof big);
    memcpy(big, good, (size_t)n);
    write_file(d->file, big, sizeof big);
    char why[HL_SEQFILE_WHY_LEN];
    int64_t got;
    assert_int_equal(hl_seqfile_load(d->file, &got, why), HL_ERR_PARSE);
    assert_non_null(strstr(why, "more than the 64"));
    /* not a regular file */
    unlink(d->file);
    assert_int_equal(mkdir(d->file, 0700), 0);
    assert_int_not_equal(hl_seqfile_load(d->file, &got, why), HL_OK);
    rmdir(d->file);
    /* missing: HL_ERR_OS with ENOENT, which the daemon takes as an empty state */
    assert_int_equal(hl_seqfile_load(d->file, &got, why), HL_ERR_OS);
    assert_int_equal(errno, ENOENT);
    /* the good text itself parses */
    assert_int_equal(hl_seqfile_parse(good, (size_t)n, &got, NULL), HL_OK);
    assert_true(got == 1700000000123456);
}

/* A save replaces the file whole, and never writes through a link planted at PATH.tmp. */
static void test_save_replaces(void **state)
{
    dir_t *d = *state;
    write_file(d->file, "garbage\n", 8);
    assert_int_equal(hl_seqfile_save(d->file, 7, NULL), HL_OK);
    int64_t got;
    assert_int_equal(hl_seqfile_load(d->file, &got, NULL), HL_OK);
    assert_true(got == 7);
    char tmp[200], target[200];
    snprintf(tmp, sizeof tmp, "%s.tmp", d->file);
    snprintf(target, sizeof target, "%s/target", d->path);
    write_file(target, "keep\n", 5);
    assert_int_equal(symlink(target, tmp), 0);
    char why[HL_SEQFILE_WHY_LEN];
    assert_int_equal(hl_seqfile_save(d->file, 8, why), HL_ERR_OS);
    assert_non_null(strstr(why, "cannot create"));
    assert_int_equal(hl_seqfile_load(d->file, &got, NULL), HL_OK);
    assert_true(got == 7);
    FILE *f = fopen(target, "r");
    char text[8] = "";
    assert_non_null(fgets(text, sizeof text, f));
    fclose(f);
    assert_string_equal(text, "keep\n");
    unlink(tmp);
    unlink(target);
    /* a folder that does not exist: an OS error naming the file */
    assert_int_equal(hl_seqfile_save("/nonexistent-hl/requests.seq", 1, why), HL_ERR_OS);
    assert_non_null(strstr(why, "/nonexistent-hl/requests.seq"));
}

static void test_default_path(void **state)
{
    (void)state;
    char out[64];
    assert_true(hl_seqfile_default_path("/var/lib/houghloc/map.hlmap", out, sizeof out));
    assert_string_equal(out, "/var/lib/houghloc/requests.seq");
    assert_true(hl_seqfile_default_path("map.hlmap", out, sizeof out));
    assert_string_equal(out, "requests.seq");
    assert_true(hl_seqfile_default_path("/map.hlmap", out, sizeof out));
    assert_string_equal(out, "/requests.seq");
    assert_false(hl_seqfile_default_path("/a/very/long/folder/name/indeed/map", out, 20));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_refused),
        cmocka_unit_test(test_save_replaces),
        cmocka_unit_test(test_default_path),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
