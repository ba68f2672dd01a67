/* map_location.c - the default map file: the service's state folder, the system's, or
 * the user's (map_location.h). */
#include "map_location.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define FOLDER_MAX 480

static bool writable(const char *dir)
{
    return access(dir, W_OK | X_OK) == 0;
}

/* mkdir -p with mode 0700 for the folders it creates. @return 0 or an errno. */
static int make_folders(const char *dir)
{
    char buf[FOLDER_MAX];
    snprintf(buf, sizeof buf, "%s", dir);
    for (char *s = buf + 1;; s++) {
        if (*s != '/' && *s != '\0')
            continue;
        char end = *s;
        *s = '\0';
        if (mkdir(buf, 0700) != 0 && errno != EEXIST)
            return errno;
        if (end == '\0')
            return 0;
        *s = '/';
    }
}

/* The user's folder: $XDG_STATE_HOME/houghloc, or ~/.local/state/houghloc. The
 * specification ignores a relative $XDG_STATE_HOME. @return false with the reason. */
static bool user_folder(char *out, size_t cap, char *reason, size_t rcap)
{
    const char *xdg = getenv("XDG_STATE_HOME"), *home = getenv("HOME");
    int n;
    if (xdg && xdg[0] == '/')
        n = snprintf(out, cap, "%s/houghloc", xdg);
    else if (home && home[0] == '/')
        n = snprintf(out, cap, "%s/.local/state/houghloc", home);
    else
        return snprintf(reason, rcap, "$XDG_STATE_HOME/houghloc: neither it nor $HOME is "
                        "set to an absolute path"), false;
    if (n < 0 || (size_t)n >= cap)
        return snprintf(reason, rcap, "$XDG_STATE_HOME/houghloc: the path is too long"), false;
    return true;
}

bool hl_map_location_default(bool create, char *path, size_t cap, const char **from,
                             char *why)
{
    char dir[FOLDER_MAX], user_reason[FOLDER_MAX + 64];
    const char *state = getenv("STATE_DIRECTORY");
    if (state && *state) {
        /* systemd lists several folders separated by ':'; ours is the first */
        size_t len = strcspn(state, ":");
        if (len + sizeof "/" HL_MAP_FILE_NAME > cap || len >= sizeof dir)
            return snprintf(why, HL_MAP_LOCATION_WHY_LEN, "$STATE_DIRECTORY is too long for a "
                            "map file path (give --map FILE)"), false;
        snprintf(path, cap, "%.*s/" HL_MAP_FILE_NAME, (int)len, state);
        *from = "$STATE_DIRECTORY";
        return true;    /* the service's own folder: no other location is right for it */
    }
    if (writable(HL_MAP_SYSTEM_DIR)) {
        snprintf(path, cap, HL_MAP_SYSTEM_DIR "/" HL_MAP_FILE_NAME);
        *from = HL_MAP_SYSTEM_DIR " (writable)";
        return true;
    }
    int system_errno = errno;
    if (user_folder(dir, sizeof dir, user_reason, sizeof user_reason)) {
        int err = create ? make_folders(dir) : 0;
        if (create && err == 0 && !writable(dir))
            err = errno;
        if (err == 0 && strlen(dir) + sizeof "/" HL_MAP_FILE_NAME <= cap) {
            snprintf(path, cap, "%s/" HL_MAP_FILE_NAME, dir);
            *from = "the user's state folder ($XDG_STATE_HOME, else ~/.local/state)";
            return true;
        }
        snprintf(user_reason, sizeof user_reason, "%s: %s", dir,
                 err ? strerror(err) : "the path is too long");
    }
    snprintf(why, HL_MAP_LOCATION_WHY_LEN,
             "no folder for the map file: tried " HL_MAP_SYSTEM_DIR " (%s) and %.500s; "
             "give --map FILE", strerror(system_errno), user_reason);
    return false;
}
