/*
 * codec_path.c - PATH (houghloc.path_t): the way the daemon plans to its destination.
 *
 * On the wire, after the 8-byte hash: 8 utime | 8 destination_seq | 4 npoints |
 * 4n x | 4n y. npoints is checked against HL_BUS_PATH_MAX_POINTS before any point is
 * read, so a hostile count cannot overrun the struct. The fingerprint comes from the
 * generated __houghloc_path_t_get_hash (see codec_scan.c).
 */
#include "wire.h"

#include "houghloc_path_t.h"

#define PATH_FIXED_BYTES (8 + 8 + 8 + 4)

_Static_assert(HL_BUS_PATH_MAX_BYTES == PATH_FIXED_BYTES + 8 * HL_BUS_PATH_MAX_POINTS,
               "bus.h's HL_BUS_PATH_MAX_BYTES disagrees with the layout");

static hl_status_t check_header(int64_t utime, int64_t seq, int64_t n, char *why)
{
    if (utime < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "path", "utime %lld is negative",
                            (long long)utime);
    if (seq != -1 && seq < 1)
        return hl_wire_fail(why, HL_ERR_RANGE, "path",
                            "destination_seq %lld is neither -1 nor positive", (long long)seq);
    if (n < 0 || n > HL_BUS_PATH_MAX_POINTS)
        return hl_wire_fail(why, HL_ERR_RANGE, "path", "npoints %lld outside 0..%d",
                            (long long)n, HL_BUS_PATH_MAX_POINTS);
    return HL_OK;
}

static hl_status_t check_points(const hl_bus_path_t *m, char *why)
{
    for (int32_t i = 0; i < m->npoints; i++)
        if (!hl_wire_coord_ok(m->x_mm[i]) || !hl_wire_coord_ok(m->y_mm[i]))
            return hl_wire_fail(why, HL_ERR_RANGE, "path",
                                "point %ld at (%ld, %ld) mm outside +-%d mm", (long)i,
                                (long)m->x_mm[i], (long)m->y_mm[i], HL_COORD_MAX_MM);
    return HL_OK;
}

int hl_bus_encode_path(const hl_bus_path_t *in, void *buf, size_t cap)
{
    if (!in || check_header(in->utime, in->destination_seq, in->npoints, NULL) != HL_OK ||
        check_points(in, NULL) != HL_OK)
        return -1;
    hl_wire_out_t w = hl_wire_out(buf, cap);
    hl_wire_put_i64(&w, __houghloc_path_t_get_hash());
    hl_wire_put_i64(&w, in->utime);
    hl_wire_put_i64(&w, in->destination_seq);
    hl_wire_put_i32(&w, in->npoints);
    for (int32_t i = 0; i < in->npoints; i++)
        hl_wire_put_i32(&w, in->x_mm[i]);
    for (int32_t i = 0; i < in->npoints; i++)
        hl_wire_put_i32(&w, in->y_mm[i]);
    return hl_wire_out_len(&w);
}

hl_status_t hl_bus_decode_path(const void *data, size_t len, hl_bus_path_t *out, char *why)
{
    hl_wire_in_t r;
    hl_status_t st = hl_wire_begin(&r, data, len, out, (uint64_t)__houghloc_path_t_get_hash(),
                                   PATH_FIXED_BYTES, false, "path", why);
    if (st != HL_OK)
        return st;
    int64_t utime = hl_wire_get_i64(&r);
    int64_t seq = hl_wire_get_i64(&r);
    int32_t n = hl_wire_get_i32(&r);
    if ((st = check_header(utime, seq, n, why)) != HL_OK)
        return st;
    if (len != PATH_FIXED_BYTES + 8 * (size_t)n)
        return hl_wire_fail(why, HL_ERR_PARSE, "path", "%zu bytes, but npoints %ld needs %zu",
                            len, (long)n, PATH_FIXED_BYTES + 8 * (size_t)n);
    out->utime = utime;
    out->destination_seq = seq;
    out->npoints = n;
    for (int32_t i = 0; i < n; i++)
        out->x_mm[i] = hl_wire_get_i32(&r);
    for (int32_t i = 0; i < n; i++)
        out->y_mm[i] = hl_wire_get_i32(&r);
    if ((st = hl_wire_end(&r, "path", why)) != HL_OK)
        return st;
    return check_points(out, why);
}
