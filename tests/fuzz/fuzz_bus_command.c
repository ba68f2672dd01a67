/*
 * fuzz_bus_command.c - hl_bus_decode_command (include/bus/houghloc/bus.h): one COMMAND message as
 * received. A decoded message must re-encode to the input's bytes (see fuzz_bus.h).
 */
#include "fuzz_bus.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hl_bus_command_t m;
    char why[HL_BUS_WHY_LEN] = "";
    hl_status_t st = hl_bus_decode_command(data, size, &m, why);
    if (st != HL_OK) {
        fuzz_bus_refused(st, why);
        return 0;
    }
    /* The ranges bus.h gives. */
    FUZZ_CHECK(m.utime >= 0 && m.seq > 0 && fuzz_bus_xy_ok(m.pose.x_mm, m.pose.y_mm));
    FUZZ_CHECK(m.kind >= HL_BUS_COMMAND_SET_POSE && m.kind <= HL_BUS_COMMAND_STOP);
    uint8_t out[HL_BUS_COMMAND_BYTES];
    fuzz_bus_same(hl_bus_encode_command(&m, out, sizeof out), out, data, size);
    return 0;
}
