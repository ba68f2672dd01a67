/* maplock.c - houghlocd's hold on its map file: the lock and the save rule (maplock.h).
 *
 * Process-wide state, as the lock itself is: main.c takes the lock and notes the loaded
 * state, loop.c's hl_loop_save asks whether a save would change the file.
 */
#include "maplock.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

static int lock_fd = -1;
static bool have_saved;
static hl_mapfile_t saved;      /* the state the file holds; vectors not kept (NULL) */

bool hl_maplock_take(const char *path, char *why, size_t cap)
{
    char reason[HL_MAPSTORE_WHY_LEN];
    pid_t holder = 0;
    int fd = hl_mapstore_lock(path, &holder, reason);
    if (fd >= 0) {
        if (lock_fd >= 0)
            hl_mapstore_unlock(lock_fd);
        lock_fd = fd;
        return true;
    }
    if (errno != EWOULDBLOCK)
        snprintf(why, cap, "%s", reason);
    else if (holder > 0)
        snprintf(why, cap, "map %s is in use by houghlocd pid %ld (lock %s" HL_MAPSTORE_LOCK_SUFFIX
                 ")", path, (long)holder, path);
    else    /* the holder has not written its pid yet, or could not */
        snprintf(why, cap, "map %s is in use by another houghlocd (lock %s"
                 HL_MAPSTORE_LOCK_SUFFIX ", which names no pid)", path, path);
    for (char *p = why; *p; p++)    /* one line, whatever the path holds */
        if ((unsigned char)*p < 0x20 || *p == 0x7f)
            *p = '?';
    return false;
}

void hl_maplock_release(void)
{
    hl_mapstore_unlock(lock_fd);
    lock_fd = -1;
    have_saved = false;
}

void hl_maplock_saved(const hl_mapfile_t *m)
{
    saved = *m;
    saved.vectors = NULL;
    have_saved = true;
}

/*
 * The test compares the headers a save would write, the old state's and the new one's.
 * The header holds every field of the file but the vectors, and the vectors need no copy
 * or comparison: the map version, in the header, increments on every change to them
 * (hl_map_version), so an equal header means an equal file. It costs two 97-byte
 * encodings and a memcmp, however large the map.
 *
 * Every header field counts, the ones a scan or a request changes without changing the
 * map too, because each is something a restarted daemon needs:
 *  - the pose and its odometry reference: where a restarted daemon puts the robot (an
 *    odometry-only or rejected scan moves them, SET_POSE sets them, the map unchanged);
 *  - the scans, last scan time, peak average, culling generator and started flag: a
 *    restored daemon takes exactly the steps of the one that saved
 *    (test_restore_continues_identically), and each scan moves some of them;
 *  - the last request seq: the replay guard; a request accepted but never saved could
 *    be replayed, signed, to a restarted daemon. Only a SAVE request's own seq is left
 *    out (ignore_request_seq): a replay of it would only save again, and without that a
 *    SAVE could never find the map unchanged. It is written with the next save.
 *  - the capacity and count, which the vectors' change also moves.
 */
bool hl_maplock_changed(const hl_mapfile_t *m, bool ignore_request_seq)
{
    if (!have_saved)
        return true;
    hl_mapfile_t now = *m;
    if (ignore_request_seq)
        now.last_request_seq = saved.last_request_seq;
    uint8_t a[HL_MAPSTORE_HEADER_BYTES], b[HL_MAPSTORE_HEADER_BYTES];
    hl_mapstore_header(&saved, a);
    hl_mapstore_header(&now, b);
    return memcmp(a, b, sizeof a) != 0;
}
