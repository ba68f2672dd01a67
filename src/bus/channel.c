/* channel.c - channel names with a deployment prefix (see hl_bus_channel in bus.h). */
#include "houghloc/bus.h"

#include <string.h>

/* Letters, digits and "_-./": safe in a shell word and a log file's channel list. liblcm
 * compiles a subscription as a regular expression, where a '.' of the prefix matches
 * any character: harmless, since every other character matches only itself. */
static bool name_char_ok(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           c == '_' || c == '-' || c == '.' || c == '/';
}

static bool name_ok(const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!name_char_ok(s[i]))
            return false;
    return true;
}

bool hl_bus_channel(const char *prefix, const char *base, char *out)
{
    if (!out || !base)
        return false;
    if (!prefix)
        prefix = "";
    size_t np = strnlen(prefix, HL_BUS_PREFIX_MAX + 1);
    size_t nb = strnlen(base, HL_BUS_CHANNEL_MAX);
    if (np > HL_BUS_PREFIX_MAX || nb == 0 || np + nb >= HL_BUS_CHANNEL_MAX)
        return false;
    if (!name_ok(prefix, np) || !name_ok(base, nb))
        return false;
    memcpy(out, prefix, np);
    memcpy(out + np, base, nb);
    out[np + nb] = '\0';
    return true;
}
