/*
 * main.c - houghloc-console: houghlocd's operator console in a browser.
 *
 * One thread, one pselect() over the LCM socket and libmicrohttpd's sockets: LCM
 * messages are decoded by the bus codecs, turned into JSON (bridge.c) and pushed to
 * every open page (hub.c); the pages' clicks come back as POST /destination (http.c)
 * and leave as DESTINATION messages, their Stop button and Escape key as POST /stop
 * and leave as a STOP COMMAND (sender.c). Nothing runs between events: the only timers
 * are libmicrohttpd's connection timeouts, the gate's request deadlines (gate.h) and a
 * keepalive every 15 s. Who may use it: access.h; what it holds: hub.h and gate.h.
 */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/select.h>
#include <time.h>

#include <lcm/lcm.h>

#include "access.h"
#include "args.h"
#include "bridge.h"
#include "houghloc/version.h"
#include "http.h"
#include "hub.h"
#include "sender.h"
#include "truth_frame.h"

#define KEEPALIVE_MS 15000
#define LOG(...) (fprintf(stderr, PROG ": " __VA_ARGS__), fputc('\n', stderr))

enum { CH_MAP, CH_POSE, CH_STATUS, CH_REPLY, CH_TRUTH, CH_PATH, CH_COUNT };
static const char *const base_names[CH_COUNT] = {
    HL_CHANNEL_MAP, HL_CHANNEL_POSE, HL_CHANNEL_STATUS, HL_CHANNEL_REPLY,
    HL_CHANNEL_GROUND_TRUTH, HL_CHANNEL_PATH,
};

typedef struct console {
    console_options_t opt;
    access_policy_t policy;
    lcm_t *lcm;
    hub_t hub;
    http_t http;
    sender_t sender;
    hl_vector_t *vectors;       /* the MAP decoder's storage, grown to the largest map */
    uint32_t max_vectors;
    jbuf_t json;                /* reused for every message */
    char channel[CH_COUNT][HL_BUS_CHANNEL_MAX];
    unsigned long undecodable[CH_COUNT];
    unsigned long forged_replies;   /* with a key: REPLY messages whose MAC is wrong */
    hl_truth_frame_t truth_frame;   /* GROUND_TRUTH (the simulator's world) to the map */
} console_t;

static volatile sig_atomic_t stop_signal;

static void on_signal(int sig)
{
    stop_signal = sig;
}

/* A message that does not decode: logged the first time on its channel, then counted. */
static void undecodable(console_t *c, int ch, const char *why)
{
    if (c->undecodable[ch]++ == 0)
        LOG("%s: a message does not decode (%s); further ones are only counted",
            c->channel[ch], why);
}

static void publish_json(console_t *c, hub_kind_t k, int32_t x, int32_t y)
{
    if (c->json.failed || !hub_publish(&c->hub, k, c->json.data, c->json.len, x, y))
        LOG("out of memory: a %s event was dropped", hub_kind_name(k));
}

static void on_message(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    console_t *c = user;
    int ch = 0;
    while (ch < CH_COUNT && strcmp(channel, c->channel[ch]) != 0)
        ch++;
    char why[HL_BUS_WHY_LEN];
    jbuf_reset(&c->json);
    if (ch == CH_MAP) {
        /* a map of n vectors is 28 + 12 n bytes: room for what this message can hold */
        uint32_t need = rbuf->data_size / 12 + 1;
        if (need > HL_MAP_MAX_CAPACITY)
            need = HL_MAP_MAX_CAPACITY;
        if (need > c->max_vectors) {
            hl_vector_t *v = realloc(c->vectors, need * sizeof *v);
            if (!v) {
                undecodable(c, ch, "out of memory");
                return;
            }
            c->vectors = v;
            c->max_vectors = need;
        }
        hl_bus_map_t m = { .vectors = c->vectors, .max_vectors = c->max_vectors };
        if (hl_bus_decode_map(rbuf->data, rbuf->data_size, &m, why) != HL_OK)
            return undecodable(c, ch, why);
        bridge_map(&c->json, &m);
        publish_json(c, HUB_MAP, 0, 0);
    } else if (ch == CH_POSE || ch == CH_TRUTH) {
        hl_bus_pose_t p;
        if (hl_bus_decode_pose(rbuf->data, rbuf->data_size, &p, why) != HL_OK)
            return undecodable(c, ch, why);
        /* drawn beside the estimate, so in its frame: truth_frame.h */
        if (ch == CH_TRUTH && !hl_truth_frame_map(&c->truth_frame, p.pose, &p.pose))
            return undecodable(c, ch, "the true pose lies beyond the map's range from "
                               "--start");
        bridge_pose(&c->json, &p);
        publish_json(c, ch == CH_POSE ? HUB_POSE : HUB_TRUTH, p.pose.x_mm, p.pose.y_mm);
    } else if (ch == CH_STATUS) {
        hl_bus_status_t s;
        if (hl_bus_decode_status(rbuf->data, rbuf->data_size, &s, why) != HL_OK)
            return undecodable(c, ch, why);
        bridge_status(&c->json, &s);
        publish_json(c, HUB_STATUS, 0, 0);
    } else if (ch == CH_REPLY) {
        hl_bus_reply_t r;
        if (hl_bus_decode_reply(rbuf->data, rbuf->data_size, &r, why) != HL_OK)
            return undecodable(c, ch, why);
        /* with a key, only the daemon's own answers reach the pages: a forged ARRIVED must
         * not tell the operator that the robot got there */
        if (!sender_reply_authentic(&c->sender, &r)) {
            if (c->forged_replies++ == 0)
                LOG("%s: ignoring a reply to seq %lld without a valid MAC (forged, or from a "
                    "daemon without this key); further ones are only counted", c->channel[ch],
                    (long long)r.seq);
            return;
        }
        bool mine = sender_is_mine(&c->sender, r.seq);
        if (mine)
            LOG("reply to seq %lld: %s%s%s", (long long)r.seq, hl_bus_reply_name(r.result),
                r.message[0] ? ": " : "", r.message);
        bridge_reply(&c->json, &r, mine);
        publish_json(c, HUB_REPLY, 0, 0);
    } else if (ch == CH_PATH) {
        hl_bus_path_t p;
        if (hl_bus_decode_path(rbuf->data, rbuf->data_size, &p, why) != HL_OK)
            return undecodable(c, ch, why);
        bridge_path(&c->json, &p);
        publish_json(c, HUB_PATH, 0, 0);
    }
}

/* POST /destination, parsed: publish it, tell every page, answer the one that asked. */
static unsigned on_destination(void *user, const destreq_t *r, jbuf_t *answer)
{
    console_t *c = user;
    hl_bus_destination_t d = destreq_message(r);
    hl_status_t st = sender_send(&c->sender, &d);
    if (st != HL_OK) {
        LOG("a destination could not be %s", st == HL_ERR_OS ? "published" : "encoded");
        jbuf_puts(answer, st == HL_ERR_OS ? "{\"error\":\"LCM refused to publish\"}"
                                          : "{\"error\":\"the destination does not encode\"}");
        return st == HL_ERR_OS ? 503 : 400;
    }
    LOG("DESTINATION seq %lld to (%.3f, %.3f) m%s, %s", (long long)d.seq, d.x_mm / 1000.0,
        d.y_mm / 1000.0, d.has_heading ? " with a heading" : "",
        c->sender.has_key ? "signed" : "unsigned");
    jbuf_reset(&c->json);
    bridge_sent(&c->json, &d, c->sender.has_key);
    publish_json(c, HUB_SENT, 0, 0);
    bridge_sent(answer, &d, c->sender.has_key);
    return 202;
}

/* POST /stop: one STOP on COMMAND at once, and its seq to the page that asked. */
static unsigned on_stop_robot(void *user, jbuf_t *answer)
{
    console_t *c = user;
    hl_bus_command_t cmd;
    hl_status_t st = sender_stop(&c->sender, &cmd);
    if (st != HL_OK) {
        LOG("a STOP could not be %s", st == HL_ERR_OS ? "published" : "encoded");
        jbuf_puts(answer, st == HL_ERR_OS ? "{\"error\":\"LCM refused to publish\"}"
                                          : "{\"error\":\"the STOP does not encode\"}");
        return st == HL_ERR_OS ? 503 : 500;
    }
    LOG("STOP seq %lld, %s", (long long)cmd.seq, c->sender.has_key ? "signed" : "unsigned");
    bridge_stop(answer, &cmd, c->sender.has_key);
    return 202;
}

static void hello(console_t *c)
{
    jbuf_reset(&c->json);
    jbuf_puts(&c->json, "{\"version\":");
    jbuf_str(&c->json, HL_VERSION);
    jbuf_puts(&c->json, ",\"prefix\":");
    jbuf_str(&c->json, c->opt.req.prefix);
    jbuf_puts(&c->json, c->sender.has_key ? ",\"signed\":true" : ",\"signed\":false");
    jbuf_puts(&c->json, c->opt.ground_truth ? ",\"ground_truth\":true}" : ",\"ground_truth\":false}");
    publish_json(c, HUB_HELLO, 0, 0);
}

static int64_t now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* The loop: until a signal, or until LCM fails. @return the exit code. */
static int run(console_t *c, const sigset_t *unblocked)
{
    const int lfd = lcm_get_fileno(c->lcm);
    int64_t keepalive_at = now_ms() + KEEPALIVE_MS;
    while (!stop_signal) {
        fd_set rs, ws, es;
        FD_ZERO(&rs);
        FD_ZERO(&ws);
        FD_ZERO(&es);
        int max_fd = lfd;
        FD_SET(lfd, &rs);
        if (!http_fdset(&c->http, &rs, &ws, &es, &max_fd)) {
            LOG("the web server's sockets do not fit select()");
            return 1;
        }
        long wait_ms = (long)(keepalive_at - now_ms());
        long http_ms = http_timeout_ms(&c->http);
        if (http_ms >= 0 && http_ms < wait_ms)
            wait_ms = http_ms;
        if (wait_ms < 0)
            wait_ms = 0;
        struct timespec ts = { .tv_sec = wait_ms / 1000, .tv_nsec = wait_ms % 1000 * 1000000 };
        int n = pselect(max_fd + 1, &rs, &ws, &es, &ts, unblocked);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0) {
            LOG("select: %s", strerror(errno));
            return 1;
        }
        if (n > 0 && FD_ISSET(lfd, &rs) && lcm_handle(c->lcm) != 0) {
            LOG("LCM stopped receiving");
            return 1;
        }
        http_run(&c->http, &rs, &ws, &es);
        if (now_ms() >= keepalive_at) {
            hub_keepalive(&c->hub);
            keepalive_at = now_ms() + KEEPALIVE_MS;
        }
    }
    LOG("stopping on signal %d", (int)stop_signal);
    return 0;
}

/* Everything that can be refused, in order; @return WAITING or the exit code. */
static int start(console_t *c)
{
    hl_truth_frame_init(&c->truth_frame, c->opt.start);
    char why[HL_KEYFILE_WHY_LEN > ACCESS_WHY_LEN ? HL_KEYFILE_WHY_LEN : ACCESS_WHY_LEN];
    char token[ACCESS_TOKEN_MAX + 1];
    if (c->opt.token_file ? access_token_load(c->opt.token_file, token, why) != HL_OK
                          : !access_token_generate(token)) {
        LOG("%s", c->opt.token_file ? why : "libsodium does not initialize");
        return EXIT_ERROR;
    }
    if (!access_policy_init(&c->policy, c->opt.loopback, c->opt.port, c->opt.host, token)) {
        LOG("libsodium does not initialize");
        return EXIT_ERROR;
    }
    if (c->opt.token_out && access_token_save(c->opt.token_out, token, why) != HL_OK) {
        LOG("%s", why);
        return EXIT_ERROR;
    }
    const char *url = c->opt.req.url;
    if (!url) {
        const char *env = getenv("LCM_DEFAULT_URL");
        url = env && *env ? env : REQ_DEFAULT_URL;
    }
    c->lcm = lcm_create(url);
    if (!c->lcm) {
        LOG("cannot start LCM with URL \"%s\"", url);
        return EXIT_ERROR;
    }
    if (sender_init(&c->sender, c->lcm, c->opt.req.prefix, c->opt.req.key_file, why) != HL_OK) {
        LOG("%s", why);
        return EXIT_ERROR;
    }
    for (int ch = 0; ch < CH_COUNT; ch++) {
        if (!hl_bus_channel(c->opt.req.prefix, base_names[ch], c->channel[ch]))
            return EXIT_USAGE; /* the prefix was checked with the longest name */
        if ((ch != CH_TRUTH || c->opt.ground_truth) &&
            !lcm_subscribe(c->lcm, c->channel[ch], on_message, c)) {
            LOG("cannot subscribe to %s", c->channel[ch]);
            return EXIT_ERROR;
        }
    }
    if (!hub_init(&c->hub, http_wake, &c->http)) {
        LOG("out of memory");
        return EXIT_ERROR;
    }
    hello(c);
    if (!http_start(&c->http, (const struct sockaddr *)&c->opt.addr, c->opt.addrlen, &c->hub,
                    &c->policy, on_destination, on_stop_robot, c, why)) {
        LOG("%s", why);
        return EXIT_ERROR;
    }
    /* The token goes only where the operator who started the console reads: this
     * terminal, or the file --token-out made (access.h). */
    char shown[ACCESS_WHY_LEN];
    if (c->opt.token_out)
        snprintf(shown, sizeof shown, "<the token in %s>", c->opt.token_out);
    else
        snprintf(shown, sizeof shown, "%s", c->policy.token);
    LOG("serving http://%s:%u/?token=%s on LCM %s%s%s, destinations %s", c->opt.host,
        (unsigned)c->opt.port, shown, url, c->opt.req.prefix[0] ? " prefix " : "",
        c->opt.req.prefix, c->sender.has_key ? "signed" : "unsigned");
    return WAITING;
}

int main(int argc, char **argv)
{
    static console_t c;
    c.opt = (console_options_t){ .req = REQ_OPTIONS_DEFAULT };
    int rc = console_parse_args(argc, argv, &c.opt);
    if (rc != WAITING)
        return rc;
    /* SIGINT and SIGTERM are taken only inside pselect, so none is missed between the
     * flag's test and the wait */
    sigset_t block, unblocked;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigprocmask(SIG_BLOCK, &block, &unblocked);
    struct sigaction sa = { .sa_handler = on_signal };
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);
    jbuf_init(&c.json, 0);

    rc = start(&c);
    if (rc == WAITING)
        rc = run(&c, &unblocked);
    http_stop(&c.http);
    for (int ch = 0; ch < CH_COUNT; ch++)
        if (c.undecodable[ch])
            LOG("%s: %lu messages did not decode", c.channel[ch], c.undecodable[ch]);
    if (c.forged_replies)
        LOG("%s: %lu replies without a valid MAC were ignored", c.channel[CH_REPLY],
            c.forged_replies);
    if (c.hub.cut_off)
        LOG("%llu pages were cut off for reading too slowly", (unsigned long long)c.hub.cut_off);
    if (c.http.gate.displaced || c.http.gate.expired || c.http.gate.refused)
        LOG("connections: %llu closed without a request in %d s, %llu displaced by a "
            "newcomer, %llu refused with every place serving",
            (unsigned long long)c.http.gate.expired, GATE_HEADER_MS / 1000,
            (unsigned long long)c.http.gate.displaced, (unsigned long long)c.http.gate.refused);
    sender_free(&c.sender);
    hub_free(&c.hub);
    if (c.lcm)
        lcm_destroy(c.lcm);
    free(c.vectors);
    jbuf_free(&c.json);
    return rc;
}
