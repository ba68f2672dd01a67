/*
 * map_location.h - where the map file lives when neither --map nor daemon.map_file says.
 *
 * In order: $STATE_DIRECTORY/map.hlmap when that is set (the service: systemd's
 * StateDirectory=houghloc; its first folder when it lists several); else
 * /var/lib/houghloc/map.hlmap when that folder is writable (a system install run by
 * hand); else $XDG_STATE_HOME/houghloc/map.hlmap, $XDG_STATE_HOME defaulting to
 * ~/.local/state (a user's run), the folders created 0700 as the XDG specification asks.
 */
#ifndef HOUGHLOC_DAEMON_MAP_LOCATION_H
#define HOUGHLOC_DAEMON_MAP_LOCATION_H

#include <stdbool.h>
#include <stddef.h>

#define HL_MAP_SYSTEM_DIR "/var/lib/houghloc"
#define HL_MAP_FILE_NAME "map.hlmap"
#define HL_MAP_LOCATION_WHY_LEN 768

/**
 * Picks the default map file.
 * @param create  create the user's folder when it is the one chosen (the daemon); false
 *                for a look that must change nothing (--check-map).
 * @param[out] path   the file (cap bytes).
 * @param[out] from   where it came from, for the log ("$STATE_DIRECTORY", ...).
 * @return true, or false with one line in @p why naming every location tried and why
 *         it failed, and suggesting --map.
 */
bool hl_map_location_default(bool create, char *path, size_t cap, const char **from,
                             char *why);

#endif
