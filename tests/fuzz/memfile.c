/* memfile.c - the fuzz input as an in-memory file, for loaders that take a path
 * (see fuzz.h). */
#define _GNU_SOURCE     /* memfd_create */
#include "fuzz.h"

#include <errno.h>
#include <sys/mman.h>
#include <unistd.h>

int fuzz_memfile(const uint8_t *data, size_t size, char *path)
{
    int fd = memfd_create("hl-fuzz", MFD_CLOEXEC);
    if (fd < 0)
        return -1;
    size_t done = 0;
    while (done < size) {
        ssize_t w = write(fd, data + done, size - done);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            close(fd);
            return -1;
        }
        done += (size_t)w;
    }
    /* A fresh open of /proc/self/fd/N starts at offset 0 with its own file position, as
     * opening a regular file does; the loaders see a regular file of @p size bytes. */
    snprintf(path, FUZZ_PATH_MAX, "/proc/self/fd/%d", fd);
    return fd;
}
