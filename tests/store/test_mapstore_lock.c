/* Tests for src/store/mapstore.c's lock (one process per map file: flock on PATH.lock,
 * holding the holder's pid), moving a good map aside to PATH.old-N, and the header a
 * save writes (what the daemon compares to tell a changed map). */
#include "mapstore_fixture.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>

static void lock_name(const fixture_t *f, char *out, size_t cap)
{
    snprintf(out, cap, "%s.lock", f->path);
}

/* The lock file's text ("" when empty). */
static void lock_text(const fixture_t *f, char *out, size_t cap)
{
    char name[256];
    lock_name(f, name, sizeof name);
    size_t n = read_bytes(name, (uint8_t *)out, cap - 1);
    out[n] = '\0';
}

static void test_lock_excludes_and_names_the_holder(void **state)
{
    fixture_t *f = *state;
    char why[HL_MAPSTORE_WHY_LEN], text[64], want[64], name[256];
    pid_t holder = 77;
    int fd = hl_mapstore_lock(f->path, &holder, why);
    assert_true(fd >= 0);
    assert_int_equal(holder, 0);
    assert_string_equal(why, "");
    assert_true(fcntl(fd, F_GETFD) & FD_CLOEXEC);
    snprintf(want, sizeof want, "%ld\n", (long)getpid());
    lock_text(f, text, sizeof text);
    assert_string_equal(text, want);
    assert_int_equal(file_size(f->path), -1);  /* the map itself is not touched */

    /* a second taker (another open file: flock excludes it in this process too) */
    errno = 0;
    assert_int_equal(hl_mapstore_lock(f->path, &holder, why), -1);
    assert_int_equal(errno, EWOULDBLOCK);
    assert_int_equal(holder, getpid());
    assert_reason(why, f->path);
    lock_name(f, name, sizeof name);
    assert_non_null(strstr(why, name));
    snprintf(want, sizeof want, "in use by pid %ld", (long)getpid());
    assert_non_null(strstr(why, want));
    lock_text(f, text, sizeof text);    /* the loser wrote nothing */
    snprintf(want, sizeof want, "%ld\n", (long)getpid());
    assert_string_equal(text, want);

    /* released: the file stays, empty, and locks again */
    hl_mapstore_unlock(fd);
    assert_int_equal(file_size(name), 0);
    fd = hl_mapstore_lock(f->path, &holder, why);
    assert_true(fd >= 0);
    hl_mapstore_unlock(fd);
    hl_mapstore_unlock(-1);     /* accepted */
}

/* A map file is not opened, read or written by the lock. */
static void test_lock_leaves_the_map_alone(void **state)
{
    fixture_t *f = *state;
    char why[HL_MAPSTORE_WHY_LEN];
    hl_mapfile_t m = sample(f->a, 5, 10);
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
    uint8_t before[HDR + 64], after[HDR + 64];
    size_t n = read_bytes(f->path, before, sizeof before);
    struct stat sa, sb;
    assert_int_equal(stat(f->path, &sa), 0);
    int fd = hl_mapstore_lock(f->path, NULL, why);
    assert_true(fd >= 0);
    assert_int_equal(hl_mapstore_lock(f->path, NULL, why), -1);
    hl_mapstore_unlock(fd);
    assert_int_equal(stat(f->path, &sb), 0);
    assert_int_equal(read_bytes(f->path, after, sizeof after), n);
    assert_memory_equal(before, after, n);
    assert_true(sa.st_ino == sb.st_ino && sa.st_mtim.tv_sec == sb.st_mtim.tv_sec &&
                sa.st_mtim.tv_nsec == sb.st_mtim.tv_nsec);
}

/* A holder killed with SIGKILL leaves its pid in the file but no lock: the next taker
 * gets it at once and writes its own pid. */
static void test_lock_after_kill_9(void **state)
{
    fixture_t *f = *state;
    char why[HL_MAPSTORE_WHY_LEN], text[64], want[64];
    int ready[2];
    assert_int_equal(pipe(ready), 0);
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        int fd = hl_mapstore_lock(f->path, NULL, NULL);
        char c = fd >= 0 ? 'y' : 'n';
        if (write(ready[1], &c, 1) != 1)
            _exit(2);
        for (;;)
            pause();
    }
    char c = 0;
    assert_int_equal(read(ready[0], &c, 1), 1);
    assert_int_equal(c, 'y');
    pid_t holder = 0;
    assert_int_equal(hl_mapstore_lock(f->path, &holder, why), -1);
    assert_int_equal(holder, child);
    kill(child, SIGKILL);
    int status;
    assert_int_equal(waitpid(child, &status, 0), child);
    snprintf(want, sizeof want, "%ld\n", (long)child);
    lock_text(f, text, sizeof text);
    assert_string_equal(text, want);    /* the dead holder's pid is still there */
    int fd = hl_mapstore_lock(f->path, &holder, why);
    assert_true(fd >= 0);
    assert_int_equal(holder, 0);
    snprintf(want, sizeof want, "%ld\n", (long)getpid());
    lock_text(f, text, sizeof text);
    assert_string_equal(text, want);
    hl_mapstore_unlock(fd);
    close(ready[0]);
    close(ready[1]);
}

/* A holder that wrote no pid (or not yet): refused all the same, the pid unknown. */
static void test_lock_held_without_a_pid(void **state)
{
    fixture_t *f = *state;
    char why[HL_MAPSTORE_WHY_LEN], name[256];
    lock_name(f, name, sizeof name);
    int other = open(name, O_RDWR | O_CREAT, 0644);
    assert_true(other >= 0);
    assert_int_equal(flock(other, LOCK_EX | LOCK_NB), 0);
    pid_t holder = 77;
    errno = 0;
    assert_int_equal(hl_mapstore_lock(f->path, &holder, why), -1);
    assert_int_equal(errno, EWOULDBLOCK);
    assert_int_equal(holder, 0);
    assert_non_null(strstr(why, "in use by another process"));
    /* nor is a pid that names no process (a dead child's) reported */
    pid_t dead = fork();
    assert_true(dead >= 0);
    if (dead == 0)
        _exit(0);
    assert_int_equal(waitpid(dead, NULL, 0), dead);
    char text[24];
    int n = snprintf(text, sizeof text, "%ld\n", (long)dead);
    assert_int_equal(pwrite(other, text, (size_t)n, 0), n);
    holder = 77;
    assert_int_equal(hl_mapstore_lock(f->path, &holder, why), -1);
    assert_int_equal(holder, 0);
    close(other);
    int fd = hl_mapstore_lock(f->path, &holder, why);
    assert_true(fd >= 0);
    hl_mapstore_unlock(fd);
}

/* Another user's lock file (one this process may not write) is locked read-only. */
static void test_lock_read_only_file(void **state)
{
    fixture_t *f = *state;
    char why[HL_MAPSTORE_WHY_LEN], name[256];
    if (geteuid() == 0)
        skip();     /* root writes any file */
    lock_name(f, name, sizeof name);
    write_bytes(name, (const uint8_t *)"1\n", 2);
    assert_int_equal(chmod(name, 0444), 0);
    int fd = hl_mapstore_lock(f->path, NULL, why);
    assert_true(fd >= 0);
    assert_int_equal(hl_mapstore_lock(f->path, NULL, why), -1);
    hl_mapstore_unlock(fd);
    assert_int_equal(file_size(name), 2);   /* left as it was */
}

/* What is not a lock file is refused, not followed or created through. */
static void test_lock_refuses_odd_files(void **state)
{
    fixture_t *f = *state;
    char why[HL_MAPSTORE_WHY_LEN], name[256], target[256];
    lock_name(f, name, sizeof name);
    snprintf(target, sizeof target, "%s/elsewhere", f->dir);
    assert_int_equal(symlink(target, name), 0);
    assert_int_equal(hl_mapstore_lock(f->path, NULL, why), -1);
    assert_reason(why, f->path);
    assert_int_equal(file_size(target), -1);    /* nothing created through the link */
    assert_int_equal(unlink(name), 0);
    assert_int_equal(mkfifo(name, 0600), 0);
    assert_int_equal(hl_mapstore_lock(f->path, NULL, why), -1);
    assert_non_null(strstr(why, "not a regular file"));
    assert_int_equal(unlink(name), 0);
    char missing[256];
    snprintf(missing, sizeof missing, "%s/no/such/map.hlmap", f->dir);
    errno = 0;
    assert_int_equal(hl_mapstore_lock(missing, NULL, why), -1);
    assert_int_equal(errno, ENOENT);
    assert_reason(why, missing);
    assert_int_equal(hl_mapstore_lock(NULL, NULL, why), -1);
}

/* A good map set aside: PATH.old-N, the first free N, byte for byte the old file. */
static void test_move_aside_as_old(void **state)
{
    fixture_t *f = *state;
    char why[HL_MAPSTORE_WHY_LEN], to[256], want[256];
    hl_mapfile_t m = sample(f->a, 40, 100), got;
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
    uint8_t before[HDR + 40 * 12 + 4], after[sizeof before];
    assert_int_equal(read_bytes(f->path, before, sizeof before), sizeof before);
    snprintf(want, sizeof want, "%s.old-1", f->path);
    write_bytes(want, (const uint8_t *)"taken", 5);     /* .old-1 is someone else's */
    assert_int_equal(hl_mapstore_move_aside_as(f->path, "old", to, sizeof to, why), HL_OK);
    snprintf(want, sizeof want, "%s.old-2", f->path);
    assert_string_equal(to, want);
    assert_int_equal(file_size(f->path), -1);
    assert_int_equal(read_bytes(want, after, sizeof after), sizeof after);
    assert_memory_equal(before, after, sizeof before);
    snprintf(want, sizeof want, "%s.old-1", f->path);
    assert_int_equal(file_size(want), 5);
    /* the set-aside file is still a map that loads */
    got = (hl_mapfile_t){ .vectors = f->b, .max_vectors = BIG };
    assert_int_equal(hl_mapstore_load(to, &got, why), HL_OK);
    assert_same(&m, &got);
    /* bad suffixes */
    assert_int_equal(hl_mapstore_move_aside_as(f->path, "", to, sizeof to, why), HL_ERR_ARG);
    assert_int_equal(hl_mapstore_move_aside_as(f->path, "a/b", to, sizeof to, why), HL_ERR_ARG);
    assert_int_equal(hl_mapstore_move_aside_as(f->path, NULL, to, sizeof to, why), HL_ERR_ARG);
    assert_string_equal(to, "");
}

/* The header is the file's first 97 bytes, and moves with every field the file holds. */
static void test_header(void **state)
{
    fixture_t *f = *state;
    char why[HL_MAPSTORE_WHY_LEN];
    hl_mapfile_t m = sample(f->a, 3, 10);
    assert_int_equal(hl_mapstore_save(f->path, &m, why), HL_OK);
    uint8_t file[HDR], h[HL_MAPSTORE_HEADER_BYTES], g[HL_MAPSTORE_HEADER_BYTES];
    assert_int_equal(HL_MAPSTORE_HEADER_BYTES, HDR);
    assert_int_equal(read_bytes(f->path, file, sizeof file), HDR);
    hl_mapstore_header(&m, h);
    assert_memory_equal(h, file, HDR);
    /* the vectors are not in it */
    hl_mapfile_t v = m;
    v.vectors = f->b;
    hl_mapstore_header(&v, g);
    assert_memory_equal(g, h, HDR);
    /* each field is */
    for (int k = 0; k < 16; k++) {
        hl_mapfile_t c = m;
        switch (k) {
        case 0: c.capacity++; break;
        case 1: c.count--; break;
        case 2: c.state.map_version++; break;
        case 3: c.state.started = !c.state.started; break;
        case 4: c.state.pose.x_mm++; break;
        case 5: c.state.pose.theta++; break;
        case 6: c.state.odom.y_mm--; break;
        case 7: c.state.odom.theta--; break;
        case 8: c.state.peak_avg++; break;
        case 9: c.state.cull_rng.state++; break;
        case 10: c.state.cull_rng.inc += 2; break;
        case 11: c.last_request_seq++; break;
        case 12: c.last_scan_utime++; break;
        case 13: c.scans++; break;
        case 14: c.state.map_version += UINT64_C(1) << 32; break;  /* its high half */
        default: c.state.pose.y_mm++; break;
        }
        hl_mapstore_header(&c, g);
        assert_memory_not_equal(g, h, HDR);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_lock_excludes_and_names_the_holder, setup, teardown),
        cmocka_unit_test_setup_teardown(test_lock_leaves_the_map_alone, setup, teardown),
        cmocka_unit_test_setup_teardown(test_lock_after_kill_9, setup, teardown),
        cmocka_unit_test_setup_teardown(test_lock_held_without_a_pid, setup, teardown),
        cmocka_unit_test_setup_teardown(test_lock_read_only_file, setup, teardown),
        cmocka_unit_test_setup_teardown(test_lock_refuses_odd_files, setup, teardown),
        cmocka_unit_test_setup_teardown(test_move_aside_as_old, setup, teardown),
        cmocka_unit_test_setup_teardown(test_header, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
