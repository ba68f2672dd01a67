/*
 * codec_map.c - MAP (houghloc.map_t).
 *
 * On the wire, after the 8-byte hash: 8 utime | 8 version | 4 capacity | 4 nvectors |
 * 4n x | 4n y | 2n normal | 2n range. The decoder writes the vectors into the caller's
 * storage (hl_bus_map_t.vectors, max_vectors of them) and checks nvectors against it
 * before it reads any, so a hostile count cannot overrun it. The fingerprint comes from
 * the generated __houghloc_map_t_get_hash (see codec_scan.c).
 */
#include "wire.h"

#include "houghloc_map_t.h"

#define MAP_FIXED_BYTES (8 + 8 + 8 + 4 + 4)
#define MAP_BYTES_PER_VECTOR (4 + 4 + 2 + 2)

size_t hl_bus_map_bytes(uint32_t count)
{
    return MAP_FIXED_BYTES + (size_t)count * MAP_BYTES_PER_VECTOR;
}

/* The header fields, for both directions. */
static hl_status_t check_header(int64_t utime, int64_t version, int64_t capacity,
                                int64_t count, char *why)
{
    if (utime < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "map", "utime %lld is negative",
                            (long long)utime);
    if (version < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "map", "version %lld is negative",
                            (long long)version);
    if (capacity < 1 || capacity > (int64_t)HL_MAP_MAX_CAPACITY)
        return hl_wire_fail(why, HL_ERR_RANGE, "map", "capacity %lld outside 1..%lu",
                            (long long)capacity, (unsigned long)HL_MAP_MAX_CAPACITY);
    if (count < 0 || count > capacity)
        return hl_wire_fail(why, HL_ERR_RANGE, "map", "nvectors %lld outside 0..capacity %lld",
                            (long long)count, (long long)capacity);
    return HL_OK;
}

static hl_status_t check_vector(const hl_vector_t *v, uint32_t i, char *why)
{
    if (!hl_wire_coord_ok(v->x_mm) || !hl_wire_coord_ok(v->y_mm))
        return hl_wire_fail(why, HL_ERR_RANGE, "map",
                            "vector %lu at (%ld, %ld) mm outside +-%d mm", (unsigned long)i,
                            (long)v->x_mm, (long)v->y_mm, HL_COORD_MAX_MM);
    if (v->range_mm > HL_RANGE_MAX_MM)
        return hl_wire_fail(why, HL_ERR_RANGE, "map", "range_mm[%lu] %u outside 0..%d",
                            (unsigned long)i, (unsigned)v->range_mm, HL_RANGE_MAX_MM);
    return HL_OK;
}

int hl_bus_encode_map(const hl_bus_map_t *in, void *buf, size_t cap)
{
    if (!in || check_header(in->utime, in->version, in->capacity, in->count, NULL) != HL_OK)
        return -1;
    uint32_t n = in->count;
    if ((n > 0 && !in->vectors) || cap < hl_bus_map_bytes(n))
        return -1;
    for (uint32_t i = 0; i < n; i++)
        if (check_vector(&in->vectors[i], i, NULL) != HL_OK)
            return -1;
    hl_wire_out_t w = hl_wire_out(buf, cap);
    hl_wire_put_i64(&w, __houghloc_map_t_get_hash());
    hl_wire_put_i64(&w, in->utime);
    hl_wire_put_i64(&w, in->version);
    hl_wire_put_i32(&w, in->capacity);
    hl_wire_put_i32(&w, (int32_t)n);
    const hl_vector_t *v = in->vectors;
    for (uint32_t i = 0; i < n; i++)
        hl_wire_put_i32(&w, v[i].x_mm);
    for (uint32_t i = 0; i < n; i++)
        hl_wire_put_i32(&w, v[i].y_mm);
    for (uint32_t i = 0; i < n; i++)
        hl_wire_put_i16(&w, (int16_t)v[i].normal);
    for (uint32_t i = 0; i < n; i++)
        hl_wire_put_i16(&w, (int16_t)v[i].range_mm);
    return hl_wire_out_len(&w);
}

hl_status_t hl_bus_decode_map(const void *data, size_t len, hl_bus_map_t *out, char *why)
{
    hl_wire_in_t r;
    hl_status_t st = hl_wire_begin(&r, data, len, out, (uint64_t)__houghloc_map_t_get_hash(),
                                   MAP_FIXED_BYTES, false, "map", why);
    if (st != HL_OK)
        return st;
    int64_t utime = hl_wire_get_i64(&r);
    int64_t version = hl_wire_get_i64(&r);
    int32_t capacity = hl_wire_get_i32(&r);
    int32_t n = hl_wire_get_i32(&r);
    if ((st = check_header(utime, version, capacity, n, why)) != HL_OK)
        return st;
    if ((uint32_t)n > out->max_vectors)
        return hl_wire_fail(why, HL_ERR_RANGE, "map", "nvectors %ld exceeds the %lu of storage",
                            (long)n, (unsigned long)out->max_vectors);
    if (n > 0 && !out->vectors)
        return hl_wire_fail(why, HL_ERR_ARG, "map", "no storage for vectors");
    if (len != hl_bus_map_bytes((uint32_t)n))
        return hl_wire_fail(why, HL_ERR_PARSE, "map", "%zu bytes, but nvectors %ld needs %zu",
                            len, (long)n, hl_bus_map_bytes((uint32_t)n));
    out->utime = utime;
    out->version = version;
    out->capacity = capacity;
    out->count = (uint32_t)n;
    hl_vector_t *v = out->vectors;
    for (int32_t i = 0; i < n; i++)
        v[i].x_mm = hl_wire_get_i32(&r);
    for (int32_t i = 0; i < n; i++)
        v[i].y_mm = hl_wire_get_i32(&r);
    for (int32_t i = 0; i < n; i++)
        v[i].normal = (hl_bam_t)hl_wire_get_i16(&r);
    for (int32_t i = 0; i < n; i++) {
        int16_t range = hl_wire_get_i16(&r);
        if (range < 0)
            return hl_wire_fail(why, HL_ERR_RANGE, "map", "range_mm[%ld] %d outside 0..%d",
                                (long)i, range, HL_RANGE_MAX_MM);
        v[i].range_mm = (uint16_t)range;
    }
    if ((st = hl_wire_end(&r, "map", why)) != HL_OK)
        return st;
    for (uint32_t i = 0; i < (uint32_t)n; i++)
        if ((st = check_vector(&v[i], i, why)) != HL_OK)
            return st;
    return HL_OK;
}
