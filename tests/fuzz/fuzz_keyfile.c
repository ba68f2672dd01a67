/*
 * fuzz_keyfile.c - the request-signing key file (include/store/houghloc/keyfile.h, the
 * key's text parsed by the bus's auth.c): the input is the file, as auth.key_file,
 * houghloc-goto --key or the console name it.
 *
 * The loader opens with O_NOFOLLOW and refuses a file open to group or others, so the
 * memfd of fuzz_memfile (a /proc/self/fd link, mode 0777) would be refused before its
 * text is read: the input goes into a real file, mode 0600, in a fresh folder under
 * /dev/shm (or $TMPDIR), removed again.
 *
 * Checked against keyfile.h: a file loads exactly when it is 64 hexadecimal digits and
 * at most one newline after them, not all zeros, and the key is then those digits; a
 * refusal is HL_ERR_RANGE for a file over HL_KEYFILE_MAX_BYTES, else HL_ERR_PARSE, with
 * one line naming the file, and leaves the caller's key alone.
 */
#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fuzz.h"
#include "houghloc/keyfile.h"

static int hex_value(uint8_t ch)
{
    if (ch >= '0' && ch <= '9')
        return ch - '0';
    if (ch >= 'a' && ch <= 'f')
        return ch - 'a' + 10;
    if (ch >= 'A' && ch <= 'F')
        return ch - 'A' + 10;
    return -1;
}

/* What keyfile.h says the file holds, decoded here on its own. @return whether it is a
 * key. */
static bool expected_key(const uint8_t *data, size_t size, hl_auth_key_t *key)
{
    const size_t digits = 2 * HL_AUTH_KEY_BYTES;
    if (size != digits && !(size == digits + 1 && data[digits] == '\n'))
        return false;
    bool zero = true;
    for (size_t i = 0; i < HL_AUTH_KEY_BYTES; i++) {
        int hi = hex_value(data[2 * i]), lo = hex_value(data[2 * i + 1]);
        if (hi < 0 || lo < 0)
            return false;
        key->bytes[i] = (uint8_t)(hi << 4 | lo);
        zero = zero && key->bytes[i] == 0;
    }
    return !zero;   /* an all-zero key is a template's placeholder: refused */
}

/* Writes the input to DIR/key, mode 0600. */
static void write_key(const char *path, const uint8_t *data, size_t size)
{
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    FUZZ_CHECK(fd >= 0);
    size_t done = 0;
    while (done < size) {
        ssize_t w = write(fd, data + done, size - done);
        FUZZ_CHECK(w > 0);
        done += (size_t)w;
    }
    FUZZ_CHECK(fchmod(fd, 0600) == 0);     /* whatever the umask */
    FUZZ_CHECK(close(fd) == 0);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FUZZ_CHECK(hl_auth_init());
    const char *base = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : getenv("TMPDIR");
    char dir[PATH_MAX], path[PATH_MAX + 8], why[HL_KEYFILE_WHY_LEN] = "";
    snprintf(dir, sizeof dir, "%s/hl-fuzz-key-XXXXXX", base ? base : "/tmp");
    FUZZ_CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/key", dir);
    write_key(path, data, size);

    hl_auth_key_t key, want;
    memset(&key, 0x5a, sizeof key);
    hl_status_t st = hl_keyfile_load(path, &key, why);
    unlink(path);
    rmdir(dir);

    FUZZ_CHECK(memchr(why, '\0', sizeof why) != NULL && strchr(why, '\n') == NULL);
    if (expected_key(data, size, &want)) {
        if (st != HL_OK)
            fprintf(stderr, "a key was refused: %s\n", why);
        FUZZ_CHECK(st == HL_OK);
        FUZZ_CHECK(memcmp(key.bytes, want.bytes, sizeof key.bytes) == 0);
        return 0;
    }
    FUZZ_CHECK(st == (size > HL_KEYFILE_MAX_BYTES ? HL_ERR_RANGE : HL_ERR_PARSE));
    FUZZ_CHECK(why[0] != '\0' && strstr(why, path) != NULL);
    for (size_t i = 0; i < sizeof key.bytes; i++)
        FUZZ_CHECK(key.bytes[i] == 0x5a);
    return 0;
}
