/*
 * fuzz_bus_scan.c - hl_bus_decode_scan (include/bus/houghloc/bus.h): one SONAR message as
 * received. A decoded scan re-encodes to the input's bytes except for the embedded
 * odometry's utime, velocity and stopped fields, which bus.h says the encoder writes as
 * the scan's utime, 0 and true (see fuzz_bus.h).
 */
#include "fuzz_bus.h"

/* Offsets in the encoding: hash 0..7, utime 8..15, seq 16..19, then the odometry:
 * utime 20..27, x 28..31, y 32..35, heading 36..37, velocity 38..39, stopped 40. */
enum { UTIME = 8, ODO_UTIME = 20, ODO_VELOCITY = 38, ODO_STOPPED = 40 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hl_bus_scan_t *m = malloc(sizeof *m);     /* 12 KiB: off the stack */
    uint8_t *out = malloc(HL_BUS_SCAN_MAX_BYTES);
    uint8_t *want = malloc(size > 0 ? size : 1);
    FUZZ_CHECK(m && out && want);
    char why[HL_BUS_WHY_LEN] = "";
    hl_status_t st = hl_bus_decode_scan(data, size, m, why);
    if (st != HL_OK) {
        fuzz_bus_refused(st, why);
    } else {
        /* The ranges bus.h gives. */
        FUZZ_CHECK(m->utime >= 0 && m->seq >= 0);
        FUZZ_CHECK(fuzz_bus_xy_ok(m->odometry.x_mm, m->odometry.y_mm));
        FUZZ_CHECK(m->scan.count <= HL_SCAN_MAX_READINGS);
        for (uint32_t i = 0; i < m->scan.count; i++) {
            const hl_reading_t *r = &m->scan.readings[i];
            FUZZ_CHECK(r->range_mm >= 0 && r->range_mm <= HL_RANGE_MAX_MM);
            FUZZ_CHECK(r->transducer >= -1);
        }
        FUZZ_CHECK(size > ODO_STOPPED);
        memcpy(want, data, size);
        memcpy(want + ODO_UTIME, data + UTIME, 8);
        want[ODO_VELOCITY] = 0;
        want[ODO_VELOCITY + 1] = 0;
        want[ODO_STOPPED] = 1;
        fuzz_bus_same(hl_bus_encode_scan(m, out, HL_BUS_SCAN_MAX_BYTES), out, want, size);
    }
    free(want);
    free(out);
    free(m);
    return 0;
}
