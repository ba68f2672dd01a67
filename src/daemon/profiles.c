/* profiles.c - the sensor profiles' keys (profiles.h), their fragment, and the advice
 * for a map file larger than the configured map. */
#include "profiles.h"

#include <stdlib.h>
#include <string.h>

/* Loop closure for a sensor that scans several times a second, should it be turned on
 * (slam.close_loops): keyframes, and its work a share a scan (docs/design/loop-closure.md). */
#define CONTINUOUS_CLOSURE_KEYS \
    { "slam.keyframe_mm", "500", \
      "with loop closure: a stop of its own every 0.5 m (or 20 degrees) of a continuous " \
      "drive, the scans between joining it, rather than a stop a scan" }, \
    { "slam.keyframe_deg", "20", "... or 20 degrees" }, \
    { "slam.closure_match_weight", "0.1", \
      "... a match counting a tenth of a step: keyframes joined by many scans' tracking " \
      "are surer than a match against a few stops" }, \
    { "slam.closure_matches_per_scan", "4", \
      "... and a stop's matches sought 4 a scan in the scans after it, its fit in the next" }, \
    { "slam.closure_redraw_readings", "50000", \
      "... and after a fit the map (a whole building's stops) drawn again aside, 50,000 " \
      "readings a scan (a few milliseconds), so that no scan waits for all of it" },

/* The LOST state off for a sensor that scans several times a second: lost, every scan
 * searches the whole map, 50-250 ms against a scan period of 100-250 ms, and the daemon
 * falls behind the sensor (the Flood trial's pseudo-sonar at 20x with the search on every
 * scan: 894 of 1,200 scans published, compute median 17 ms against 11 ms a scan); and the search's settings that answer wrong
 * on 1 % or fewer of a building's trials were measured on maps made for the search
 * (tools/lab/kidnap/laser-search.conf, sonar-search.conf), not on the tracking maps these
 * profiles make.
 * RELOCALIZE still searches on demand. */
#define LOST_OFF_KEYS \
    { "daemon.search_every", "0", \
      "no global search besides tracking (lost, every scan would search: more than a scan " \
      "period)" }, \
    { "daemon.lost_after", "0", "... and no LOST state on doubtful scans" },

/* A sonar sounded at the laser's rate rather than at stops: the settings measured on the
 * pseudo-sonar ring of five real buildings (docs/results/real-buildings.md, "Pseudo-sonar"). */
static const hl_profile_key_t sonar_continuous[] = {
    { "slam.heading_gain", "0.3",
      "soundings a few centimetres apart: odometry's heading between two is better than one "
      "sounding's against the map, so take 30 % of each heading correction" },
    { "localize.prior_sigma_mm", "100", "... and a tighter odometry prior in position" },
    { "localize.prior_sigma_deg", "5", "... and in heading" },
    { "echo.half_beam_deg", "11",
      "the nearest return anywhere in a hard 22-degree cone (half of it), not the 7 degrees "
      "of a Polaroid-type beam" },
    CONTINUOUS_CLOSURE_KEYS
    { "slam.closure_match_readings", "256",
      "... a keyframe matched with 256 of its readings (up to 1,024 joined), which keeps a "
      "scan's matches within 50 ms" },
    { "slam.closure_redraw_mm", "25",
      "... and a fit drawn only once it has moved some stop 25 mm from where its vectors "
      "lie: most move the map less than its 50 mm squares, and a redraw is most of a "
      "scan's time" },
    { "reloc.coarse_cell_mm", "200",
      "maps of whole buildings (up to 46 x 45 m): the global search's coarse cell doubled, "
      "a quarter of the cells for as many answers" },
    { "reloc.coarse_max_cells", "1048576", "... and room for such a map drawn at drifted poses" },
    LOST_OFF_KEYS
};

/* A laser scanner: the settings of all five real buildings (docs/results/real-buildings.md). */
static const hl_profile_key_t laser[] = {
    { "slam.map_capacity", "15000",
      "360 readings a scan: 1500 vectors hold a few seconds of them, 15,000 hold whole floors" },
    { "slam.map_per_place", "2",
      "at most 2 vectors of any map_square_mm square seen from one side (a new one replaces "
      "one of them at random)" },
    { "slam.map_square_mm", "50", "... in 50 mm squares" },
    { "slam.window_mm", "500",
      "scans several times a second: odometry is off by centimetres between two, and a "
      "+-0.5 m window is plenty" },
    { "slam.echo_bearings", "false", "a thin beam: the echo lies on the beam's axis" },
    { "slam.fit_normals", "true",
      "a laser hears a wall at any angle: each reading takes the normal of a line through "
      "its neighbours" },
    { "normals.keep_unfitted", "true",
      "... and a reading on no line (a corner, clutter) stays square to its beam" },
    { "localize.reading_stride", "2",
      "every second reading votes, which pins the peak as well (the refinement fits all)" },
    { "localize.group_mm", "48",
      "the map stays dense along walls: vectors of one 48 mm square vote together" },
    CONTINUOUS_CLOSURE_KEYS
    { "slam.closure_match_readings", "512",
      "... a keyframe matched with 512 of its readings (up to 1,024 joined), which keeps a "
      "scan's matches within 50 ms" },
    { "reloc.coarse_cell_mm", "200",
      "maps of whole buildings (up to 56 x 84 m): the global search's coarse cell doubled, "
      "a quarter of the cells" },
    { "reloc.coarse_max_cells", "2097152", "... and room for such a map drawn at drifted poses" },
    LOST_OFF_KEYS
};

#define PROFILE(name, summary, keys) { name, summary, keys, sizeof keys / sizeof keys[0] }

static const hl_sensor_profile_t profiles[] = {
    { "sonar-stops",
      "the paper's sonar ring, sounded at stops a metre or so apart: the compiled-in "
      "defaults", NULL, 0 },
    PROFILE("sonar-continuous",
            "a sonar ring sounded several times a second while the robot moves", sonar_continuous),
    PROFILE("laser", "a laser scanner: hundreds of thin beams several times a second", laser),
};

size_t hl_sensor_profile_count(void)
{
    return sizeof profiles / sizeof profiles[0];
}

const hl_sensor_profile_t *hl_sensor_profile_at(size_t i)
{
    return i < hl_sensor_profile_count() ? &profiles[i] : NULL;
}

const hl_sensor_profile_t *hl_sensor_profile_find(const char *name)
{
    for (size_t i = 0; name && i < hl_sensor_profile_count(); i++)
        if (strcmp(name, profiles[i].name) == 0)
            return &profiles[i];
    return NULL;
}

void hl_sensor_profile_print(const hl_sensor_profile_t *p, FILE *out)
{
    fprintf(out,
            "; houghloc sensor profile '%s' (houghlocd --print-profile %s):\n"
            "; %s.\n"
            "; Its keys, as `slam.profile = %s` sets them after slam.mode's preset and\n"
            "; before every other key; read as a configuration file, this sets the same.\n",
            p->name, p->name, p->summary, p->name);
    if (p->n_keys == 0) {
        fputs("; It sets no key.\n", out);
        return;
    }
    const char *section = "";
    size_t section_len = 0;
    for (size_t i = 0; i < p->n_keys; i++) {
        const char *key = p->keys[i].key, *dot = strchr(key, '.');
        size_t len = (size_t)(dot - key);
        if (len != section_len || strncmp(key, section, len) != 0) {
            fprintf(out, "\n[%.*s]\n", (int)len, key);
            section = key;
            section_len = len;
        }
        fprintf(out, "; %s\n%s = %s\n", p->keys[i].why, dot + 1, p->keys[i].value);
    }
}

uint32_t hl_sensor_profile_capacity(const hl_sensor_profile_t *p)
{
    for (size_t i = 0; p && i < p->n_keys; i++)
        if (strcmp(p->keys[i].key, "slam.map_capacity") == 0)
            return (uint32_t)strtoul(p->keys[i].value, NULL, 10);
    return 0;
}

void hl_capacity_advice(const char *path, uint32_t count, uint32_t capacity, char *out,
                        size_t cap)
{
    /* the profile with the smallest map that holds the file, if any */
    const hl_sensor_profile_t *fits = NULL;
    for (size_t i = 0; i < hl_sensor_profile_count(); i++) {
        uint32_t c = hl_sensor_profile_capacity(&profiles[i]);
        if (c >= count && (!fits || c < hl_sensor_profile_capacity(fits)))
            fits = &profiles[i];
    }
    char profile[64] = "";
    if (fits)
        snprintf(profile, sizeof profile, ", or slam.profile = %s", fits->name);
    snprintf(out, cap,
             "%.300s: holds %u vectors, more than slam.map_capacity = %u: raise it "
             "(--set slam.map_capacity=%u%s) or start afresh with --fresh-map (which moves "
             "this file aside)",
             path, count, capacity, count, profile);
}
