/*
 * fuzz_bus_map.c - hl_bus_decode_map (include/bus/houghloc/bus.h): one MAP message as
 * received, decoded into caller storage sized to the input (a heap block of exactly
 * that many vectors, so AddressSanitizer sees a write past it). A decoded map must
 * re-encode to the input's bytes, and storage one vector short must be refused with
 * HL_ERR_RANGE before anything is written past it (see fuzz_bus.h).
 */
#include "fuzz_bus.h"

static hl_vector_t *storage(uint32_t n)
{
    hl_vector_t *v = malloc(n > 0 ? n * sizeof *v : 1);
    FUZZ_CHECK(v != NULL);
    return v;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* A map of n vectors takes 28 + 12 n bytes: size / 12 vectors always suffice. */
    uint32_t max = (uint32_t)(size / 12u);
    hl_bus_map_t m = { .vectors = storage(max), .max_vectors = max };
    char why[HL_BUS_WHY_LEN] = "";
    hl_status_t st = hl_bus_decode_map(data, size, &m, why);
    if (st != HL_OK) {
        fuzz_bus_refused(st, why);
        free(m.vectors);
        return 0;
    }
    /* The ranges bus.h gives. */
    FUZZ_CHECK(m.utime >= 0 && m.version >= 0);
    FUZZ_CHECK(m.capacity >= 1 && m.capacity <= (int32_t)HL_MAP_MAX_CAPACITY);
    FUZZ_CHECK(m.count <= (uint32_t)m.capacity && m.count <= max);
    FUZZ_CHECK(size == hl_bus_map_bytes(m.count));
    for (uint32_t i = 0; i < m.count; i++) {
        FUZZ_CHECK(fuzz_bus_xy_ok(m.vectors[i].x_mm, m.vectors[i].y_mm));
        FUZZ_CHECK(m.vectors[i].range_mm <= HL_RANGE_MAX_MM);
    }
    uint8_t *out = malloc(size);
    FUZZ_CHECK(out != NULL);
    fuzz_bus_same(hl_bus_encode_map(&m, out, size), out, data, size);
    free(out);

    if (m.count > 0) {
        hl_bus_map_t shorter = { .vectors = storage(m.count - 1), .max_vectors = m.count - 1 };
        FUZZ_CHECK(hl_bus_decode_map(data, size, &shorter, why) == HL_ERR_RANGE);
        free(shorter.vectors);
    }
    free(m.vectors);
    return 0;
}
