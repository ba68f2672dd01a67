/*
 * replay_main.c - runs a fuzz target's LLVMFuzzerTestOneInput over files, without
 * libFuzzer: how `make test` replays the committed corpus and regression inputs as an
 * ordinary test (built with gcc under AddressSanitizer and UBSan, tests/fuzz/fuzz.mk).
 *
 *   replay_NAME                 the compiled-in folders: HL_FUZZ_CORPUS, HL_FUZZ_REGRESS
 *                               (paths relative to the repository root, where
 *                               tests/run-unit.sh runs)
 *   replay_NAME PATH...         these files and folders instead (one crash input, say)
 *
 * Each file is read into a heap block of exactly its size, so that a read past the input
 * is caught. Names starting with '.' and README files in a folder are not inputs. A
 * failing input aborts (a sanitizer report or a FUZZ_CHECK), and its name is printed
 * after the report (AddressSanitizer's death callback, the SIGABRT handler for UBSan and
 * FUZZ_CHECK); a folder that cannot be read fails the run.
 */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fuzz.h"

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/common_interface_defs.h>
#endif

#ifndef HL_FUZZ_NAME
#error "compile with -DHL_FUZZ_NAME='\"name\"' -DHL_FUZZ_CORPUS=... -DHL_FUZZ_REGRESS=..."
#endif

/* The input being run, for the failure message (set before each run). */
static char current[4096];

/* Async-signal-safe: only write(2). */
static void say_current(void)
{
    static const char head[] = "replay " HL_FUZZ_NAME ": failing input: ";
    ssize_t r = write(STDERR_FILENO, head, sizeof head - 1);
    r = write(STDERR_FILENO, current, strlen(current));
    r = write(STDERR_FILENO, "\n", 1);
    (void)r;
}

/* UBSan's runtime does not call the death callback that AddressSanitizer's takes: make
 * it abort instead of exiting, so that the SIGABRT handler names the input. */
const char *__ubsan_default_options(void);
const char *__ubsan_default_options(void)
{
    return "abort_on_error=1";
}

static void on_abort(int sig)
{
    say_current();
    signal(sig, SIG_DFL);
    raise(sig);
}

/* Runs one file. @return 0, or -1 when it cannot be read. */
static int replay_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "replay %s: %s: %s\n", HL_FUZZ_NAME, path, strerror(errno));
        return -1;
    }
    size_t cap = 4096, n = 0;
    unsigned char *buf = malloc(cap);
    size_t got;
    while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            unsigned char *bigger = realloc(buf, cap * 2);
            if (!bigger) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = bigger;
            cap *= 2;
        }
    }
    bool bad = !buf || ferror(f);
    fclose(f);
    /* exactly n bytes (at least one, so the pointer is never NULL) */
    uint8_t *input = bad ? NULL : malloc(n > 0 ? n : 1);
    if (!input) {
        fprintf(stderr, "replay %s: %s: cannot read\n", HL_FUZZ_NAME, path);
        free(buf);
        return -1;
    }
    memcpy(input, buf, n);
    free(buf);
    snprintf(current, sizeof current, "%s", path);
    LLVMFuzzerTestOneInput(input, n);
    free(input);
    return 0;
}

static int by_name(const struct dirent **a, const struct dirent **b)
{
    return strcmp((*a)->d_name, (*b)->d_name);
}

static int no_dots(const struct dirent *e)
{
    return e->d_name[0] != '.' && strncmp(e->d_name, "README", 6) != 0;
}

/* Runs a file, or every file of a folder in name order. @return inputs run, or -1. */
static long replay_path(const char *path)
{
    struct stat sb;
    if (stat(path, &sb) != 0) {
        fprintf(stderr, "replay %s: %s: %s\n", HL_FUZZ_NAME, path, strerror(errno));
        return -1;
    }
    if (!S_ISDIR(sb.st_mode))
        return replay_file(path) == 0 ? 1 : -1;
    struct dirent **names = NULL;
    int k = scandir(path, &names, no_dots, by_name);
    if (k < 0) {
        fprintf(stderr, "replay %s: %s: %s\n", HL_FUZZ_NAME, path, strerror(errno));
        return -1;
    }
    long count = 0;
    for (int i = 0; i < k; i++) {
        char file[4096];
        snprintf(file, sizeof file, "%s/%s", path, names[i]->d_name);
        if (count >= 0) {
            long r = replay_path(file);
            count = r < 0 ? -1 : count + r;
        }
        free(names[i]);
    }
    free(names);
    return count;
}

int main(int argc, char **argv)
{
    static const char *const builtin[] = { HL_FUZZ_CORPUS, HL_FUZZ_REGRESS };
    const char *const *paths = argc > 1 ? (const char *const *)argv + 1 : builtin;
    int n = argc > 1 ? argc - 1 : 2;
    signal(SIGABRT, on_abort);
#if defined(__SANITIZE_ADDRESS__)
    __sanitizer_set_death_callback(say_current);
#endif
    char counts[1024] = "";
    size_t used = 0;
    long total = 0;
    for (int i = 0; i < n; i++) {
        long r = replay_path(paths[i]);
        if (r < 0)
            return 1;
        if (used < sizeof counts)
            used += (size_t)snprintf(counts + used, sizeof counts - used, "%s%s: %ld",
                                     i ? ", " : "", paths[i], r);
        total += r;
    }
    printf("replay %s: %ld inputs (%s), no failure\n", HL_FUZZ_NAME, total, counts);
    return 0;
}
