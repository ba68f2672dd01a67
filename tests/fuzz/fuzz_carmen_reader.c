/*
 * fuzz_carmen_reader.c - the CARMEN log reader (tools/carmen/carmen_log.h): the input is
 * a whole log file, plain text or gzip, read line by line through a path as
 * houghloc-import-carmen reads it, each line then parsed.
 *
 * Checked: lines are numbered 1, 2, 3...; an error comes with a reason; the reader frees
 * everything it took (LeakSanitizer). A plain-text file (zlib passes it through) must
 * come back line for line: each line is the file's next line without its "\n" and the
 * "\r"s before it, whatever the line's length against the reader's growing buffer. A
 * line holding a NUL byte is refused, except that the last line, with no newline after
 * it, may come back cut at the NUL (gzgets cannot tell that NUL from the end).
 */
#include <string.h>
#include <unistd.h>

#include "carmen_log.h"
#include "fuzz.h"

/* The file's next line from @p *pos, as the reader should return it: [*start, *len),
 * whether a NUL is in it, and whether a newline ends it. */
typedef struct expect {
    const uint8_t *start;
    size_t len;
    bool has_nul, has_newline;
} expect_t;

static expect_t next_expected(const uint8_t *data, size_t size, size_t *pos)
{
    expect_t e = { data + *pos, 0, false, false };
    const uint8_t *nl = memchr(data + *pos, '\n', size - *pos);
    size_t end = nl ? (size_t)(nl - data) : size;
    e.has_newline = nl != NULL;
    e.len = end - *pos;
    const uint8_t *nul = memchr(e.start, '\0', e.len);
    if (nul) {
        e.has_nul = true;
        e.len = (size_t)(nul - e.start);    /* what a C string of it holds */
    }
    while (e.len > 0 && e.start[e.len - 1] == '\r')
        e.len--;
    *pos = nl ? end + 1 : size;
    return e;
}

static void check_against_file(const expect_t *e, int got, const char *line)
{
    if (e->has_nul && e->has_newline) {
        FUZZ_CHECK(got == -1);
        return;
    }
    if (e->has_nul && got == -1)
        return;
    FUZZ_CHECK(got == 1);
    FUZZ_CHECK(strlen(line) == e->len && memcmp(line, e->start, e->len) == 0);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[FUZZ_PATH_MAX], why[CARMEN_WHY_LEN] = "";
    int fd = fuzz_memfile(data, size, path);
    FUZZ_CHECK(fd >= 0);
    double *ranges = malloc(CARMEN_MAX_BEAMS * sizeof *ranges);
    FUZZ_CHECK(ranges != NULL);
    carmen_reader_t *r = carmen_open(path, why);
    FUZZ_CHECK(r != NULL);
    /* 0x1f starts the gzip magic: leave those to zlib without a model. */
    bool plain = size == 0 || data[0] != 0x1f;
    size_t pos = 0;
    long expect_no = 0;
    for (;;) {
        char *line = NULL;
        long lineno = 0;
        why[0] = '\0';
        int got = carmen_next_line(r, &line, &lineno, why);
        if (plain && got != 0) {
            FUZZ_CHECK(pos < size);
            expect_t e = next_expected(data, size, &pos);
            check_against_file(&e, got, line);
        }
        if (got < 0) {
            FUZZ_CHECK(memchr(why, '\0', sizeof why) != NULL && why[0] != '\0');
            break;
        }
        if (got == 0) {
            FUZZ_CHECK(!plain || pos == size);
            break;
        }
        FUZZ_CHECK(got == 1 && line != NULL && lineno == ++expect_no);
        FUZZ_CHECK(strlen(line) <= CARMEN_MAX_LINE);
        carmen_line_t out;
        memset(&out, 0, sizeof out);
        out.flaser.ranges = ranges;
        char reason[CARMEN_WHY_LEN] = "";
        if (carmen_parse_line(line, &out, reason) != 0)
            FUZZ_CHECK(reason[0] != '\0');
    }
    carmen_close(r);
    free(ranges);
    close(fd);
    return 0;
}
