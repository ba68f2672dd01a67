/*
 * fuzz.h - shared by the fuzz targets (tests/fuzz/fuzz_*.c): a check that fails loudly,
 * the input as a file that a path-based loader can open, and cut points for streams.
 *
 * Each target defines LLVMFuzzerTestOneInput. Built with clang -fsanitize=fuzzer (make
 * fuzz) libFuzzer calls it; built with gcc and replay_main.c (make test) it replays the
 * committed corpus and regression inputs. A target keeps no state between two calls:
 * everything it allocates or opens it releases before it returns.
 */
#ifndef HOUGHLOC_TESTS_FUZZ_H
#define HOUGHLOC_TESTS_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#ifdef __cplusplus
extern "C" {
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A property the code under test promises (its header says so) and broke: report where,
 * then abort, which both libFuzzer and the replay count as a crash. Never used for
 * anything the header leaves open, so that a crash is always a real bug. */
#define FUZZ_CHECK(cond)                                                                  \
    do {                                                                                  \
        if (!(cond)) {                                                                    \
            fprintf(stderr, "%s:%d: fuzz check failed: %s\n", __FILE__, __LINE__, #cond); \
            abort();                                                                      \
        }                                                                                 \
    } while (0)

/* Room for "/proc/self/fd/N". */
#define FUZZ_PATH_MAX 64

/**
 * Puts @p size bytes into an anonymous in-memory file (memfd: nothing on disk, nothing
 * left behind by a crash) and writes a path that opens it afresh into @p path.
 * @return the fd, which the caller closes; -1 when the kernel refuses (not expected).
 */
int fuzz_memfile(const uint8_t *data, size_t size, char *path);

/** A 64-bit seed from the input itself (FNV-1a), so that cut points replay exactly. */
static inline uint64_t fuzz_seed(const uint8_t *data, size_t size)
{
    uint64_t h = 0xcbf29ce484222325u;
    for (size_t i = 0; i < size; i++)
        h = (h ^ data[i]) * 0x100000001b3u;
    return h | 1u;
}

/** The next cut from @p state (xorshift64*): a chunk of 0 .. @p left bytes, mostly short,
 *  sometimes empty, sometimes long, as reads from a serial port or a socket come. */
static inline size_t fuzz_cut(uint64_t *state, size_t left)
{
    uint64_t x = *state;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    *state = x;
    uint64_t r = x * 0x2545f4914f6cdd1du;
    size_t n;
    switch (r & 7u) {
    case 0: n = 0; break;
    case 1: case 2: n = 1; break;
    case 3: case 4: n = (size_t)(r >> 8) % 16u + 1u; break;
    default: n = (size_t)(r >> 8) % 300u + 1u; break;
    }
    return n < left ? n : left;
}

#ifdef __cplusplus
}
#endif
#endif
