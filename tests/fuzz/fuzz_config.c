/*
 * fuzz_config.c - houghlocd's configuration file (src/daemon/config.h, libinih under
 * it): the input is the file, loaded by hl_config_load through a path, as the daemon
 * loads /etc/houghloc/houghlocd.conf.
 *
 * A refusal must come with one line of reason. A file that loads must survive the round
 * trip config.h promises: hl_config_print writes an INI file that hl_config_load reads
 * back, so printing, loading that and printing again gives the same text.
 */
#include <string.h>
#include <unistd.h>

#include "config.h"
#include "fuzz.h"

static bool load_bytes(const void *data, size_t size, hl_config_t *c, char *why)
{
    char path[FUZZ_PATH_MAX];
    int fd = fuzz_memfile(data, size, path);
    FUZZ_CHECK(fd >= 0);
    bool ok = hl_config_load(c, path, false, NULL, 0, why);
    close(fd);
    return ok;
}

static char *print(const hl_config_t *c, size_t *len)
{
    char *text = NULL;
    FILE *f = open_memstream(&text, len);
    FUZZ_CHECK(f != NULL);
    hl_config_print(c, f);
    FUZZ_CHECK(fclose(f) == 0);
    return text;
}

/* Prints the first line where the two printed configurations differ. */
static void first_difference(const char *a, const char *b)
{
    size_t line = 0;
    while (*a && *a == *b) {
        if (*a == '\n')
            line = 0;
        else
            line++;
        a++;
        b++;
    }
    a -= line;
    b -= line;
    fprintf(stderr, "printed:                \"%.*s\"\nprinted after reloading: \"%.*s\"\n",
            (int)strcspn(a, "\n"), a, (int)strcspn(b, "\n"), b);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hl_config_t *c = malloc(sizeof *c), *again = malloc(sizeof *again);
    FUZZ_CHECK(c && again);
    char why[HL_CONFIG_WHY_LEN] = "";
    if (!load_bytes(data, size, c, why)) {
        FUZZ_CHECK(memchr(why, '\0', sizeof why) != NULL);
        FUZZ_CHECK(why[0] != '\0' && strchr(why, '\n') == NULL);
    } else {
        size_t n1 = 0, n2 = 0;
        char *text = print(c, &n1);
        bool reloaded = load_bytes(text, n1, again, why);
        if (!reloaded)
            fprintf(stderr, "the printed configuration does not load: %s\n", why);
        FUZZ_CHECK(reloaded);
        char *text2 = print(again, &n2);
        if (n1 != n2 || memcmp(text, text2, n1) != 0)
            first_difference(text, text2);
        FUZZ_CHECK(n1 == n2 && memcmp(text, text2, n1) == 0);
        free(text2);
        free(text);
    }
    free(again);
    free(c);
    return 0;
}
