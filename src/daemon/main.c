/* main.c - houghlocd: arguments, configuration, the map file, then the loop. */
#include <errno.h>
#include <getopt.h>
#include <inttypes.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <systemd/sd-daemon.h>
#include <unistd.h>

#include "config.h"
#include "cycle.h"
#include "houghloc/logcheck.h"
#include "houghloc/version.h"
#include "houghloc/keyfile.h"
#include "log.h"
#include "loop.h"
#include "map_location.h"
#include "maplock.h"
#include "houghloc/mapstore.h"
#include "profiles.h"
#include "request_state.h"


#define HOST_ONLY_URL "udpm://239.255.76.67:7667?ttl=0"

static const char usage[] =
    "Usage: houghlocd [OPTIONS]\n"
    "Sonar localization and map-making daemon: localizes each SONAR scan against its map\n"
    "of tangent vectors with a Hough transform, adds it to the map, and publishes POSE,\n"
    "MAP and STATUS over LCM; answers DESTINATION and COMMAND on REPLY.\n"
    "\n"
    "Options:\n"
    "  -c, --config FILE    configuration file (default " HL_CONFIG_DEFAULT_PATH ";\n"
    "                       a missing default file means the compiled-in defaults)\n"
    "  -m, --map FILE       map file (default: $STATE_DIRECTORY/map.hlmap under the\n"
    "                       service; else /var/lib/houghloc/map.hlmap if that folder is\n"
    "                       writable; else $XDG_STATE_HOME/houghloc/map.hlmap, by default\n"
    "                       ~/.local/state/houghloc/, created 0700); logged at start\n"
    "      --fresh-map      start with an empty map; an existing map file is moved aside\n"
    "                       first, to FILE.old-N (FILE.bad-N if it does not load)\n"
    "  -u, --lcm-url URL    listen here (default: config lcm.url, $LCM_DEFAULT_URL, else\n"
    "                       " HOST_ONLY_URL ", this host only).\n"
    "                       'file://IN.lcmlog?speed=0' replays a log as fast as possible\n"
    "                       and exits at its end\n"
    "  -o, --lcm-out URL    publish here (default: the listening URL; for a replay, the\n"
    "                       live default); 'file://OUT.lcmlog?mode=w' records a log\n"
    "  -p, --prefix P       channel name prefix (SONAR becomes PSONAR, ...)\n"
    "  -s, --set K=V        set configuration key K (section.key), after the file;\n"
    "                       may be repeated; e.g. --set slam.profile=laser,\n"
    "                       --set robot.profile=houghloc-sim\n"
    "      --print-config   print the effective configuration's operator keys (and any\n"
    "                       other key set away from its default) and exit\n"
    "      --print-config=all  print every key of it, each with its comment, and exit\n"
    "      --print-profile NAME  print the keys sensor profile NAME sets (slam.profile:\n"
    "                       sonar-stops, sonar-continuous or laser) as an INI fragment,\n"
    "                       the file share/houghloc/profiles/NAME.conf, and exit\n"
    "      --check-map      check the map file, print what it holds and exit (0 if it\n"
    "                       loads, 1 if not)\n"
    "  -h, --help           this text\n"
    "      --version        the version\n"
    "\n"
    "Channels: SONAR, ODOMETRY, DESTINATION, COMMAND in; POSE (one per scan), MAP,\n"
    "STATUS, REPLY out. SIGTERM/SIGINT save the map and stop; SIGHUP saves it; a map\n"
    "unchanged since it was loaded or saved is not written. One daemon per map file: it\n"
    "holds a lock on FILE.lock while it runs.\n"
    "Exit status: 0 after a clean stop or the end of a replay, 1 on a start-up error or\n"
    "a fault, 2 on bad usage. See README.md for the whole story.\n";

typedef struct options {
    const char *config;
    bool config_given;
    bool fresh_map, print_config, print_all, check_map;
    const char *sets[HL_CONFIG_MAX_OVERRIDES];
    char set_buf[4][HL_CONFIG_URL_MAX + 32];   /* --map/--lcm-url/--lcm-out/--prefix as sets */
    int n_sets, n_buf;
} options_t;

static int usage_error(const char *what, const char *arg)
{
    fprintf(stderr, "houghlocd: %s '%s' (try --help)\n", what, arg);
    return 2;
}

static bool add_set(options_t *o, const char *key, const char *value)
{
    if (o->n_sets >= HL_CONFIG_MAX_OVERRIDES)
        return false;
    if (!key) {
        o->sets[o->n_sets++] = value;
        return true;
    }
    if (o->n_buf >= 4)
        return false;
    char *b = o->set_buf[o->n_buf++];
    snprintf(b, sizeof o->set_buf[0], "%s=%s", key, value);
    o->sets[o->n_sets++] = b;
    return true;
}

/* @return -1 to go on, else the exit code. */
static int parse_args(int argc, char **argv, options_t *o)
{
    enum { OPT_FRESH = 256, OPT_PRINT, OPT_VERSION, OPT_CHECK, OPT_PROFILE };
    static const struct option longopts[] = {
        { "config", required_argument, NULL, 'c' },  { "map", required_argument, NULL, 'm' },
        { "fresh-map", no_argument, NULL, OPT_FRESH }, { "lcm-url", required_argument, NULL, 'u' },
        { "lcm-out", required_argument, NULL, 'o' }, { "prefix", required_argument, NULL, 'p' },
        { "set", required_argument, NULL, 's' },
        { "print-config", optional_argument, NULL, OPT_PRINT },
        { "print-profile", required_argument, NULL, OPT_PROFILE },
        { "check-map", no_argument, NULL, OPT_CHECK }, { "help", no_argument, NULL, 'h' },
        { "version", no_argument, NULL, OPT_VERSION },
        { NULL, 0, NULL, 0 },
    };
    o->config = HL_CONFIG_DEFAULT_PATH;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":c:m:u:o:p:s:h", longopts, NULL)) != -1) {
        bool ok = true;
        switch (c) {
        case 'c': o->config = optarg; o->config_given = true; break;
        case 'm': ok = add_set(o, "daemon.map_file", optarg); break;
        case 'u': ok = add_set(o, "lcm.url", optarg); break;
        case 'o': ok = add_set(o, "lcm.out_url", optarg); break;
        case 'p': ok = add_set(o, "lcm.prefix", optarg); break;
        case 's': ok = add_set(o, NULL, optarg); break;
        case OPT_FRESH: o->fresh_map = true; break;
        case OPT_PRINT:
            if (optarg && strcmp(optarg, "all") != 0)
                return usage_error("--print-config takes no value or '=all', not", optarg);
            o->print_config = true;
            o->print_all = optarg != NULL;
            break;
        case OPT_PROFILE: {
            const hl_param_preset_t *p = hl_sensor_profile_find(optarg);
            if (!p) {
                fprintf(stderr, "houghlocd: unknown sensor profile '%s' (%s)\n", optarg,
                        hl_sensor_profile_names());
                return 2;
            }
            hl_sensor_profile_print(p, stdout);
            return 0;
        }
        case OPT_CHECK: o->check_map = true; break;
        case 'h': fputs(usage, stdout); return 0;
        case OPT_VERSION: puts("houghlocd " HL_VERSION); return 0;
        case ':': return usage_error("this option needs a value:", argv[optind - 1]);
        default: return usage_error("unknown option", argv[optind - 1]);
        }
        if (!ok)
            return usage_error("too many settings (at most 64), at", argv[optind - 1]);
    }
    if (optind < argc && o->print_config && strcmp(argv[optind], "all") == 0)
        return usage_error("unexpected argument (write --print-config=all)", argv[optind]);
    if (optind < argc)
        return usage_error("unexpected argument", argv[optind]);
    return -1;
}

/* The map file: the config's (--map), else the default location (map_location.h).
 * @param create  may create the user's folder (the daemon; not --check-map).
 * @param[out] from  where a default location came from (for the log), NULL for --map.
 * @return false after printing why. */
static bool map_path(const hl_config_t *cfg, bool create, char *out, size_t cap,
                     const char **from)
{
    *from = NULL;
    if (cfg->map_file[0]) {
        snprintf(out, cap, "%s", cfg->map_file);
        return true;
    }
    char why[HL_MAP_LOCATION_WHY_LEN];
    if (!hl_map_location_default(create, out, cap, from, why))
        return fprintf(stderr, "houghlocd: %s\n", why), false;
    return true;
}

/* A daemon that could not save would lose its map at the first stop: refuse at once. */
static bool map_folder_writable(const char *path)
{
    char copy[HL_CONFIG_PATH_MAX];
    snprintf(copy, sizeof copy, "%s", path);
    const char *dir = dirname(copy);
    if (access(dir, W_OK | X_OK) == 0)
        return true;
    fprintf(stderr, "houghlocd: cannot write the map file's folder %s: %s (give --map FILE)\n",
            dir, strerror(errno));
    return false;
}

/* Loads the map file into the cycle, whose state then is what later saves compare with
 * (maplock.h: only a change is written). With --fresh-map, an existing file is moved
 * aside first, never overwritten: to FILE.old-N when it is a map (one too big for
 * slam.map_capacity too), to FILE.bad-N when it does not load. @return false after
 * printing why. */
static bool load_map(hl_cycle_t *cycle, const char *path, bool fresh, uint32_t capacity)
{
    hl_mapfile_t m = { .max_vectors = capacity };
    m.vectors = calloc(capacity, sizeof *m.vectors);
    if (!m.vectors)
        return fprintf(stderr, "houghlocd: out of memory\n"), false;
    char why[HL_MAPSTORE_WHY_LEN];
    hl_status_t st = hl_mapstore_load(path, &m, why);
    bool too_big = st == HL_ERR_CAPACITY;
    if (too_big)    /* a good map for a larger configuration: name the setting */
        hl_capacity_advice(path, m.needed, capacity, why, sizeof why);
    if (st == HL_OK && !fresh) {
        st = hl_cycle_restore(cycle, &m);
        too_big = st != HL_OK;
        if (too_big)
            hl_capacity_advice(path, m.count, capacity, why, sizeof why);
    }
    bool ok = true;
    if (st == HL_OK && !fresh) {
        hl_mapfile_t loaded;    /* the cycle's own view of it: only its changes count */
        hl_cycle_snapshot(cycle, &loaded);
        hl_maplock_saved(&loaded);
        hl_log(HL_LOG_INFO, "map %s: %u vectors, %llu scans", path, m.count,
               (unsigned long long)m.scans);
    } else if (st == HL_ERR_OS && errno == ENOENT) {
        hl_log(HL_LOG_INFO, "map %s does not exist yet: starting empty", path);
    } else if (fresh) {
        bool good = st == HL_OK || st == HL_ERR_CAPACITY;
        char moved[HL_CONFIG_PATH_MAX + 16], why2[HL_MAPSTORE_WHY_LEN];
        ok = hl_mapstore_move_aside_as(path, good ? "old" : "bad", moved, sizeof moved,
                                       why2) == HL_OK;
        if (!ok)
            fprintf(stderr, "houghlocd: %s\n", why2);
        else if (st == HL_OK)
            hl_log(HL_LOG_NOTICE, "--fresh-map: moved the map (%u vectors, %llu scans) to %s; "
                   "starting empty", m.count, (unsigned long long)m.scans, moved);
        else if (good)
            hl_log(HL_LOG_NOTICE, "--fresh-map: moved the map (%u vectors, more than "
                   "slam.map_capacity) to %s; starting empty", m.needed, moved);
        else
            hl_log(HL_LOG_NOTICE, "--fresh-map: moved the unloadable map to %s (%s); starting "
                   "empty", moved, why);
    } else if (too_big) {
        fprintf(stderr, "houghlocd: %s\n", why);
        ok = false;
    } else {
        fprintf(stderr, "houghlocd: %s; start with --fresh-map to move it aside and begin a "
                "new map\n", why);
        ok = false;
    }
    free(m.vectors);
    return ok;
}

static int check_map(const hl_config_t *cfg)
{
    char path[HL_CONFIG_PATH_MAX], why[HL_MAPSTORE_WHY_LEN];
    const char *from;
    if (!map_path(cfg, false, path, sizeof path, &from))     /* only reads: no lock */
        return 1;
    hl_mapfile_t m = { .max_vectors = HL_MAP_MAX_CAPACITY };
    m.vectors = calloc(HL_MAP_MAX_CAPACITY, sizeof *m.vectors);
    if (!m.vectors)
        return fprintf(stderr, "houghlocd: out of memory\n"), 1;
    int rc = 0;
    if (hl_mapstore_load(path, &m, why) != HL_OK) {
        fprintf(stderr, "houghlocd: %s\n", why);
        rc = 1;
    } else {
        printf("%s: format %u, %u of %u vectors, map version %llu, %llu scans, last scan "
               "utime %lld, last request seq %lld, pose (%.3f, %.3f) m %.2f deg\n",
               path, m.format, m.count, m.capacity,
               (unsigned long long)m.state.map_version,
               (unsigned long long)m.scans, (long long)m.last_scan_utime,
               (long long)m.last_request_seq, m.state.pose.x_mm / 1000.0,
               m.state.pose.y_mm / 1000.0, hl_bam_to_sdeg(m.state.pose.theta));
    }
    free(m.vectors);
    return rc;
}

static bool cycle_params(const hl_config_t *cfg, hl_cycle_params_t *p)
{
    *p = (hl_cycle_params_t){
        .params = cfg->params, .start = cfg->start, .fence = cfg->fence,
        .save_every = cfg->save_every, .map_period_ms = cfg->map_period_ms,
        .map_input_ratio = cfg->map_input_ratio,
        .idle_after_ms = cfg->idle_after_ms, .compute_window = cfg->compute_window,
        .max_ahead_us = (int64_t)cfg->max_ahead_s * 1000000,
    };
    snprintf(p->prefix, sizeof p->prefix, "%s", cfg->prefix);
    if (!cfg->key_file[0])
        return true;
    char why[HL_KEYFILE_WHY_LEN];
    if (!hl_auth_init())
        return fprintf(stderr, "houghlocd: libsodium does not start\n"), false;
    if (hl_keyfile_load(cfg->key_file, &p->key, why) != HL_OK)
        return fprintf(stderr, "houghlocd: %s\n", why), false;
    p->authenticate = true;
    return true;
}

/* The live robot's parameters from the configuration (robot.link set). */
static bool robot_params(const hl_config_t *cfg, hl_robot_params_t *p)
{
    char why[HL_LINK_WHY_LEN];
    *p = (hl_robot_params_t){ .sounder = cfg->sounder, .drive = cfg->drive, .rlink = cfg->rlink,
                              .conv = HL_ARCOS_CONV_PIONEER,
                              .reconnect_max_ms = cfg->robot_reconnect_max_ms,
                              .sound_on_connect = cfg->robot_sound_on_connect,
                              .lost_soundings = cfg->robot_lost_soundings,
                              .radius_mm = cfg->robot_radius_mm,
                              .lockstep = cfg->robot_lockstep };
    if (!hl_link_spec_parse(cfg->robot_link, &p->link, why))
        return fprintf(stderr, "houghlocd: %s\n", why), false;
    if (hl_robot_profile_find(cfg->robot_profile, &p->profile) != HL_OK)
        return fprintf(stderr, "houghlocd: unknown robot profile '%s' (" HL_ROBOT_PROFILE_NAMES
                       ")\n", cfg->robot_profile), false;
    return true;
}

/* The daemon, its map file locked (run). */
static int run_locked(const hl_config_t *cfg, const options_t *o, const char *path)
{
    char log_path[HL_CONFIG_PATH_MAX], why[HL_CONFIG_WHY_LEN];
    const char *env_url = getenv("LCM_DEFAULT_URL");
    const char *live = env_url && *env_url ? env_url : HOST_ONLY_URL;
    const char *in_url = cfg->lcm_url[0] ? cfg->lcm_url : live;
    int reads_log = hl_log_url_path(in_url, log_path, sizeof log_path);
    if (reads_log < 0)
        return fprintf(stderr, "houghlocd: the log path in '%s' is too long\n", in_url), 1;
    if (reads_log == 1) {
        char lwhy[HL_LOG_WHY_LEN];
        hl_log_info_t info;
        if (hl_log_check(log_path, &info, lwhy) != HL_OK)
            return fprintf(stderr, "houghlocd: %s\n", lwhy), 1;
        hl_log(HL_LOG_INFO, "replaying %s: %llu events", log_path,
               (unsigned long long)info.events);
    }
    const char *out_url = cfg->lcm_out[0] ? cfg->lcm_out : reads_log ? live : in_url;
    bool live_robot = cfg->robot_link[0] != '\0';
    hl_robot_params_t rp;
    if (live_robot && reads_log == 1)
        return fprintf(stderr, "houghlocd: robot.link and a log to replay (lcm.url %s) exclude "
                       "each other\n", in_url), 1;
    if (live_robot && !robot_params(cfg, &rp))
        return 1;

    hl_cycle_params_t cp;
    if (!cycle_params(cfg, &cp))
        return 1;
    /* with a key, the request state file: one daemon's, as the map file is */
    char state_path[HL_CONFIG_PATH_MAX], swhy[HL_REQUEST_STATE_WHY_LEN];
    int state_lock = -1;
    if (cp.authenticate) {
        if (!hl_request_state_path(cfg->state_file, path, state_path, sizeof state_path))
            return fprintf(stderr, "houghlocd: the request state file's path is too long "
                           "(set auth.state_file)\n"), 1;
        pid_t holder;
        state_lock = hl_mapstore_lock(state_path, &holder, swhy);
        if (state_lock < 0)
            return fprintf(stderr, "houghlocd: request state %s (give each daemon its own "
                           "auth.state_file)\n", swhy), 1;
        if (!hl_request_state_check(state_path, swhy)) {
            hl_mapstore_unlock(state_lock);
            return fprintf(stderr, "houghlocd: %s\n", swhy), 1;
        }
    }
    hl_loop_params_t lp = { .in_url = in_url, .out_url = out_url, .batch = reads_log == 1,
                            .prefix = cfg->prefix, .queue = cfg->queue,
                            .status_period_ms = cfg->status_period_ms, .map_path = path,
                            .state_path = cp.authenticate ? state_path : NULL,
                            .robot = live_robot };
    hl_loop_t *loop = hl_loop_create(&lp, why);
    if (!loop) {
        hl_mapstore_unlock(state_lock);
        return fprintf(stderr, "houghlocd: %s\n", why), 1;
    }
    hl_cycle_io_t io = hl_loop_io(loop);
    hl_cycle_t *cycle = hl_cycle_create(&cp, &io);
    hl_robot_t *robot = cycle && live_robot ? hl_robot_create(&rp, cycle, &io) : NULL;
    int rc = 1;
    if (!cycle || (live_robot && !robot))
        fprintf(stderr, "houghlocd: out of memory for a map of %u vectors\n",
                hl_config_map_capacity(cfg));
    else if (!load_map(cycle, path, o->fresh_map, hl_config_map_capacity(cfg)))
        ;   /* said why */
    else if (cp.authenticate && !hl_request_state_open(cycle, state_path, swhy))
        fprintf(stderr, "houghlocd: %s\n", swhy);
    else {
        hl_loop_attach_robot(loop, robot);
        if (live_robot)
            hl_log(HL_LOG_INFO, "robot: %s, profile %s, %d x %d readings per sounding, "
                   "calibration mm = raw x %d / 65536 %+d", cfg->robot_link, rp.profile.name,
                   rp.profile.transducers, rp.sounder.steps, rp.sounder.calib.gain_q16,
                   rp.sounder.calib.offset_mm);
        char profile[64];
        hl_params_get(&cfg->params, "slam.profile", profile, sizeof profile);
        hl_log(HL_LOG_INFO, "houghlocd %s ready: in %s, out %s, channel prefix '%s', "
               "profile %s, map %s, requests %s", HL_VERSION, in_url, out_url,
               cfg->prefix, profile, path,
               cp.authenticate ? "authenticated" : "NOT authenticated");
        sd_notify(0, "READY=1");
        hl_cycle_set_state(cycle, HL_BUS_STATE_IDLE, 0);
        rc = hl_loop_run(loop, cycle);
        const hl_cycle_counts_t *n = hl_cycle_counts(cycle);
        struct rusage ru;
        getrusage(RUSAGE_SELF, &ru);
        hl_log(HL_LOG_INFO, "stopped: %" PRId64 " scans (%" PRId64 " accepted, %" PRId64
               " rejected, %" PRId64 " odometry only, %" PRId64 " relocalized, %" PRId64
               " lost), %" PRId64 " missed, %" PRId64 " bad messages, %" PRId64
               " requests refused, %" PRId64 " saves; peak memory %ld KiB",
               n->scans, n->accepted, n->rejected_wild, n->odometry_only, n->relocalized,
               n->lost, n->missed_scans,
               n->bad_messages, n->rejected_requests, n->saves, ru.ru_maxrss);
    }
    hl_robot_destroy(robot);
    hl_cycle_destroy(cycle);
    hl_loop_destroy(loop);
    hl_mapstore_unlock(state_lock);
    return rc;
}

/* The map file first: its lock decides whether this daemon may run at all, so it is taken
 * before the map (or a log) is read, anything is written (the output log too) or logged,
 * and a second daemon on the same map stops with one line naming the holder. */
static int run(const hl_config_t *cfg, const options_t *o)
{
    char path[HL_CONFIG_PATH_MAX], why[2 * HL_CONFIG_PATH_MAX + HL_MAPSTORE_WHY_LEN];
    const char *from;
    if (!map_path(cfg, true, path, sizeof path, &from) || !map_folder_writable(path))
        return 1;
    if (!hl_maplock_take(path, why, sizeof why))
        return fprintf(stderr, "houghlocd: %s\n", why), 1;
    if (from)
        hl_log(HL_LOG_INFO, "map file %s: the default location, from %s", path, from);
    int rc = run_locked(cfg, o, path);
    hl_maplock_release();
    return rc;
}

int main(int argc, char **argv)
{
    options_t o = { 0 };
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0)
        return rc;
    hl_config_t *cfg = malloc(sizeof *cfg);
    char why[HL_CONFIG_WHY_LEN];
    if (!cfg)
        return fprintf(stderr, "houghlocd: out of memory\n"), 1;
    if (!hl_config_load(cfg, o.config, !o.config_given, o.sets, o.n_sets, why)) {
        fprintf(stderr, "houghlocd: %s\n", why);
        free(cfg);
        return 1;
    }
    hl_log_set_level(cfg->log_level);
    for (int i = 0; i < cfg->n_notes; i++)
        hl_log(HL_LOG_WARNING, "config: %s", cfg->notes[i]);
    if (o.print_config) {
        if (o.print_all)
            hl_config_print(cfg, stdout);
        else
            hl_config_print_operator(cfg, stdout);
        rc = 0;
    } else if (o.check_map)
        rc = check_map(cfg);
    else
        rc = run(cfg, &o);
    free(cfg);
    return rc;
}
