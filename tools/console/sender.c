/* sender.c - stamping, signing and publishing the console's destinations (sender.h). */
#include "sender.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

#include <sodium.h>

hl_status_t sender_init(sender_t *s, lcm_t *lcm, const char *prefix, const char *key_file,
                        char *why)
{
    *s = (sender_t){ .lcm = lcm };
    if (!hl_bus_channel(prefix, HL_CHANNEL_DESTINATION, s->channel))
        return HL_ERR_ARG; /* the command line checked the prefix already */
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

hl_status_t sender_send(sender_t *s, hl_bus_destination_t *d)
{
    /* The wall clock in microseconds, and above the last one even if the clock stepped
     * back: the daemon accepts only increasing seqs (REJECTED_REPLAY otherwise). */
    int64_t now = wall_us();
    d->seq = now > s->last_seq ? now : s->last_seq + 1;
    d->utime = now;
    memset(d->mac, 0, sizeof d->mac);
    if (s->has_key && !hl_auth_sign_destination(&s->key, d))
        return HL_ERR_RANGE;
    uint8_t buf[HL_BUS_DESTINATION_BYTES];
    int len = hl_bus_encode_destination(d, buf, sizeof buf);
    if (len < 0)
        return HL_ERR_RANGE;
    if (lcm_publish(s->lcm, s->channel, buf, (unsigned)len) != 0)
        return HL_ERR_OS;
    s->last_seq = d->seq;
    s->mine[s->next] = d->seq;
    s->next = (s->next + 1) % SENDER_KEPT;
    s->sent++;
    return HL_OK;
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
