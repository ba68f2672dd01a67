/*
 * flood.c - hl-flood: publishes malformed LCM messages on houghlocd's input channels at
 * a fixed rate for a bounded time (the Flood trial, tools/lab/trials/flood.sh).
 *
 * Loopback only: the URL must be udpm:// with ttl=0, so the flood never leaves the host.
 * The messages come from flood_msg.c, each checked to be refused by the daemon's own
 * decoder. The rate is per channel: --rate 10000 on the four inputs is 40,000 messages a
 * second in all. The last stdout line says what was sent.
 *
 * --kind save sends well-formed unsigned SAVE requests on COMMAND instead, seq 1, 2, ...
 * (the save-flood trial, tools/lab/trials/save_flood.sh): requests a daemon without a key
 * takes, each asking it to write its map.
 */
#include <errno.h>
#include <lcm/lcm.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "flood_msg.h"
#include "houghloc/bus.h"
#include "houghloc/version.h"
#include "trial_args.h"

#define PROG "hl-flood"

static const char usage[] =
    "Usage: hl-flood --lcm-url URL [--seconds S] [--rate N] [--seed N] [--prefix P]\n"
    "                [--channels LIST] [--kind malformed|save]\n"
    "Publishes malformed messages on houghlocd's input channels: random bytes, truncated\n"
    "encodings, wrong fingerprints, messages of another type, trailing bytes and fields\n"
    "out of range, each checked to be refused by the channel's own decoder.\n"
    "  --lcm-url URL    where to publish: udpm:// with ttl=0 only (this host; required)\n"
    "  --seconds S      how long, 0.1..3600 (default 10); SIGINT or SIGTERM stops sooner\n"
    "  --rate N         messages per second on EACH channel, 1..1000000 (default 10000:\n"
    "                   40,000 a second in all on the four channels)\n"
    "  --seed N         everything sent is a function of it (default 1)\n"
    "  --prefix P       the channel prefix, as houghlocd's --prefix\n"
    "  --channels LIST  comma-separated subset of SONAR,ODOMETRY,DESTINATION,COMMAND\n"
    "                   (default all four)\n"
    "  --kind K         malformed (default) or save: well-formed unsigned SAVE requests\n"
    "                   on COMMAND alone, seq 1, 2, ... (--rate of them a second)\n"
    "  --help, --version\n"
    "The last line on stdout:\n"
    "  flood sent=<n> seconds=<s> per_channel_per_s=<r> SONAR=<n> ODOMETRY=<n>\n"
    "        DESTINATION=<n> COMMAND=<n> publish_errors=<n>\n"
    "per kind counts go to stderr. Exit status: 0 done, 1 LCM or generator failure,\n"
    "2 bad usage.\n";

typedef struct options {
    const char *url, *prefix;
    double seconds;
    long rate;
    unsigned long long seed;
    bool use[FLOOD_INPUTS];
    bool save;                  /* --kind save */
} options_t;

static volatile sig_atomic_t stop_requested;

static void on_stop(int sig)
{
    (void)sig;
    stop_requested = 1;
}

static bool parse_ull(const char *s, unsigned long long *out)
{
    if (*s < '0' || *s > '9')
        return false;
    char *end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (*end || errno)
        return false;
    *out = v;
    return true;
}

/* udpm://... with a query parameter exactly ttl=0. */
static bool loopback_url(const char *url)
{
    if (strncmp(url, "udpm://", 7) != 0)
        return false;
    const char *q = strchr(url, '?');
    while (q) {
        q++;
        size_t n = strcspn(q, "&");
        if (n == 5 && strncmp(q, "ttl=0", 5) == 0)
            return true;
        q = strchr(q, '&');
    }
    return false;
}

static bool parse_channels(const char *list, bool *use)
{
    memset(use, 0, FLOOD_INPUTS * sizeof *use);
    const char *p = list;
    bool any = false;
    for (;;) {
        size_t n = strcspn(p, ",");
        int found = -1;
        for (int i = 0; i < FLOOD_INPUTS; i++)
            if (strlen(flood_input_name((flood_input_t)i)) == n &&
                strncmp(p, flood_input_name((flood_input_t)i), n) == 0)
                found = i;
        if (found < 0 || use[found])
            return false;
        use[found] = any = true;
        if (!p[n])
            return any;
        p += n + 1;
    }
}

/* @return -1 to go on, else an exit status (after --help or an error message). */
static int parse_args(int argc, char **argv, options_t *o)
{
    static const char *const names[] = { "--lcm-url", "--seconds", "--rate", "--seed",
                                          "--prefix", "--channels", "--kind" };
    const trial_cli_t cli = { PROG, usage, HL_VERSION, names, 7, true };
    for (int i = 1; i < argc; i++) {
        const char *v;
        int status;
        int k = trial_next_option(&cli, argc, argv, &i, &v, &status);
        if (k < 0)
            return status;
        double d;
        char channel[HL_BUS_CHANNEL_MAX];
        switch (k) {
        case 0: o->url = v; break;
        case 1:
            if (!trial_parse_double(v, 0.1, 3600.0, &d))
                return trial_usage_error(PROG, "--seconds: give 0.1 to 3600, not", v);
            o->seconds = d;
            break;
        case 2:
            if (!trial_parse_double(v, 1, 1e6, &d) || d != (long)d)
                return trial_usage_error(PROG, "--rate: give a whole number 1 to 1000000, not", v);
            o->rate = (long)d;
            break;
        case 3:
            if (!parse_ull(v, &o->seed))
                return trial_usage_error(PROG, "--seed: give a non-negative whole number, not", v);
            break;
        case 4:
            if (!hl_bus_channel(v, HL_CHANNEL_DESTINATION, channel))
                return trial_usage_error(PROG, "--prefix: at most 32 letters, digits, '_-./', not", v);
            o->prefix = v;
            break;
        case 6:
            if (strcmp(v, "malformed") != 0 && strcmp(v, "save") != 0)
                return trial_usage_error(PROG, "--kind: give malformed or save, not", v);
            o->save = strcmp(v, "save") == 0;
            break;
        default:
            if (!parse_channels(v, o->use))
                return trial_usage_error(PROG, "--channels: a comma-separated subset of "
                                   "SONAR,ODOMETRY,DESTINATION,COMMAND, not", v);
        }
    }
    if (!o->url)
        return fprintf(stderr, "%s: --lcm-url is required; try %s --help\n", PROG, PROG),
               TRIAL_EXIT_USAGE;
    if (!loopback_url(o->url))
        return trial_usage_error(PROG, "refusing to flood beyond this host: give a udpm:// URL with "
                           "ttl=0, not", o->url);
    if (o->save)    /* SAVE requests go on COMMAND */
        for (int i = 0; i < FLOOD_INPUTS; i++)
            o->use[i] = i == FLOOD_COMMAND;
    return -1;
}

static int64_t mono_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

typedef struct flood {
    lcm_t *lcm;
    bool save;
    hl_rng_t rng;
    int n_inputs;
    flood_input_t inputs[FLOOD_INPUTS];
    char channel[FLOOD_INPUTS][HL_BUS_CHANNEL_MAX];
    long long sent, per_input[FLOOD_INPUTS], per_kind[FLOOD_KINDS], errors;
} flood_t;

/* One message on the next channel in turn. @return false on a generator failure. */
static bool send_one(flood_t *f)
{
    static uint8_t buf[FLOOD_MSG_MAX];
    int which = (int)(f->sent % f->n_inputs);
    flood_input_t in = f->inputs[which];
    flood_kind_t kind = FLOOD_RANDOM;
    int len = f->save ? flood_make_save(f->sent + 1, buf) : flood_make(&f->rng, in, buf, &kind);
    if (len < 0)
        return fprintf(stderr, "%s: could not make a %s %s message (a bug)\n", PROG,
                       f->save ? "SAVE" : "malformed", flood_input_name(in)), false;
    if (lcm_publish(f->lcm, f->channel[which], buf, (unsigned)len) != 0)
        f->errors++;
    f->sent++;
    f->per_input[in]++;
    f->per_kind[kind] += !f->save;
    return true;
}

/* Sends at rate * n_inputs messages a second, catching up in bursts after a late wake-up,
 * until the time is up or a signal arrives. */
static bool run(flood_t *f, const options_t *o)
{
    const double total_rate = (double)o->rate * f->n_inputs;
    const int64_t start = mono_us(), end = start + (int64_t)(o->seconds * 1e6);
    for (int64_t now = start; now < end && !stop_requested; now = mono_us()) {
        long long due = (long long)((double)(now - start) * total_rate / 1e6) + 1;
        while (f->sent < due && !stop_requested)
            if (!send_one(f))
                return false;
        struct timespec pause = { 0, 200000 };  /* 0.2 ms: bursts of at most ~8 at 40k/s */
        nanosleep(&pause, NULL);
    }
    return true;
}

int main(int argc, char **argv)
{
    options_t o = { .prefix = "", .seconds = 10.0, .rate = 10000, .seed = 1,
                    .use = { true, true, true, true } };
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0)
        return rc;
    flood_t f = { .n_inputs = 0, .save = o.save };
    for (int i = 0; i < FLOOD_INPUTS; i++)
        if (o.use[i]) {
            f.inputs[f.n_inputs] = (flood_input_t)i;
            hl_bus_channel(o.prefix, flood_input_name((flood_input_t)i), f.channel[f.n_inputs]);
            f.n_inputs++;
        }
    hl_rng_seed(&f.rng, o.seed);
    f.lcm = lcm_create(o.url);
    if (!f.lcm)
        return fprintf(stderr, "%s: cannot open LCM at %s\n", PROG, o.url), 1;
    struct sigaction sa = { .sa_handler = on_stop };
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    int64_t t0 = mono_us();
    bool ok = run(&f, &o);
    double secs = (double)(mono_us() - t0) / 1e6;
    lcm_destroy(f.lcm);

    fprintf(stderr, "%s: kinds", PROG);
    for (int k = 0; k < FLOOD_KINDS; k++)
        fprintf(stderr, " %s=%lld", flood_kind_name((flood_kind_t)k), f.per_kind[k]);
    fprintf(stderr, "\n");
    printf("flood sent=%lld seconds=%.2f per_channel_per_s=%.0f", f.sent, secs,
           secs > 0 ? (double)f.sent / f.n_inputs / secs : 0.0);
    for (int i = 0; i < FLOOD_INPUTS; i++)
        printf(" %s=%lld", flood_input_name((flood_input_t)i), f.per_input[i]);
    printf(" publish_errors=%lld\n", f.errors);
    return ok ? 0 : 1;
}
