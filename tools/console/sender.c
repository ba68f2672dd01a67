/* sender.c - stamping, signing and publishing the console's requests (sender.h). */
#include "sender.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

#include <sodium.h>

#include "stamp.h"

hl_status_t sender_init(sender_t *s, lcm_t *lcm, const char *prefix, const char *key_file,
                        char *why)
{
    *s = (sender_t){ .lcm = lcm };
    if (!hl_bus_channel(prefix, HL_CHANNEL_DESTINATION, s->channel) ||
        !hl_bus_channel(prefix, HL_CHANNEL_COMMAND, s->command_channel))
        return HL_ERR_ARG; /* the command line checked the prefix already */
    snprintf(s->prefix, sizeof s->prefix, "%s", prefix);
    if (!key_file)
        return HL_OK;
    if (!hl_auth_init()) {
        snprintf(why, HL_KEYFILE_WHY_LEN, "libsodium does not initialize");
        return HL_ERR_OS;
    }
    hl_status_t st = hl_keyfile_load(key_file, &s->key, why);
    s->has_key = st == HL_OK;
    return st;
}

static int64_t wall_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

/* Publishes @p len bytes of a request stamped @p seq and remembers the seq as mine. */
static hl_status_t publish(sender_t *s, const char *channel, const uint8_t *buf, int len,
                           int64_t seq)
{
    if (len < 0)
        return HL_ERR_RANGE;
    if (lcm_publish(s->lcm, channel, buf, (unsigned)len) != 0)
        return HL_ERR_OS;
    s->last_seq = seq;
    s->mine[s->next] = seq;
    s->next = (s->next + 1) % SENDER_KEPT;
    return HL_OK;
}

hl_status_t sender_send(sender_t *s, hl_bus_destination_t *d)
{
    /* The daemon accepts only increasing seqs (REJECTED_REPLAY otherwise): stamp_seq. */
    int64_t now = wall_us();
    uint8_t buf[STAMP_MAX_BYTES];
    int len = stamp_destination(d, now, stamp_seq(now, s->last_seq),
                                s->has_key ? &s->key : NULL, s->prefix, buf, sizeof buf);
    hl_status_t st = publish(s, s->channel, buf, len, d->seq);
    if (st == HL_OK)
        s->sent++;
    return st;
}

hl_status_t sender_stop(sender_t *s, hl_bus_command_t *c)
{
    int64_t now = wall_us();
    uint8_t buf[STAMP_MAX_BYTES];
    int len = stamp_stop(c, now, stamp_seq(now, s->last_seq), s->has_key ? &s->key : NULL,
                         s->prefix, buf, sizeof buf);
    hl_status_t st = publish(s, s->command_channel, buf, len, c->seq);
    if (st == HL_OK)
        s->stops++;
    return st;
}

bool sender_reply_authentic(const sender_t *s, const hl_bus_reply_t *r)
{
    return !s->has_key || hl_auth_check_reply(&s->key, s->prefix, r);
}

bool sender_is_mine(const sender_t *s, int64_t seq)
{
    for (unsigned i = 0; i < SENDER_KEPT; i++)
        if (s->mine[i] == seq && seq > 0)
            return true;
    return false;
}

void sender_free(sender_t *s)
{
    sodium_memzero(&s->key, sizeof s->key);
    s->has_key = false;
}
