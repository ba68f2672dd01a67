/*
 * fuzz_bus_pose.c - hl_bus_decode_pose (include/bus/houghloc/bus.h): one POSE message as
 * received. A decoded message must re-encode to the input's bytes (see fuzz_bus.h).
 */
#include "fuzz_bus.h"
#include "houghloc/slam.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hl_bus_pose_t m;
    char why[HL_BUS_WHY_LEN] = "";
    hl_status_t st = hl_bus_decode_pose(data, size, &m, why);
    if (st != HL_OK) {
        fuzz_bus_refused(st, why);
        return 0;
    }
    /* The ranges bus.h gives. */
    FUZZ_CHECK(m.utime >= 0 && m.scan_seq >= 0 && fuzz_bus_xy_ok(m.pose.x_mm, m.pose.y_mm));
    FUZZ_CHECK(m.status >= HL_BUS_POSE_ACCEPTED && m.status <= HL_BUS_POSE_LOST);
    FUZZ_CHECK(m.confidence >= 0.0f && m.confidence <= 1.0f);
    FUZZ_CHECK(m.peak >= 0 && m.second_peak >= 0 && m.votes >= 0);
    FUZZ_CHECK(m.search_score >= 0.0f && m.search_score <= 1.0f);
    FUZZ_CHECK(m.runner_up_score >= 0.0f && m.runner_up_score <= 1.0f);
    FUZZ_CHECK(fuzz_bus_xy_ok(m.runner_up.x_mm, m.runner_up.y_mm));
    uint8_t out[HL_BUS_POSE_BYTES];
    int n = hl_bus_encode_pose(&m, out, sizeof out);
    if (size == HL_BUS_POSE_BYTES) {
        fuzz_bus_same(n, out, data, size);
        return 0;
    }
    /* the older layout (codec_pose.c): its fields come back the same, the search's zero,
     * and the current layout is written */
    FUZZ_CHECK(n == HL_BUS_POSE_BYTES && size == HL_BUS_POSE_BYTES - 18);
    FUZZ_CHECK(memcmp(out + 8, data + 8, size - 8) == 0);
    FUZZ_CHECK(m.search_score == 0.0f && m.runner_up_score == 0.0f);
    FUZZ_CHECK(m.runner_up.x_mm == 0 && m.runner_up.y_mm == 0 && m.runner_up.theta == 0);
    return 0;
}
