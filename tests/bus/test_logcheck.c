/* Tests for src/bus/logcheck.c: good logs (written by liblcm and by hand, from a file
 * and through a pipe), every kind of bad framing with the byte offset it is reported
 * at, empty and missing files, and LCM URL parsing. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <lcm/eventlog.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "houghloc/logcheck.h"

typedef struct dir {
    char path[64];
    char file[128];
} dir_t;

static int setup(void **state)
{
    dir_t *d = calloc(1, sizeof *d);
    if (!d)
        return -1;
    strcpy(d->path, "/tmp/hl_logcheck_XXXXXX");
    if (!mkdtemp(d->path))
        return -1;
    snprintf(d->file, sizeof d->file, "%s/t.lcmlog", d->path);
    *state = d;
    return 0;
}

static int teardown(void **state)
{
    dir_t *d = *state;
    unlink(d->file);
    rmdir(d->path);
    free(d);
    return 0;
}

static void put_be(uint8_t *b, uint64_t v, int n)
{
    for (int i = 0; i < n; i++)
        b[i] = (uint8_t)(v >> (8 * (n - 1 - i)));
}

/* One event by hand, with whatever header fields the test asks for; returns its size. */
static size_t put_event(FILE *f, uint32_t sync, int64_t utime, int32_t chan_len,
                        int32_t data_len, const char *chan, size_t chan_bytes,
                        size_t data_bytes)
{
    uint8_t h[28];
    put_be(h, sync, 4);
    put_be(h + 4, 0, 8);
    put_be(h + 12, (uint64_t)utime, 8);
    put_be(h + 20, (uint32_t)chan_len, 4);
    put_be(h + 24, (uint32_t)data_len, 4);
    assert_int_equal(fwrite(h, 1, sizeof h, f), sizeof h);
    assert_int_equal(fwrite(chan, 1, chan_bytes, f), chan_bytes);
    for (size_t i = 0; i < data_bytes; i++)
        assert_int_not_equal(fputc((int)(i & 0xff), f), EOF);
    return sizeof h + chan_bytes + data_bytes;
}

static size_t good_event(FILE *f, int64_t utime, size_t data_bytes)
{
    return put_event(f, HL_LOG_SYNC, utime, 5, (int32_t)data_bytes, "SONAR", 5, data_bytes);
}

/* hl_log_check fails with @p want, one line, naming the file and "byte <at>: " and
 * containing @p text. */
static void expect_bad(const dir_t *d, hl_status_t want, uint64_t at, const char *text)
{
    char why[HL_LOG_WHY_LEN] = "", prefix[200];
    hl_log_info_t info;
    assert_int_equal(hl_log_check(d->file, &info, why), want);
    snprintf(prefix, sizeof prefix, "%s: byte %llu: ", d->file, (unsigned long long)at);
    if (strncmp(why, prefix, strlen(prefix)) != 0 || !strstr(why, text))
        fail_msg("reason \"%s\" lacks \"%s\" or \"%s\"", why, prefix, text);
    assert_null(strchr(why, '\n'));
}

static void test_log_written_by_liblcm(void **state)
{
    dir_t *d = *state;
    lcm_eventlog_t *log = lcm_eventlog_create(d->file, "w");
    assert_non_null(log);
    uint8_t data[300] = { 0 };
    char chan[] = "POSE";
    for (int i = 0; i < 3; i++) {
        lcm_eventlog_event_t ev = { .eventnum = i, .timestamp = 1000 + i * 10,
                                    .channellen = 4, .datalen = 100 * i,
                                    .channel = chan, .data = data };
        assert_int_equal(lcm_eventlog_write_event(log, &ev), 0);
    }
    lcm_eventlog_destroy(log);
    hl_log_info_t info;
    char why[HL_LOG_WHY_LEN];
    assert_int_equal(hl_log_check(d->file, &info, why), HL_OK);
    assert_int_equal(info.events, 3);
    assert_int_equal(info.bytes, 3 * (28 + 4) + 0 + 100 + 200);
    assert_int_equal(info.first_utime, 1000);
    assert_int_equal(info.last_utime, 1020);
    assert_int_equal(hl_log_check(d->file, NULL, NULL), HL_OK);
}

static void test_bad_framing_reported_at_its_event(void **state)
{
    dir_t *d = *state;
    FILE *f;
    size_t first;
    /* a valid first event, then a header declaring 0x7fffffff data bytes and a few */
    f = fopen(d->file, "wb");
    first = good_event(f, 5, 40);
    put_event(f, HL_LOG_SYNC, 6, 5, 0x7fffffff, "SONAR", 5, 7);
    fclose(f);
    expect_bad(d, HL_ERR_PARSE, first, "data length 2147483647 runs past the end");

    /* truncated inside the second header */
    f = fopen(d->file, "wb");
    first = good_event(f, 5, 40);
    assert_int_equal(fwrite("\xed\xa1\xda\x01\0\0", 1, 6, f), 6);
    fclose(f);
    expect_bad(d, HL_ERR_PARSE, first, "truncated event header: 6 of 28");

    /* truncated inside the data, and inside the channel */
    f = fopen(d->file, "wb");
    first = good_event(f, 5, 40);
    put_event(f, HL_LOG_SYNC, 6, 5, 100, "SONAR", 5, 99);
    fclose(f);
    expect_bad(d, HL_ERR_PARSE, first, "data length 100 runs past the end");
    f = fopen(d->file, "wb");
    put_event(f, HL_LOG_SYNC, 6, 9, 0, "SONAR", 5, 0);
    fclose(f);
    expect_bad(d, HL_ERR_PARSE, 0, "channel length 9 runs past the end");

    /* bad sync word, in the first event and after two good ones */
    f = fopen(d->file, "wb");
    put_event(f, 0xEDA1DA02u, 6, 5, 0, "SONAR", 5, 0);
    fclose(f);
    expect_bad(d, HL_ERR_PARSE, 0, "sync word 0xeda1da02");
    f = fopen(d->file, "wb");
    first = good_event(f, 5, 3);
    first += good_event(f, 6, 0);
    put_event(f, 0, 7, 5, 0, "SONAR", 5, 0);
    fclose(f);
    expect_bad(d, HL_ERR_PARSE, first, "sync word 0x00000000");

    /* channel lengths 0, 256 and negative; a negative data length; an event above the
     * size limit although the file holds it */
    const int32_t chans[] = { 0, HL_LOG_CHANNEL_MAX + 1, -1 };
    for (int k = 0; k < 3; k++) {
        f = fopen(d->file, "wb");
        first = good_event(f, 5, 1);
        put_event(f, HL_LOG_SYNC, 6, chans[k], 0, "SONAR", 5, 0);
        fclose(f);
        char text[64];
        snprintf(text, sizeof text, "channel length %d outside 1..255", chans[k]);
        expect_bad(d, HL_ERR_PARSE, first, text);
    }
    f = fopen(d->file, "wb");
    put_event(f, HL_LOG_SYNC, 6, 5, -28, "SONAR", 5, 0);
    fclose(f);
    expect_bad(d, HL_ERR_PARSE, 0, "data length -28 is negative");
    f = fopen(d->file, "wb");
    put_event(f, HL_LOG_SYNC, 6, 5, (int32_t)HL_LOG_EVENT_MAX_BYTES + 1, "SONAR", 5,
              HL_LOG_EVENT_MAX_BYTES + 1);
    fclose(f);
    expect_bad(d, HL_ERR_PARSE, 0, "above the 67108864-byte limit");
}

static void test_empty_and_missing_files(void **state)
{
    dir_t *d = *state;
    FILE *f = fopen(d->file, "wb");
    fclose(f);
    expect_bad(d, HL_ERR_EMPTY, 0, "no event");

    char missing[160], why[HL_LOG_WHY_LEN];
    snprintf(missing, sizeof missing, "%s/nothing.lcmlog", d->path);
    errno = 0;
    assert_int_equal(hl_log_check(missing, NULL, why), HL_ERR_OS);
    assert_int_equal(errno, ENOENT);
    assert_non_null(strstr(why, missing));
    assert_non_null(strstr(why, "cannot open"));
    assert_int_equal(hl_log_check(NULL, NULL, why), HL_ERR_ARG);
    assert_int_equal(hl_log_check(d->path, NULL, why), HL_ERR_OS);    /* a folder */
}

/* The same walk through a pipe, where the size is not known and data is read past. */
static hl_status_t check_through_fifo(const dir_t *d, const uint8_t *bytes, size_t n,
                                      hl_log_info_t *info, char *why)
{
    char fifo[160];
    snprintf(fifo, sizeof fifo, "%s/fifo", d->path);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        FILE *w = fopen(fifo, "wb");
        size_t put = w ? fwrite(bytes, 1, n, w) : 0;
        _exit(w && put == n && fclose(w) == 0 ? 0 : 1);
    }
    hl_status_t st = hl_log_check(fifo, info, why);
    int wstatus = 0;
    assert_int_equal(waitpid(pid, &wstatus, 0), pid);
    unlink(fifo);
    return st;
}

static void test_pipe(void **state)
{
    dir_t *d = *state;
    FILE *f = fopen(d->file, "wb");
    size_t first = good_event(f, 5, 5000);
    good_event(f, 9, 20000);
    fclose(f);
    static uint8_t bytes[40000];
    f = fopen(d->file, "rb");
    size_t n = fread(bytes, 1, sizeof bytes, f);
    fclose(f);
    hl_log_info_t info;
    char why[HL_LOG_WHY_LEN];
    assert_int_equal(check_through_fifo(d, bytes, n, &info, why), HL_OK);
    assert_int_equal(info.events, 2);
    assert_int_equal(info.bytes, n);
    assert_int_equal(info.last_utime, 9);
    assert_int_equal(check_through_fifo(d, bytes, n - 1, &info, why), HL_ERR_PARSE);
    char want[64];
    snprintf(want, sizeof want, "byte %zu: event data length 20000 runs past", first);
    if (!strstr(why, want))
        fail_msg("reason \"%s\" lacks \"%s\"", why, want);
}

static void test_url_path(void **state)
{
    (void)state;
    char out[64];
    struct { const char *url; int want; const char *path; } cases[] = {
        { "file:///abs/in.lcmlog", 1, "/abs/in.lcmlog" },
        { "file://rel/in.lcmlog?speed=0", 1, "rel/in.lcmlog" },
        { "file:logs/tour.lcmlog", 1, "logs/tour.lcmlog" },
        { "file://x.lcmlog?speed=0&mode=r", 1, "x.lcmlog" },
        { "file://x.lcmlog?mode=w", 0, NULL },
        { "file://x.lcmlog?speed=1,mode=a", 0, NULL },
        { "file://x.lcmlog?mode=w&mode=r", 1, "x.lcmlog" },     /* the last one counts */
        { "file://x.lcmlog?mode=r&mode=w", 0, NULL },
        { "file://x.lcmlog?moderate=w", 1, "x.lcmlog" },
        { "file://", 0, NULL },
        { "file://?speed=0", 0, NULL },
        { "udpm://239.255.76.67:7667?ttl=0", 0, NULL },
        { "memq://", 0, NULL },
        { "", 0, NULL },
        { "logs/tour.lcmlog", 0, NULL },
        { "FILE:///x", 0, NULL },
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        strcpy(out, "untouched");
        int got = hl_log_url_path(cases[k].url, out, sizeof out);
        if (got != cases[k].want)
            fail_msg("%s: %d, not %d", cases[k].url, got, cases[k].want);
        assert_string_equal(out, cases[k].path ? cases[k].path : "untouched");
    }
    assert_int_equal(hl_log_url_path(NULL, out, sizeof out), 0);
    /* the path and its NUL must fit */
    assert_int_equal(hl_log_url_path("file://abcdefg?x", out, 8), 1);
    assert_string_equal(out, "abcdefg");
    assert_int_equal(hl_log_url_path("file://abcdefgh?x", out, 8), -1);
    assert_int_equal(hl_log_url_path("file://a", NULL, 0), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_log_written_by_liblcm, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_framing_reported_at_its_event, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_empty_and_missing_files, setup, teardown),
        cmocka_unit_test_setup_teardown(test_pipe, setup, teardown),
        cmocka_unit_test(test_url_path),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
