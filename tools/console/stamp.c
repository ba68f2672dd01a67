/* stamp.c - stamping, signing and encoding the console's requests (stamp.h). */
#include "stamp.h"

#include <string.h>

int64_t stamp_seq(int64_t now_us, int64_t last_seq)
{
    if (last_seq < 0)
        last_seq = 0;
    return now_us > last_seq ? now_us : last_seq + 1;
}

int stamp_destination(hl_bus_destination_t *d, int64_t now_us, int64_t seq,
                      const hl_auth_key_t *key, const char *prefix, uint8_t *buf, size_t cap)
{
    d->utime = now_us;
    d->seq = seq;
    memset(d->mac, 0, sizeof d->mac);
    if (key && !hl_auth_sign_destination(key, prefix, d))
        return -1;
    return hl_bus_encode_destination(d, buf, cap);
}

int stamp_stop(hl_bus_command_t *c, int64_t now_us, int64_t seq, const hl_auth_key_t *key,
               const char *prefix, uint8_t *buf, size_t cap)
{
    *c = (hl_bus_command_t){ .utime = now_us, .seq = seq, .kind = HL_BUS_COMMAND_STOP };
    if (key && !hl_auth_sign_command(key, prefix, c))
        return -1;
    return hl_bus_encode_command(c, buf, cap);
}
