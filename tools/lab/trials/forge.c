/*
 * forge.c - hl-forge: the client side of the Commands trial (tools/lab/trials/commands.sh).
 *
 * Sends houghlocd, one at a time, valid requests signed with its key interleaved with
 * forged, replayed, stale, unsigned and out-of-fence ones (forge_req.c makes them), waits
 * for each one's REPLY and checks its result: valid destinations NO_ROBOT (the daemon has
 * no robot: the answer that comes after the MAC, freshness and fence checks) and valid
 * commands (SET_POSE, SAVE) ACCEPTED; forged and unsigned REJECTED_AUTH, replayed and
 * stale REJECTED_REPLAY, outside the fence REJECTED_FENCE.
 *
 * Two other modes: --cross-prefix P sends valid requests signed for another robot's
 * channel prefix P (captured there, played here), each of which must be refused
 * (REJECTED_AUTH); --forge-replies S plays the attacker against the clients: for S
 * seconds it answers every request it sees with forged REPLY messages (ARRIVED for a
 * destination, ACCEPTED for a command), unsigned, signed with a wrong key, and signed with
 * the right key for another prefix, which a client holding the key must ignore.
 */
#include <errno.h>
#include <lcm/lcm.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "forge_req.h"
#include "houghloc/version.h"
#include "trial_args.h"
#include "houghloc/keyfile.h"

#define PROG "hl-forge"
#define SHOW_WRONG 10       /* wrong answers printed one by one; the rest only counted */

static const char usage[] =
    "Usage: hl-forge --lcm-url URL --key FILE [--rounds N] [--seed N] [--prefix P]\n"
    "                [--timeout S] [--fence-m M] [--cross-prefix P | --forge-replies S]\n"
    "Sends houghlocd (with auth.key_file set and no robot) a valid DESTINATION and a valid\n"
    "COMMAND, then N rounds, each in a seeded order: a valid destination, a valid command\n"
    "(SET_POSE or SAVE), and one forged (wrong key, a flipped MAC bit, a field changed after\n"
    "signing), replayed (an exact copy of an accepted request), stale (seq below the last\n"
    "accepted), unsigned and out-of-fence request. Each waits for its REPLY: valid\n"
    "destinations must get NO_ROBOT, valid commands ACCEPTED, forged and unsigned\n"
    "REJECTED_AUTH, replayed and stale REJECTED_REPLAY, out-of-fence REJECTED_FENCE.\n"
    "Fresh seqs follow the wall clock in microseconds, as houghloc-goto's.\n"
    "  --lcm-url URL   the daemon's LCM URL (required)\n"
    "  --key FILE      the daemon's key file (required; mode 0600 or 0400)\n"
    "  --rounds N      1..10000 (default 60)\n"
    "  --seed N        the order and contents (default 1)\n"
    "  --prefix P      the channel prefix, as houghlocd's --prefix\n"
    "  --timeout S     seconds to wait for each REPLY, 0.1..60 (default 2)\n"
    "  --fence-m M     the daemon's fence holds the square +-M metres and refuses beyond\n"
    "                  1.5 M (default 10, the default fence)\n"
    "  --cross-prefix P  instead: N valid requests signed for channel prefix P, sent on\n"
    "                  --prefix's channels; each must be refused (REJECTED_AUTH)\n"
    "  --forge-replies S  instead: for S seconds (0.1..3600), answer every DESTINATION and\n"
    "                  COMMAND seen on --prefix's channels with forged REPLY messages\n"
    "  --help, --version\n"
    "The last line on stdout:\n"
    "  forge valid=<k>/<n> forged=<k>/<n> replayed=<k>/<n> stale=<k>/<n> unsigned=<k>/<n>\n"
    "        out_of_fence=<k>/<n> bad_rejected=<k>/<n> valid_accepted=<k>/<n> no_reply=<n>\n"
    "(k: answered as required); with --cross-prefix:\n"
    "  forge cross_prefix accepted=<k>/<n> no_reply=<n>\n"
    "with --forge-replies:\n"
    "  forge replies requests=<n> forged=<n>\n"
    "Exit status: 0 all as required, 1 otherwise or on an error, 2 bad usage.\n";

typedef struct options {
    const char *url, *key_file, *prefix;
    const char *cross_prefix;   /* NULL: the normal trial */
    long rounds;
    unsigned long long seed;
    double timeout_s, fence_m;
    double forge_replies_s;     /* 0: not that mode */
} options_t;

/* @return -1 to go on, else an exit status (after --help or an error message). */
static int parse_args(int argc, char **argv, options_t *o)
{
    static const char *const names[] = { "--lcm-url", "--key", "--rounds", "--seed",
                                          "--prefix", "--timeout", "--fence-m",
                                          "--cross-prefix", "--forge-replies" };
    const trial_cli_t cli = { PROG, usage, HL_VERSION, names, 9, false };
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
        case 1: o->key_file = v; break;
        case 2:
            if (!trial_parse_double(v, 1, 10000, &d) || d != (long)d)
                return trial_usage_error(PROG, "--rounds: give a whole number 1 to 10000, not", v);
            o->rounds = (long)d;
            break;
        case 3:
            if (!trial_parse_double(v, 0, 1e15, &d) || d != (double)(unsigned long long)d)
                return trial_usage_error(PROG, "--seed: give a whole number 0 to 10^15, not", v);
            o->seed = (unsigned long long)d;
            break;
        case 4:
            if (!hl_bus_channel(v, HL_CHANNEL_DESTINATION, channel))
                return trial_usage_error(PROG, "--prefix: at most 32 letters, digits, '_-./', not", v);
            o->prefix = v;
            break;
        case 5:
            if (!trial_parse_double(v, 0.1, 60, &o->timeout_s))
                return trial_usage_error(PROG, "--timeout: give 0.1 to 60 seconds, not", v);
            break;
        case 6:
            if (!trial_parse_double(v, 1, 1000, &o->fence_m))
                return trial_usage_error(PROG, "--fence-m: give 1 to 1000 metres, not", v);
            break;
        case 7:
            if (!hl_bus_channel(v, HL_CHANNEL_DESTINATION, channel))
                return trial_usage_error(PROG, "--cross-prefix: at most 32 letters, digits, "
                                         "'_-./', not", v);
            o->cross_prefix = v;
            break;
        default:
            if (!trial_parse_double(v, 0.1, 3600, &o->forge_replies_s))
                return trial_usage_error(PROG, "--forge-replies: give 0.1 to 3600 seconds, not",
                                         v);
        }
    }
    if (!o->url || !o->key_file)
        return fprintf(stderr, "%s: --lcm-url and --key are required; try %s --help\n", PROG,
                       PROG), TRIAL_EXIT_USAGE;
    return -1;
}

/* ---- one request, one answer ------------------------------------------------------------ */

typedef struct waiter {
    int64_t seq;
    bool answered;
    int8_t result;
} waiter_t;

static void on_reply(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    waiter_t *w = user;
    hl_bus_reply_t r;
    /* requests go one at a time, so the first answer with the seq is this request's */
    if (!w->answered && hl_bus_decode_reply(rbuf->data, rbuf->data_size, &r, NULL) == HL_OK &&
        r.seq == w->seq) {
        w->answered = true;
        w->result = r.result;
    }
}

static int64_t now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static int64_t mono_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* How long a SAVE may wait for its answer: houghlocd writes the map for requests at most
 * once per 5 s, and answers a SAVE that comes sooner once the 5 s are over. */
#define SAVE_WAIT_S 7.0

/* Publishes @p r and waits for its REPLY. @return false on an LCM error. */
static bool ask(lcm_t *lcm, const char *channel, const forge_req_t *r, waiter_t *w,
                double timeout_s)
{
    *w = (waiter_t){ .seq = r->seq };
    if (r->waits_for_save && timeout_s < SAVE_WAIT_S)
        timeout_s = SAVE_WAIT_S;
    if (lcm_publish(lcm, channel, r->bytes, (unsigned)r->len) != 0)
        return fprintf(stderr, "%s: cannot publish on %s\n", PROG, channel), false;
    int64_t deadline = mono_ms() + (int64_t)(timeout_s * 1000);
    while (!w->answered) {
        int64_t left = deadline - mono_ms();
        if (left <= 0)
            return true;
        struct pollfd p = { .fd = lcm_get_fileno(lcm), .events = POLLIN };
        int n = poll(&p, 1, (int)left);
        if (n < 0 && errno != EINTR)
            return fprintf(stderr, "%s: poll: %s\n", PROG, strerror(errno)), false;
        if (n > 0 && lcm_handle(lcm) != 0)
            return fprintf(stderr, "%s: LCM stopped receiving\n", PROG), false;
    }
    return true;
}

/* ---- the trial ----------------------------------------------------------------------- */

typedef struct tally {
    long sent[FORGE_KINDS], right[FORGE_KINDS], no_reply, wrong_shown;
} tally_t;

static void record(tally_t *t, const forge_req_t *r, const waiter_t *w, long n)
{
    t->sent[r->kind]++;
    if (w->answered && w->result == r->expect) {
        t->right[r->kind]++;
        return;
    }
    t->no_reply += !w->answered;
    if (t->wrong_shown++ < SHOW_WRONG)
        fprintf(stderr, "%s: request %ld, %s (%s) on %s with seq %lld: wanted %s, got %s\n",
                PROG, n, forge_kind_name(r->kind), r->what,
                r->command ? HL_CHANNEL_COMMAND : HL_CHANNEL_DESTINATION, (long long)r->seq,
                hl_bus_reply_name(r->expect),
                w->answered ? hl_bus_reply_name(w->result) : "no reply");
}

static void shuffle(hl_rng_t *rng, forge_kind_t *k, int n)
{
    for (int i = n - 1; i > 0; i--) {
        int j = (int)hl_rng_below(rng, (uint32_t)i + 1);
        forge_kind_t t = k[i];
        k[i] = k[j];
        k[j] = t;
    }
}

static void channel_regex(const char *name, char *out, size_t cap)
{
    size_t n = 0;
    for (const char *c = name; *c && n + 3 < cap; c++) {
        if (*c == '.')
            out[n++] = '\\';
        out[n++] = *c;
    }
    out[n] = '\0';
}

static int run(forge_t *f, lcm_t *lcm, const options_t *o, tally_t *t)
{
    char dest_ch[HL_BUS_CHANNEL_MAX], cmd_ch[HL_BUS_CHANNEL_MAX], reply_ch[HL_BUS_CHANNEL_MAX];
    char regex[2 * HL_BUS_CHANNEL_MAX];
    hl_bus_channel(o->prefix, HL_CHANNEL_DESTINATION, dest_ch);
    hl_bus_channel(o->prefix, HL_CHANNEL_COMMAND, cmd_ch);
    hl_bus_channel(o->prefix, HL_CHANNEL_REPLY, reply_ch);
    channel_regex(reply_ch, regex, sizeof regex);
    waiter_t w;
    if (!lcm_subscribe(lcm, regex, on_reply, &w))
        return fprintf(stderr, "%s: cannot subscribe to %s\n", PROG, reply_ch), 1;

    static forge_req_t r;   /* a forge_req_t is small, but the generator state is not */
    long n = 0;
    /* a valid destination and command first, so that there is something to replay */
    forge_kind_t round[] = { FORGE_VALID, FORGE_VALID, FORGE_FORGED, FORGE_REPLAYED,
                             FORGE_STALE, FORGE_UNSIGNED, FORGE_FENCE };
    const int per_round = (int)(sizeof round / sizeof round[0]);
    for (long i = -1; i < o->rounds; i++) {
        int count = i < 0 ? 2 : per_round;
        if (i >= 0)
            shuffle(&f->rng, round, per_round);
        for (int j = 0; j < count; j++) {
            forge_make(f, i < 0 ? FORGE_VALID : round[j], &r);
            if (r.len <= 0)
                return fprintf(stderr, "%s: a request did not encode (a bug)\n", PROG), 1;
            if (!ask(lcm, r.command ? cmd_ch : dest_ch, &r, &w, o->timeout_s))
                return 1;
            record(t, &r, &w, ++n);
            if (w.answered)
                forge_answered(f, &r, w.result);
        }
    }
    return 0;
}

/* ---- --cross-prefix: requests signed for another robot's channels ------------------- */

static int cross_prefix(forge_t *f, lcm_t *lcm, const options_t *o)
{
    char dest_ch[HL_BUS_CHANNEL_MAX], cmd_ch[HL_BUS_CHANNEL_MAX], reply_ch[HL_BUS_CHANNEL_MAX];
    char regex[2 * HL_BUS_CHANNEL_MAX];
    hl_bus_channel(o->prefix, HL_CHANNEL_DESTINATION, dest_ch);
    hl_bus_channel(o->prefix, HL_CHANNEL_COMMAND, cmd_ch);
    hl_bus_channel(o->prefix, HL_CHANNEL_REPLY, reply_ch);
    channel_regex(reply_ch, regex, sizeof regex);
    waiter_t w;
    if (!lcm_subscribe(lcm, regex, on_reply, &w))
        return fprintf(stderr, "%s: cannot subscribe to %s\n", PROG, reply_ch), 1;
    static forge_req_t r;
    long accepted = 0, no_reply = 0;
    for (long i = 0; i < o->rounds; i++) {
        /* valid in every way for the robot on cross_prefix: its key, fresh seqs (the
         * clock: above whatever this daemon took before), inside the fence */
        forge_make(f, FORGE_VALID, &r);
        if (!ask(lcm, r.command ? cmd_ch : dest_ch, &r, &w, o->timeout_s))
            return 1;
        f->last_seq = r.seq;    /* each the next: a refusal is then never a replay's */
        if (!w.answered)
            no_reply++;
        else if (w.result != HL_BUS_REPLY_REJECTED_AUTH) {
            accepted++;
            fprintf(stderr, "%s: a request signed for prefix '%s' was answered %s on '%s'\n",
                    PROG, o->cross_prefix, hl_bus_reply_name(w.result), o->prefix);
        }
    }
    printf("forge cross_prefix accepted=%ld/%ld no_reply=%ld\n", accepted, o->rounds, no_reply);
    return accepted == 0 && no_reply == 0 ? 0 : 1;
}

/* ---- --forge-replies: false answers to the clients ------------------------------------ */

typedef struct replier {
    lcm_t *lcm;
    const forge_t *f;
    char reply_ch[HL_BUS_CHANNEL_MAX];
    long requests, forged;
} replier_t;

static void forge_reply(replier_t *p, int64_t seq, bool command)
{
    static const char other_prefix[] = "another-robot/";
    for (int variant = 0; variant < 3; variant++) {
        hl_bus_reply_t r = { .utime = 1, .seq = seq,
                             .result = command ? HL_BUS_REPLY_ACCEPTED : HL_BUS_REPLY_ARRIVED };
        snprintf(r.message, sizeof r.message, "forged");
        if (variant == 1)
            hl_auth_sign_reply(&p->f->wrong_key, p->f->prefix, &r);
        else if (variant == 2)
            hl_auth_sign_reply(&p->f->key, other_prefix, &r);
        uint8_t buf[HL_BUS_REPLY_MAX_BYTES];
        int len = hl_bus_encode_reply(&r, buf, sizeof buf);
        if (len > 0 && lcm_publish(p->lcm, p->reply_ch, buf, (unsigned)len) == 0)
            p->forged++;
    }
}

static void on_request(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    replier_t *p = user;
    hl_bus_destination_t d;
    hl_bus_command_t c;
    bool command = strstr(channel, HL_CHANNEL_COMMAND) != NULL;
    int64_t seq;
    if (!command && hl_bus_decode_destination(rbuf->data, rbuf->data_size, &d, NULL) == HL_OK)
        seq = d.seq;
    else if (command && hl_bus_decode_command(rbuf->data, rbuf->data_size, &c, NULL) == HL_OK)
        seq = c.seq;
    else
        return;
    p->requests++;
    forge_reply(p, seq, command);
}

static int forge_replies(const forge_t *f, lcm_t *lcm, const options_t *o)
{
    replier_t p = { .lcm = lcm, .f = f };
    char ch[HL_BUS_CHANNEL_MAX], regex[2 * HL_BUS_CHANNEL_MAX];
    hl_bus_channel(o->prefix, HL_CHANNEL_REPLY, p.reply_ch);
    const char *const inputs[] = { HL_CHANNEL_DESTINATION, HL_CHANNEL_COMMAND };
    for (int i = 0; i < 2; i++) {
        hl_bus_channel(o->prefix, inputs[i], ch);
        channel_regex(ch, regex, sizeof regex);
        if (!lcm_subscribe(lcm, regex, on_request, &p))
            return fprintf(stderr, "%s: cannot subscribe to %s\n", PROG, ch), 1;
    }
    int64_t end = mono_ms() + (int64_t)(o->forge_replies_s * 1000);
    for (int64_t left; (left = end - mono_ms()) > 0;) {
        struct pollfd pf = { .fd = lcm_get_fileno(lcm), .events = POLLIN };
        int n = poll(&pf, 1, (int)left);
        if (n < 0 && errno != EINTR)
            return fprintf(stderr, "%s: poll: %s\n", PROG, strerror(errno)), 1;
        if (n > 0 && lcm_handle(lcm) != 0)
            return fprintf(stderr, "%s: LCM stopped receiving\n", PROG), 1;
    }
    printf("forge replies requests=%ld forged=%ld\n", p.requests, p.forged);
    return 0;
}

int main(int argc, char **argv)
{
    options_t o = { .prefix = "", .rounds = 60, .seed = 1, .timeout_s = 2.0, .fence_m = 10.0 };
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0)
        return rc;
    hl_auth_key_t key;
    char why[HL_KEYFILE_WHY_LEN];
    if (hl_keyfile_load(o.key_file, &key, why) != HL_OK)
        return fprintf(stderr, "%s: %s\n", PROG, why), 1;
    static forge_t f;
    if (!forge_init(&f, &key, o.cross_prefix ? o.cross_prefix : o.prefix, o.seed, o.fence_m))
        return fprintf(stderr, "%s: libsodium does not start\n", PROG), 1;
    lcm_t *lcm = lcm_create(o.url);
    if (!lcm)
        return fprintf(stderr, "%s: cannot open LCM at %s\n", PROG, o.url), 1;
    /* seqs follow the wall clock, as houghloc-goto's do: fresh whatever the daemon took
     * before (its request state outlives its map), and never ahead of its clock */
    f.last_seq = now_us() - 1000000;
    if (o.cross_prefix || o.forge_replies_s > 0) {
        rc = o.cross_prefix ? cross_prefix(&f, lcm, &o) : forge_replies(&f, lcm, &o);
        lcm_destroy(lcm);
        return rc;
    }
    tally_t t = { .no_reply = 0 };
    rc = run(&f, lcm, &o, &t);
    lcm_destroy(lcm);
    if (rc != 0)
        return rc;

    long bad = 0, bad_right = 0;
    printf("forge");
    for (int k = 0; k < FORGE_KINDS; k++) {
        printf(" %s=%ld/%ld", forge_kind_name((forge_kind_t)k), t.right[k], t.sent[k]);
        if (k != FORGE_VALID) {
            bad += t.sent[k];
            bad_right += t.right[k];
        }
    }
    printf(" bad_rejected=%ld/%ld valid_accepted=%ld/%ld no_reply=%ld\n", bad_right, bad,
           t.right[FORGE_VALID], t.sent[FORGE_VALID], t.no_reply);
    return bad_right == bad && t.right[FORGE_VALID] == t.sent[FORGE_VALID] ? 0 : 1;
}
