/*
 * fuzz_bus_status.c - hl_bus_decode_status (include/bus/houghloc/bus.h): one STATUS message
 * as received. A decoded message must re-encode to the input's bytes (see fuzz_bus.h).
 */
#include "fuzz_bus.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hl_bus_status_t m;
    char why[HL_BUS_WHY_LEN] = "";
    hl_status_t st = hl_bus_decode_status(data, size, &m, why);
    if (st != HL_OK) {
        fuzz_bus_refused(st, why);
        return 0;
    }
    /* The ranges bus.h gives. */
    FUZZ_CHECK(m.utime >= 0);
    FUZZ_CHECK(m.state >= HL_BUS_STATE_STARTING && m.state <= HL_BUS_STATE_LOST);
    FUZZ_CHECK(m.destination_seq == -1 || m.destination_seq > 0);
    const int64_t counters[] = { m.scans, m.accepted, m.rejected_wild, m.odometry_only,
                                 m.relocalized, m.lost, m.bad_packets, m.bad_messages,
                                 m.rejected_requests, m.map_version, m.saves };
    for (size_t i = 0; i < sizeof counters / sizeof counters[0]; i++)
        FUZZ_CHECK(counters[i] >= 0);
    FUZZ_CHECK(m.compute_median_us >= 0 && m.compute_p99_us >= 0 && m.compute_samples >= 0);
    FUZZ_CHECK(m.map_vectors >= 0 && m.map_vectors <= (int32_t)HL_MAP_MAX_CAPACITY);
    FUZZ_CHECK(fuzz_bus_xy_ok(m.pose.x_mm, m.pose.y_mm));
    FUZZ_CHECK(fuzz_bus_text_ok(m.last_error));
    uint8_t out[HL_BUS_STATUS_MAX_BYTES];
    fuzz_bus_same(hl_bus_encode_status(&m, out, sizeof out), out, data, size);
    return 0;
}
