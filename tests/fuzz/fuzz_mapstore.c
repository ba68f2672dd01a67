/*
 * fuzz_mapstore.c - the map file loader (include/store/houghloc/mapstore.h): the input is a map
 * file as found on disk after a crash, a bad disk or a hostile hand.
 *
 * It is loaded twice: as it is, and with its last four bytes replaced by the right
 * CRC-32 of the rest, so that the range checks behind the checksum are reached too. The
 * caller's storage is a heap block of exactly max_vectors vectors (AddressSanitizer sees
 * a write past it). Checked: a refusal has a status mapstore.h lists and a one-line
 * reason; a file that loads holds what mapstore.h promises, and saving it again writes
 * the same bytes (the header is read field by field, so every bit must come back); a
 * file of format version 1 is saved in version 2, which loads back to the same header
 * and vectors.
 */
#include <errno.h>
#include <limits.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "fuzz.h"
#include "houghloc/mapstore.h"

/* The file at @p path, loaded again: the same header (as version 2 writes it) and
 * vectors as @p m. */
static void check_reload(const char *path, const hl_mapfile_t *m)
{
    char why[HL_MAPSTORE_WHY_LEN];
    hl_mapfile_t r = { .vectors = malloc(m->count ? m->count * sizeof(hl_vector_t) : 1),
                       .max_vectors = m->count };
    FUZZ_CHECK(r.vectors != NULL);
    FUZZ_CHECK(hl_mapstore_load(path, &r, why) == HL_OK && r.format == HL_MAPSTORE_VERSION);
    uint8_t a[HL_MAPSTORE_HEADER_BYTES], b[HL_MAPSTORE_HEADER_BYTES];
    hl_mapstore_header(m, a);
    hl_mapstore_header(&r, b);
    FUZZ_CHECK(memcmp(a, b, sizeof a) == 0);
    FUZZ_CHECK(memcmp(r.vectors, m->vectors, m->count * sizeof(hl_vector_t)) == 0);
    free(r.vectors);
}

/* Saves @p m into a fresh folder under /dev/shm (or $TMPDIR) and compares the file with
 * @p data (a version 1 file: loads it back, check_reload); the folder is removed again. */
static void check_save(const hl_mapfile_t *m, const uint8_t *data, size_t size)
{
    const char *base = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : getenv("TMPDIR");
    char dir[PATH_MAX], path[PATH_MAX + 16], why[HL_MAPSTORE_WHY_LEN];
    snprintf(dir, sizeof dir, "%s/hl-fuzz-map-XXXXXX", base ? base : "/tmp");
    FUZZ_CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/map.hlmap", dir);
    FUZZ_CHECK(hl_mapstore_save(path, m, why) == HL_OK);
    if (m->format == 1) {
        check_reload(path, m);
    } else {
        FILE *f = fopen(path, "rb");
        FUZZ_CHECK(f != NULL);
        uint8_t *back = malloc(size + 1);
        FUZZ_CHECK(back != NULL);
        size_t got = fread(back, 1, size + 1, f);
        fclose(f);
        FUZZ_CHECK(got == size && memcmp(back, data, size) == 0);
        free(back);
    }
    unlink(path);
    rmdir(dir);
}

static void load(const uint8_t *data, size_t size)
{
    char path[FUZZ_PATH_MAX], why[HL_MAPSTORE_WHY_LEN] = "";
    int fd = fuzz_memfile(data, size, path);
    FUZZ_CHECK(fd >= 0);
    /* A map of n vectors takes 101 + 12 n bytes (97 + 12 n in version 1): size / 12
     * always suffice. */
    uint32_t max = (uint32_t)(size / 12u);
    hl_mapfile_t m = { .vectors = malloc(max > 0 ? max * sizeof(hl_vector_t) : 1),
                       .max_vectors = max };
    FUZZ_CHECK(m.vectors != NULL);
    hl_vector_t *storage = m.vectors;
    hl_status_t st = hl_mapstore_load(path, &m, why);
    close(fd);
    FUZZ_CHECK(memchr(why, '\0', sizeof why) != NULL && strchr(why, '\n') == NULL);
    if (st != HL_OK) {
        FUZZ_CHECK(st == HL_ERR_PARSE || st == HL_ERR_RANGE || st == HL_ERR_CAPACITY);
        FUZZ_CHECK(why[0] != '\0');
    } else {
        FUZZ_CHECK(m.vectors == storage && m.max_vectors == max);
        FUZZ_CHECK(m.capacity >= 1 && m.capacity <= HL_MAP_MAX_CAPACITY);
        FUZZ_CHECK(m.count <= m.capacity && m.count <= max);
        FUZZ_CHECK(m.format == 1 || m.format == HL_MAPSTORE_VERSION);
        FUZZ_CHECK(size == (m.format == 1 ? HL_MAPSTORE_V1_HEADER_BYTES
                                          : HL_MAPSTORE_HEADER_BYTES) +
                               12u * (size_t)m.count + 4u);
        FUZZ_CHECK(m.state.map_version <= (uint64_t)HL_COUNT_MAX);
        FUZZ_CHECK(hl_pose_in_range(m.state.pose) && hl_pose_in_range(m.state.odom));
        for (uint32_t i = 0; i < m.count; i++)
            FUZZ_CHECK(hl_vector_in_range(&m.vectors[i]));
        check_save(&m, data, size);
    }
    free(storage);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    load(data, size);
    if (size < 4)
        return 0;
    uint8_t *fixed = malloc(size);
    FUZZ_CHECK(fixed != NULL);
    memcpy(fixed, data, size);
    uint32_t crc = (uint32_t)crc32(crc32(0L, Z_NULL, 0), fixed, (uInt)(size - 4));
    for (int i = 0; i < 4; i++)
        fixed[size - 4 + (size_t)i] = (uint8_t)(crc >> (8 * i));
    if (memcmp(fixed, data, size) != 0)
        load(fixed, size);
    free(fixed);
    return 0;
}
