/* cycle_map.c - MAP: the whole map, when it changed, at a bounded rate.
 *
 * A MAP message carries every vector of the map (a laser's 15,000 make 180 kB), and a
 * laser changes the map on every scan: published on every change, MAP makes a recorded
 * run many times the size of its input (a laser replay of the intel building: 1.5 MB in,
 * 141 MB out, 99.9 % of it MAP). Two bounds hold it back, both counted in the input
 * (message time and message bytes, never the wall clock), so that MAP stays a function
 * of the input and the parameters and a replay reproduces it:
 *  - time: at most one MAP per map_period_ms of message time;
 *  - bytes: after the first MAP, the next goes out only once the SONAR and ODOMETRY
 *    bytes taken since the previous one, times map_input_ratio, reach its size.
 * So MAP adds at most map_input_ratio bytes per byte of input, plus the first map and
 * the one hl_cycle_flush_map sends at the end (the final map, which a log's reader
 * takes). A map held back is not lost: the next MAP carries it, and STATUS's
 * map_version tells a consumer that a newer one exists.
 */
#include "cycle_internal.h"

/* input_since_map stops here: times HL_CYCLE_MAP_RATIO_MAX it still fits an int64 */
#define INPUT_SINCE_MAP_MAX (INT64_MAX / (HL_CYCLE_MAP_RATIO_MAX + 1))

static void publish_map(hl_cycle_t *c)
{
    hl_map_t *map = hl_slam_map(c->slam);
    hl_bus_map_t m = {
        .utime = c->map_changed_utime, .version = (int64_t)hl_map_version(map),
        .capacity = (int32_t)hl_map_capacity(map), .count = hl_map_count(map),
        .vectors = (hl_vector_t *)hl_map_vectors(map),
    };
    int len = hl_bus_encode_map(&m, c->map_buf, c->map_buf_len);
    if (len < 0) {
        hl_cycle_fault(c, NULL, "map encode", "MAP: the map does not encode (a bug)");
        return;
    }
    c->io.emit(c->io.ctx, HL_CH_MAP, c->map_buf, (size_t)len);
    c->published_version = hl_map_version(map);
    c->map_published = true;
    c->map_published_utime = c->map_changed_utime;
    c->input_since_map = 0;
}

static bool map_pending(const hl_cycle_t *c)
{
    return hl_map_version(hl_slam_map(c->slam)) != c->published_version;
}

/* A change whose time is before the last MAP's (the input's clock is behind the time a
 * restored map file carried, or a stream re-synchronized back in time, stream.h) starts
 * the period afresh: waiting for the clock to catch up would hold the map back for as
 * long as the clock is behind. */
static bool period_allows(const hl_cycle_t *c)
{
    if (c->map_changed_utime < c->map_published_utime)
        return true;
    return (uint64_t)c->map_changed_utime - (uint64_t)c->map_published_utime >=
           (uint64_t)c->p.map_period_ms * 1000;
}

/* The input since the last MAP pays for this one, at map_input_ratio. */
static bool bytes_allow(const hl_cycle_t *c)
{
    if (c->p.map_input_ratio == 0)
        return true;
    size_t size = hl_bus_map_bytes(hl_map_count(hl_slam_map(c->slam)));
    return c->input_since_map * c->p.map_input_ratio >= (int64_t)size;
}

void hl_cycle_map_input(hl_cycle_t *c, size_t len)
{
    if ((uint64_t)len >= (uint64_t)(INPUT_SINCE_MAP_MAX - c->input_since_map))
        c->input_since_map = INPUT_SINCE_MAP_MAX;
    else
        c->input_since_map += (int64_t)len;
}

void hl_cycle_maybe_publish_map(hl_cycle_t *c)
{
    /* the first MAP goes out at once: a consumer should not wait for the map */
    if (map_pending(c) && (!c->map_published || (period_allows(c) && bytes_allow(c))))
        publish_map(c);
}

void hl_cycle_flush_map(hl_cycle_t *c)
{
    if (map_pending(c))
        publish_map(c);
}
