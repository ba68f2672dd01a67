/* config_keys.c - the daemon's own configuration keys, their types, ranges and meanings
 * (the tracker's are the core's table: houghloc/params.h); and the keys it no longer has. */
#include "config_keys.h"

#include <string.h>

#include "config.h"
#include "houghloc/fixed.h"

#define F(field) offsetof(hl_config_t, field), sizeof(((hl_config_t *)0)->field)
#define SND(field) F(sounder.field)
/* No longer a key: fixed at its default, which nothing changed (no profile, trial or
 * documented need; the values and why: the defaults' functions, hl_config_defaults for
 * the daemon's own). Read with a warning when a file names that value, refused otherwise
 * (config.c). */
#define RETIRED NULL

const hl_config_key_t hl_config_keys[] = {
    { "lcm.url", HL_KEY_STR, F(lcm_url), 0, 0,
      "LCM URL to listen on; empty: $LCM_DEFAULT_URL, else udpm://239.255.76.67:7667?ttl=0 "
      "(this host only); a file:// URL replays a log as fast as possible and exits at its end" },
    { "lcm.out_url", HL_KEY_STR, F(lcm_out), 0, 0,
      "LCM URL to publish on; empty: the listening URL (for a log replay: the live default); "
      "file://OUT.lcmlog?mode=w records the output" },
    { "lcm.prefix", HL_KEY_STR, F(prefix), 0, 0,
      "put in front of every channel name (SONAR, POSE, ...) so that robots share a network" },
    { "lcm.queue", HL_KEY_I32, F(queue), 1, 100000,
      "messages liblcm queues per input channel before it drops (its default is 30)" },
    { "daemon.map_file", HL_KEY_STR, F(map_file), 0, 0,
      "the map file; empty: $STATE_DIRECTORY/map.hlmap (the service), else "
      "/var/lib/houghloc/map.hlmap if that folder is writable, else "
      "$XDG_STATE_HOME/houghloc/map.hlmap (~/.local/state/houghloc/)" },
    { "daemon.save_every", HL_KEY_I32, F(save_every), 0, 1000000,
      "save the map after this many integrated scans; 0: only on exit and on SAVE" },
    { "daemon.map_period_ms", HL_KEY_I32, F(map_period_ms), 0, 3600000, RETIRED },
    { "daemon.map_input_ratio", HL_KEY_I32, F(map_input_ratio), 0, 1000,
      "after the first MAP, the next waits until the SONAR and ODOMETRY bytes since the last, "
      "times this, reach its size: MAP stays within this many times the input; 0: no bound "
      "in bytes" },
    { "daemon.status_period_ms", HL_KEY_I32, F(status_period_ms), 100, 60000,
      "publish STATUS this often (and on every state change)" },
    { "daemon.idle_after_ms", HL_KEY_I32, F(idle_after_ms), 100, 3600000, RETIRED },
    { "daemon.compute_window", HL_KEY_I32, F(compute_window), 1, 10000,
      "scans over which STATUS reports the median and 99th percentile compute time" },
    { "daemon.log_level", HL_KEY_LEVEL, F(log_level), 0, 0,
      "error, warning, notice, info or debug" },
    { "auth.key_file", HL_KEY_STR, F(key_file), 0, 0,
      "a file of 64 hex digits, mode 0600; when set, DESTINATION and COMMAND must carry its MAC "
      "(under systemd: /run/credentials/houghlocd.service/key, see docs/manual/service.md)" },
    { "auth.state_file", HL_KEY_STR, F(state_file), 0, 0,
      "with a key: the file keeping the last accepted request seq against replays after a "
      "crash or a new map; empty: requests.seq in the map file's folder; one daemon per file" },
    { "auth.max_ahead_s", HL_KEY_I32, F(max_ahead_s), 1, 31622400,
      "refuse a request seq (the sender's clock, us) this many seconds ahead of the daemon's "
      "clock, so a sender with a wrong clock cannot lock others out; 300: NTP clocks and more" },
    { "start.x_m", HL_KEY_METRES, F(start.x_mm), -4194, 4194,
      "where the first scan is placed, metres (this defines the map frame)" },
    { "start.y_m", HL_KEY_METRES, F(start.y_mm), -4194, 4194, "metres" },
    { "start.heading_deg", HL_KEY_DEG, F(start.theta), -360, 360, "degrees, counter-clockwise" },
    { "fence.rect", HL_KEY_FENCE_RECT, F(fence), 0, 0,
      "destinations must lie in this rectangle: MIN_X,MIN_Y,MAX_X,MAX_Y in metres" },
    { "fence.polygon", HL_KEY_FENCE_POLYGON, F(fence), 0, 0,
      "destinations must lie in this polygon: X,Y X,Y X,Y ... in metres (3 to 64 vertices, "
      "one line); or fence.rect, MIN_X,MIN_Y,MAX_X,MAX_Y; the last of the two wins" },
    /* the core's sections ([slam], [localize], [echo], [normals], [reloc]): its table's
     * keys, printed here, in its order (config_print.c) */
    { "slam.*", HL_KEY_CORE, 0, 0, 0, 0, NULL },
    { "robot.link", HL_KEY_LINK, F(robot_link), 0, 0,
      "the robot: serial:DEVICE[,BAUD] (ARCOS, 9600 baud unless given), tcp:HOST:PORT "
      "(houghloc-sim) or file:CAPTURE (a houghloc-sim --capture, replayed); empty: SONAR and "
      "ODOMETRY come over LCM" },
    { "robot.profile", HL_KEY_ROBOT_PROFILE, F(robot_profile), 0, 0,
      "which robot: bonnie (16 transducers evenly, the paper's), pioneer3, or houghloc-sim "
      "(bonnie's ring with the simulator's calibration); a preset under calibration.*" },
    { "robot.sound_on_connect", HL_KEY_BOOL, F(robot_sound_on_connect), 0, 0,
      "sound once when the robot first connects (the map's first scan)" },
    { "robot.lost_soundings", HL_KEY_I32, F(robot_lost_soundings), 0, 1000, RETIRED },
    { "robot.reconnect_max_ms", HL_KEY_I32, F(robot_reconnect_max_ms), 250, 600000, RETIRED },
    { "robot.radius_mm", HL_KEY_I32, F(robot_radius_mm), 50, 2000,
      "the robot's body: paths keep its centre this far from walls on the map, and the "
      "safety stop watches a strip this wide to each side" },
    { "robot.lockstep", HL_KEY_BOOL, F(robot_lockstep), 0, 0,
      "the robot is houghloc-sim --lockstep: its clock runs as the daemon deals with each "
      "packet, held while the robot is idle, so a run does not depend on the machine's load "
      "(never for a real robot)" },
    { "robot.sounding_steps", HL_KEY_I32, SND(steps), 1, 32, RETIRED },
    { "robot.sounding_step_deg", HL_KEY_DEG, SND(step), 0.01, 90, RETIRED },
    { "robot.settle_ms", HL_KEY_I32, SND(settle_ms), 0, 60000, RETIRED },
    { "robot.step_timeout_ms", HL_KEY_I32, SND(step_timeout_ms), 100, 600000, RETIRED },
    { "calibration.gain_q16", HL_KEY_I32, SND(calib.gain_q16), 1, 1048576,
      "sonar range: mm per raw unit x 65536 (hl-calibrate prints it; default: "
      "robot.profile's)" },
    { "calibration.offset_mm", HL_KEY_I32, SND(calib.offset_mm), -10000, 10000,
      "sonar range: added after the gain" },
    { "calibration.min_raw", HL_KEY_U16, SND(calib.min_raw), 0, 65535, RETIRED },
    { "calibration.sentinel_raw", HL_KEY_U16, SND(calib.sentinel_raw), 1, 65535, RETIRED },
    { "calibration.max_range_mm", HL_KEY_I32, SND(calib.max_range_mm), 1, 32767, RETIRED },
    { "drive.arrive_mm", HL_KEY_I32, F(drive.arrive_mm), 10, 5000,
      "a destination is reached when the localized estimate is this close" },
    { "drive.max_leg_mm", HL_KEY_I32, F(drive.max_leg_mm), 10, 30000,
      "longest drive between two soundings" },
    { "drive.max_legs", HL_KEY_I32, F(drive.max_legs), 1, 1000, RETIRED },
    { "drive.speed_mm_s", HL_KEY_I32, F(drive.speed_mm_s), 10, 5000,
      "the base's top speed on a leg (SETV), and its timeouts" },
    { "drive.turn_deg_s", HL_KEY_I32, F(drive.turn_deg_s), 1, 720,
      "the base's turning speed, for timeouts" },
    { "drive.slack_ms", HL_KEY_I32, F(drive.slack_ms), 0, 600000, RETIRED },
    { "drive.stop_mm", HL_KEY_I32, F(drive.stop_mm), 0, 5000,
      "the safety stop: a sonar reading in the way ahead this close (from the robot's centre) "
      "stops the leg; the robot sounds and plans round it (the radius and 100 mm)" },
    { "drive.slow_mm", HL_KEY_I32, F(drive.slow_mm), 0, 10000,
      "a reading in the way this close slows the leg, down to a quarter of the speed at "
      "drive.stop_mm; 0: never slow" },
    { "link.sync_timeout_ms", HL_KEY_I32, F(rlink.sync_timeout_ms), 10, 60000, RETIRED },
    { "link.sync_tries", HL_KEY_I32, F(rlink.sync_tries), 1, 100, RETIRED },
    { "link.silence_ms", HL_KEY_I32, F(rlink.silence_ms), 100, 600000,
      "no packet from the robot this long: the link is lost (wall clock)" },
    { "link.pulse_ms", HL_KEY_I32, F(rlink.pulse_ms), 10, 1500, RETIRED },
};

const size_t hl_config_nkeys = sizeof hl_config_keys / sizeof hl_config_keys[0];

/* The daemon's keys an operator sets (--print-config, packaging/houghlocd.conf): where
 * the daemon talks and keeps its map, who may command it, where the robot starts and may
 * go, which robot it has, and how the robot drives (the core's table marks its own
 * operator keys: the sensor profile, the map's size, the LOST state). */
static const char *const operator_keys[] = {
    "lcm.url", "lcm.prefix",
    "daemon.map_file", "daemon.save_every", "daemon.log_level",
    "auth.key_file",
    "start.x_m", "start.y_m", "start.heading_deg",
    "fence.polygon",
    "robot.link", "robot.profile",
    "calibration.gain_q16", "calibration.offset_mm",
    "robot.radius_mm",
    "drive.arrive_mm", "drive.max_leg_mm", "drive.speed_mm_s", "drive.turn_deg_s",
    "drive.stop_mm", "drive.slow_mm",
};

const hl_config_key_t *hl_config_key_find(const char *name)
{
    for (size_t i = 0; i < hl_config_nkeys; i++)
        if (strcmp(hl_config_keys[i].name, name) == 0)
            return &hl_config_keys[i];
    return NULL;
}

bool hl_config_key_for_operator(const hl_config_key_t *k)
{
    for (size_t i = 0; i < sizeof operator_keys / sizeof operator_keys[0]; i++)
        if (strcmp(k->name, operator_keys[i]) == 0)
            return true;
    return false;
}
