/*
 * fuzz_bus_reply.c - hl_bus_decode_reply (include/bus/houghloc/bus.h): one REPLY message as
 * received. A decoded message must re-encode to the input's bytes (see fuzz_bus.h).
 */
#include "fuzz_bus.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hl_bus_reply_t m;
    char why[HL_BUS_WHY_LEN] = "";
    hl_status_t st = hl_bus_decode_reply(data, size, &m, why);
    if (st != HL_OK) {
        fuzz_bus_refused(st, why);
        return 0;
    }
    /* The ranges bus.h gives: any seq, a known result, a one-line message. */
    FUZZ_CHECK(m.utime >= 0);
    FUZZ_CHECK(strcmp(hl_bus_reply_name(m.result), "?") != 0);
    FUZZ_CHECK(fuzz_bus_text_ok(m.message));
    uint8_t out[HL_BUS_REPLY_MAX_BYTES];
    fuzz_bus_same(hl_bus_encode_reply(&m, out, sizeof out), out, data, size);
    return 0;
}
