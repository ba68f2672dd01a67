/* Tests for what the configuration refuses before and after its keys: files that are not
 * text files of a sane size (config_file.c: /dev/zero, a FIFO, a directory, an oversized
 * file, a NUL byte), the rules over several keys, each message naming its keys with
 * their values (config_check.c), a robot link host that would need a name lookup
 * (link.c), and the key file named by auth.key_file (src/store/keyfile.c).
 *
 * A load that reads /dev/zero or opens a FIFO without the checks never returns: an
 * alarm ends such a test with a failure instead of hanging `make test`. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "config.h"
#include "config_file.h"
#include "config_keys.h"
#include "houghloc/keyfile.h"
#include "link.h"

#define HANG_SECONDS 5

typedef struct fixture {
    char dir[64];
    char path[128];
    hl_config_t c;
    char why[HL_CONFIG_WHY_LEN];
} fixture_t;

static void on_alarm(int sig)
{
    (void)sig;
    static const char msg[] = "test_config_files: a configuration load hung (it read a file "
                              "that never ends, or waited on a FIFO)\n";
    ssize_t r = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)r;
    _exit(1);
}

static int setup(void **state)
{
    fixture_t *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    snprintf(f->dir, sizeof f->dir, "/tmp/hl-config-files-XXXXXX");
    if (!mkdtemp(f->dir))
        return -1;
    *state = f;
    signal(SIGALRM, on_alarm);
    alarm(HANG_SECONDS);
    return 0;
}

static int teardown(void **state)
{
    fixture_t *f = *state;
    alarm(0);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", f->dir);
    int rc = system(cmd);
    free(f);
    return rc == 0 ? 0 : -1;
}

/* Writes @p len bytes of @p text to DIR/@p name. @return its path (f->path). */
static const char *write_file(fixture_t *f, const char *name, const char *text, size_t len)
{
    snprintf(f->path, sizeof f->path, "%s/%s", f->dir, name);
    int fd = open(f->path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, text, len), (ssize_t)len);
    assert_int_equal(close(fd), 0);
    return f->path;
}

/* @p path is refused, in one line that names it and says @p reason. */
static void refused(fixture_t *f, const char *path, bool optional, const char *reason)
{
    assert_false(hl_config_load(&f->c, path, optional, NULL, 0, f->why));
    if (!strstr(f->why, path) || !strstr(f->why, reason))
        fail_msg("message \"%s\" should name %s and say \"%s\"", f->why, path, reason);
    assert_null(strchr(f->why, '\n'));
}

static void loads(fixture_t *f, const char *path, const char *const *sets, int n)
{
    if (!hl_config_load(&f->c, path, false, sets, n, f->why))
        fail_msg("%s", f->why);
}

/* ---- files ------------------------------------------------------------------------- */

static void test_dev_zero_refused(void **state)
{
    fixture_t *f = *state;
    refused(f, "/dev/zero", false, "/dev/zero: not a regular file (a character device)");
    /* the default path's "a missing file is no error" does not let it through either */
    refused(f, "/dev/zero", true, "not a regular file");
}

static void test_fifo_refused_at_once(void **state)
{
    fixture_t *f = *state;
    snprintf(f->path, sizeof f->path, "%s/fifo", f->dir);
    assert_int_equal(mkfifo(f->path, 0600), 0);
    refused(f, f->path, false, ": not a regular file (a FIFO)");
    refused(f, f->path, true, ": not a regular file (a FIFO)");
}

static void test_directory_refused(void **state)
{
    fixture_t *f = *state;
    refused(f, f->dir, false, ": not a regular file (a directory)");
}

/* `--config /dev/null` is the documented "no file": the defaults. */
static void test_dev_null_is_an_empty_file(void **state)
{
    fixture_t *f = *state;
    loads(f, "/dev/null", NULL, 0);
    hl_config_t *d = malloc(sizeof *d);
    assert_non_null(d);
    hl_config_defaults(d);
    assert_memory_equal(&f->c, d, sizeof *d);
    free(d);
}

static void test_missing_file(void **state)
{
    fixture_t *f = *state;
    snprintf(f->path, sizeof f->path, "%s/none.conf", f->dir);
    refused(f, f->path, false, ": cannot open: No such file or directory");
    loads(f, NULL, NULL, 0);
    assert_true(hl_config_load(&f->c, f->path, true, NULL, 0, f->why));
}

/* At most HL_CONFIG_FILE_MAX_BYTES (1 MiB): one byte more is refused with the bound. */
static void test_size_bound(void **state)
{
    fixture_t *f = *state;
    size_t n = HL_CONFIG_FILE_MAX_BYTES + 1;
    char *text = malloc(n);
    assert_non_null(text);
    for (size_t i = 0; i < n; i++)     /* comment lines of 100 bytes */
        text[i] = i % 100 == 99 ? '\n' : ';';
    const char *p = write_file(f, "big.conf", text, n - 1);
    loads(f, p, NULL, 0);
    p = write_file(f, "big.conf", text, n);
    refused(f, p, false, ": larger than 1048576 bytes (1048577 bytes)");
    free(text);
}

/* libinih ends a line at a NUL: a short line was reported as longer than 198 characters,
 * and anything after the NUL was lost. */
static void test_nul_byte_named_by_line(void **state)
{
    fixture_t *f = *state;
    static const char text[] = "[daemon]\nsave_every = 5\0\nlog_level = debug\n";
    const char *p = write_file(f, "nul.conf", text, sizeof text - 1);
    refused(f, p, false, "nul.conf:2: holds a NUL byte");
    static const char first[] = "\0[daemon]\n";
    p = write_file(f, "nul.conf", first, sizeof first - 1);
    refused(f, p, false, "nul.conf:1: holds a NUL byte");
    static const char last[] = "[daemon]\n\n\nsave_every = 5\n\0";
    p = write_file(f, "nul.conf", last, sizeof last - 1);
    refused(f, p, false, "nul.conf:5: holds a NUL byte");
}

/* The text is parsed from memory now: lines are still counted, and a line longer than
 * libinih reads is still named, not misread. */
static void test_lines_counted_from_memory(void **state)
{
    fixture_t *f = *state;
    char text[512];
    int n = snprintf(text, sizeof text, "[daemon]\n;%0198d\nsave_every = 7\n", 0);
    const char *p = write_file(f, "long.conf", text, (size_t)n);
    refused(f, p, false, "long.conf:2: longer than 198 characters");
    n = snprintf(text, sizeof text, "[daemon]\n;%0197d\nsave_every = 7", 0);
    p = write_file(f, "long.conf", text, (size_t)n);   /* 198 and no final newline */
    loads(f, p, NULL, 0);
    assert_int_equal(f->c.save_every, 7);
    p = write_file(f, "bad.conf", "[daemon]\n\nsave_every = x\n", 25);
    refused(f, p, false, "bad.conf:3: key 'daemon.save_every': 'x' is not a number");
}

/* ---- rules over several keys --------------------------------------------------------- */

typedef struct rule_case {
    const char *sets[4];    /* refused */
    const char *ok[4];      /* the same keys just inside the rule: loads */
    const char *why;        /* the whole message */
} rule_case_t;

static const rule_case_t rules[] = {
    { { "drive.max_leg_mm=200", "drive.arrive_mm=300" },
      { "drive.max_leg_mm=300", "drive.arrive_mm=300" },
      "config: drive.max_leg_mm (200) must be at least drive.arrive_mm (300)" },
    { { "drive.slow_mm=350", "drive.stop_mm=350" },
      { "drive.slow_mm=351", "drive.stop_mm=350" },
      "config: drive.slow_mm (350) must be 0 (never slow) or above drive.stop_mm (350)" },
    /* the tracker's rules are the core's (hl_params_check), in the same form */
    { { "localize.blur_sigma_mm=501", "localize.cell_mm=50" },
      { "localize.blur_sigma_mm=500", "localize.cell_mm=50" },
      "config: localize.blur_sigma_mm (501) must be at most 10 x localize.cell_mm (50)" },
    { { "localize.max_cells=1000" },
      { "localize.max_cells=1000", "slam.window_mm=0" },
      "config: slam.window_mm (1000) needs 119952 raster cells of localize.cell_mm (24) "
      "over 17 headings, more than localize.max_cells (1000)" },
    { { "slam.square_walls=true" },
      { "slam.square_walls=true", "slam.close_loops=true" },
      "config: slam.square_walls (true) needs slam.close_loops (false) set to true" },
};

/* Single keys whose range is not one min..max: refused as they are read, by the table. */
static const rule_case_t ranges[] = {
    { { "localize.group_mm=7" }, { "localize.group_mm=8" },
      "--set localize.group_mm=7: 7 is outside 0 or 8..1000" },
    { { "localize.group_mm=1001" }, { "localize.group_mm=0" },
      "--set localize.group_mm=1001: 1001 is outside 0 or 8..1000" },
    { { "echo.half_beam_deg=46" }, { "echo.half_beam_deg=45" },
      "--set echo.half_beam_deg=46: 46 is outside 1..45" },
};

static int count(const char *const *sets)
{
    int n = 0;
    while (n < 4 && sets[n])
        n++;
    return n;
}

/* The keys a message names, "section.key (value)": each must be a key of the table.
 * @return how many. */
static int named_keys(const char *msg)
{
    int n = 0;
    for (const char *s = strstr(msg, " ("); s; s = strstr(s + 2, " (")) {
        const char *start = s;
        while (start > msg && (start[-1] == '_' || start[-1] == '.' ||
                               (start[-1] >= 'a' && start[-1] <= 'z')))
            start--;
        char name[64];
        snprintf(name, sizeof name, "%.*s", (int)(s - start), start);
        if (!strchr(name, '.'))
            continue;   /* "(2 x half beam ...)" */
        if (!hl_config_key_find(name) && !hl_config_core_key(name))
            fail_msg("\"%s\" names %s, which is no key", msg, name);
        n++;
    }
    return n;
}

/* Each rule: refused in exactly its words, naming its keys as "section.key (value)",
 * every one a key of the table; the same keys just inside the rule load. */
static void test_rules_name_their_keys(void **state)
{
    fixture_t *f = *state;
    for (size_t i = 0; i < sizeof rules / sizeof rules[0]; i++) {
        const rule_case_t *r = &rules[i];
        assert_false(hl_config_load(&f->c, NULL, false, r->sets, count(r->sets), f->why));
        if (strcmp(f->why, r->why) != 0)
            fail_msg("rule %zu:\n  said \"%s\"\n  want \"%s\"", i, f->why, r->why);
        /* the first override's key always takes part */
        char first[64];
        snprintf(first, sizeof first, "%.*s (", (int)strcspn(r->sets[0], "="), r->sets[0]);
        if (!strstr(f->why, first))
            fail_msg("rule %zu: \"%s\" does not name %s", i, f->why, first);
        assert_true(named_keys(f->why) >= 1);
        if (!hl_config_load(&f->c, NULL, false, r->ok, count(r->ok), f->why))
            fail_msg("rule %zu: just inside, refused: %s", i, f->why);
    }
}

static void test_ranges_refused_as_read(void **state)
{
    fixture_t *f = *state;
    for (size_t i = 0; i < sizeof ranges / sizeof ranges[0]; i++) {
        const rule_case_t *r = &ranges[i];
        assert_false(hl_config_load(&f->c, NULL, false, r->sets, count(r->sets), f->why));
        assert_string_equal(f->why, r->why);
        if (!hl_config_load(&f->c, NULL, false, r->ok, count(r->ok), f->why))
            fail_msg("range %zu: inside, refused: %s", i, f->why);
    }
}

/* The same from a file: a combination is no one line's, so it names no line. */
static void test_rule_from_a_file(void **state)
{
    fixture_t *f = *state;
    static const char text[] = "[drive]\nmax_leg_mm = 200\narrive_mm = 300\n";
    const char *p = write_file(f, "drive.conf", text, sizeof text - 1);
    assert_false(hl_config_load(&f->c, p, false, NULL, 0, f->why));
    assert_string_equal(f->why, "config: drive.max_leg_mm (200) must be at least "
                                "drive.arrive_mm (300)");
}

/* ---- the robot link's host ------------------------------------------------------------ */

/* A host name would be looked up (blocking) at every reconnection: refused. */
static void test_host_name_refused(void **state)
{
    fixture_t *f = *state;
    const char *sets[1] = { "robot.link=tcp:robot.example:8101" };
    assert_false(hl_config_load(&f->c, NULL, false, sets, 1, f->why));
    assert_string_equal(f->why, "--set robot.link=tcp:robot.example:8101: robot link "
                                "'tcp:robot.example:8101': HOST must be a numeric IPv4/IPv6 "
                                "address (name resolution would block the daemon)");
    static const char text[] = "[robot]\nlink = tcp:robot.example:8101\n";
    const char *p = write_file(f, "link.conf", text, sizeof text - 1);
    refused(f, p, false, "link.conf:2: key 'robot.link': robot link 'tcp:robot.example:8101': "
                         "HOST must be a numeric IPv4/IPv6 address");
}

static void test_numeric_hosts(void **state)
{
    (void)state;
    static const struct { const char *text, *host; } good[] = {
        { "tcp:127.0.0.1:8101", "127.0.0.1" },
        { "tcp:192.0.2.7:1", "192.0.2.7" },
        { "tcp:::1:8101", "::1" },
        { "tcp:[::1]:8101", "::1" },
        { "tcp:[2001:db8::5]:65535", "2001:db8::5" },
        { "tcp:localhost:8101", "127.0.0.1" },  /* the loopback, without a lookup */
    };
    hl_link_spec_t spec;
    char why[HL_LINK_WHY_LEN];
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        if (!hl_link_spec_parse(good[i].text, &spec, why))
            fail_msg("%s: %s", good[i].text, why);
        assert_int_equal(spec.kind, HL_LINK_TCP);
        assert_string_equal(spec.host, good[i].host);
    }
    static const char *const bad[] = { "tcp:robot:8101", "tcp:robot.local:8101",
                                       "tcp:LOCALHOST.:8101", "tcp:[robot]:8101",
                                       "tcp:[]:8101", "tcp::8101" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_false(hl_link_spec_parse(bad[i], &spec, why));
}

/* ---- the key file (auth.key_file) ------------------------------------------------------- */

static void key_refused(const char *path, const char *reason)
{
    hl_auth_key_t key;
    char why[HL_KEYFILE_WHY_LEN] = "";
    assert_int_not_equal(hl_keyfile_load(path, &key, why), HL_OK);
    if (!strstr(why, path) || !strstr(why, reason))
        fail_msg("message \"%s\" should name %s and say \"%s\"", why, path, reason);
}

static void test_key_file_checks(void **state)
{
    fixture_t *f = *state;
    key_refused("/dev/zero", ": not a regular file");
    snprintf(f->path, sizeof f->path, "%s/key.fifo", f->dir);
    assert_int_equal(mkfifo(f->path, 0600), 0);
    key_refused(f->path, ": not a regular file");
    static char big[HL_KEYFILE_MAX_BYTES + 1];
    memset(big, 'a', sizeof big);
    key_refused(write_file(f, "key", big, sizeof big), ": larger than 1024 bytes (1025 bytes)");
}

int main(void)
{
    if (!hl_auth_init())
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_dev_zero_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_fifo_refused_at_once, setup, teardown),
        cmocka_unit_test_setup_teardown(test_directory_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_dev_null_is_an_empty_file, setup, teardown),
        cmocka_unit_test_setup_teardown(test_missing_file, setup, teardown),
        cmocka_unit_test_setup_teardown(test_size_bound, setup, teardown),
        cmocka_unit_test_setup_teardown(test_nul_byte_named_by_line, setup, teardown),
        cmocka_unit_test_setup_teardown(test_lines_counted_from_memory, setup, teardown),
        cmocka_unit_test_setup_teardown(test_rules_name_their_keys, setup, teardown),
        cmocka_unit_test_setup_teardown(test_ranges_refused_as_read, setup, teardown),
        cmocka_unit_test_setup_teardown(test_rule_from_a_file, setup, teardown),
        cmocka_unit_test_setup_teardown(test_host_name_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_numeric_hosts, setup, teardown),
        cmocka_unit_test_setup_teardown(test_key_file_checks, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
