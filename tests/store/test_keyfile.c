/* Tests for src/store/keyfile.c: a good key file, and every file it must refuse (open
 * to group or others, missing, a directory, a FIFO, a symbolic link, too large, not a
 * key), each with one line naming the file. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "houghloc/keyfile.h"

static const char good_hex[] =
    "000102030405060708090a0b0c0d0e0f101112131415161718191a1b1c1d1e1f\n";

typedef struct fixture {
    char dir[64];
    char path[128];
} fixture_t;

static int setup(void **state)
{
    fixture_t *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    snprintf(f->dir, sizeof f->dir, "/tmp/hl_keyfile_XXXXXX");
    if (!mkdtemp(f->dir))
        return -1;
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture_t *f = *state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", f->dir);
    int rc = system(cmd);
    free(f);
    return rc == 0 ? 0 : -1;
}

/* Writes @p text to DIR/@p name with @p mode (set explicitly, whatever the umask). */
static const char *write_file(fixture_t *f, const char *name, const char *text, size_t len,
                              mode_t mode)
{
    snprintf(f->path, sizeof f->path, "%s/%s", f->dir, name);
    int fd = open(f->path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, text, len), (ssize_t)len);
    assert_int_equal(fchmod(fd, mode), 0);
    assert_int_equal(close(fd), 0);
    return f->path;
}

/* The load fails with @p want, leaves the key alone, and says one line with the path
 * and @p reason. */
static void refused(const char *path, hl_status_t want, const char *reason)
{
    hl_auth_key_t key;
    memset(&key, 0x5a, sizeof key);
    char why[HL_KEYFILE_WHY_LEN] = "";
    assert_int_equal(hl_keyfile_load(path, &key, why), want);
    if (!strstr(why, reason) || !strstr(why, path))
        fail_msg("message \"%s\" should name %s and say \"%s\"", why, path, reason);
    assert_null(strchr(why, '\n'));
    for (int i = 0; i < HL_AUTH_KEY_BYTES; i++)
        assert_int_equal(key.bytes[i], 0x5a);
}

static void test_good_key(void **state)
{
    fixture_t *f = *state;
    hl_auth_key_t key;
    char why[HL_KEYFILE_WHY_LEN];
    const char *p = write_file(f, "key", good_hex, strlen(good_hex), 0600);
    assert_int_equal(hl_keyfile_load(p, &key, why), HL_OK);
    for (int i = 0; i < HL_AUTH_KEY_BYTES; i++)
        assert_int_equal(key.bytes[i], i);
    /* Read-only for the owner is fine too, and so is no final newline. */
    p = write_file(f, "key_ro", good_hex, 64, 0400);
    memset(&key, 0, sizeof key);
    assert_int_equal(hl_keyfile_load(p, &key, NULL), HL_OK);
    assert_int_equal(key.bytes[31], 0x1f);
}

static void test_open_to_group_or_others(void **state)
{
    fixture_t *f = *state;
    const mode_t modes[] = { 0644, 0640, 0604, 0620, 0602, 0660, 0666 };
    for (size_t i = 0; i < sizeof modes / sizeof modes[0]; i++) {
        const char *p = write_file(f, "key", good_hex, strlen(good_hex), modes[i]);
        refused(p, HL_ERR_RANGE, "chmod 600");
    }
    const char *p = write_file(f, "key", good_hex, strlen(good_hex), 0644);
    refused(p, HL_ERR_RANGE, "mode 0644");
    p = write_file(f, "key", good_hex, strlen(good_hex), 0640);
    refused(p, HL_ERR_RANGE, "mode 0640");
}

static void test_missing_file(void **state)
{
    fixture_t *f = *state;
    snprintf(f->path, sizeof f->path, "%s/nothing", f->dir);
    refused(f->path, HL_ERR_OS, "No such file");
    hl_auth_key_t key;
    errno = 0;
    assert_int_equal(hl_keyfile_load(f->path, &key, NULL), HL_ERR_OS);
    assert_int_equal(errno, ENOENT);
}

static void test_not_a_regular_file(void **state)
{
    fixture_t *f = *state;
    snprintf(f->path, sizeof f->path, "%s/sub", f->dir);
    assert_int_equal(mkdir(f->path, 0700), 0);
    refused(f->path, HL_ERR_RANGE, "directory");
    /* A FIFO with no writer: refused at once, not waited on. */
    snprintf(f->path, sizeof f->path, "%s/fifo", f->dir);
    assert_int_equal(mkfifo(f->path, 0600), 0);
    refused(f->path, HL_ERR_RANGE, "not a regular file");
}

static void test_symlink_refused(void **state)
{
    fixture_t *f = *state;
    write_file(f, "real", good_hex, strlen(good_hex), 0600);
    char real[128];
    snprintf(real, sizeof real, "%s", f->path);
    snprintf(f->path, sizeof f->path, "%s/link", f->dir);
    assert_int_equal(symlink(real, f->path), 0);
    refused(f->path, HL_ERR_OS, "symbolic link");
    hl_auth_key_t key;
    assert_int_equal(hl_keyfile_load(real, &key, NULL), HL_OK);
}

static void test_bad_content(void **state)
{
    fixture_t *f = *state;
    const char *p = write_file(f, "key", "not a key\n", 10, 0600);
    refused(p, HL_ERR_PARSE, "not a hexadecimal digit at byte 1");
    p = write_file(f, "key", good_hex, 40, 0600);
    refused(p, HL_ERR_PARSE, "40 hexadecimal digits");
    p = write_file(f, "key", "", 0, 0600);
    refused(p, HL_ERR_PARSE, "empty");
    char text[80];
    snprintf(text, sizeof text, "%.64s\r\n", good_hex);
    p = write_file(f, "key", text, strlen(text), 0600);
    refused(p, HL_ERR_PARSE, "extra bytes");
}

static void test_too_large(void **state)
{
    fixture_t *f = *state;
    static char big[HL_KEYFILE_MAX_BYTES + 1];
    memset(big, '0', sizeof big);
    const char *p = write_file(f, "key", big, sizeof big, 0600);
    refused(p, HL_ERR_RANGE, "1025 bytes");
    /* Exactly 1 KiB passes the size check and fails on content. */
    p = write_file(f, "key", big, HL_KEYFILE_MAX_BYTES, 0600);
    refused(p, HL_ERR_PARSE, "more than 64");
}

int main(void)
{
    if (!hl_auth_init())
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_good_key, setup, teardown),
        cmocka_unit_test_setup_teardown(test_open_to_group_or_others, setup, teardown),
        cmocka_unit_test_setup_teardown(test_missing_file, setup, teardown),
        cmocka_unit_test_setup_teardown(test_not_a_regular_file, setup, teardown),
        cmocka_unit_test_setup_teardown(test_symlink_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_content, setup, teardown),
        cmocka_unit_test_setup_teardown(test_too_large, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
