/* map.c - the fixed-capacity map of tangent vectors with random culling, optionally bounded
 * in density and culled by evidence. */
#include "houghloc-internal/map.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cellhash.h"
#include "houghloc-internal/fixed.h"
#include "houghloc/rng.h"
#include "houghloc-internal/slam_params.h"
#include "houghloc/count.h"
#include "mapdisc.h"
#include "mapsq.h"

/* A new vector confirms an old one within confirm_mm whose normal agrees within this:
 * the tracking localizer's own normal gate. */
#define CONFIRM_GATE_DEG 30.0
#define ROUND_GATE (HL_BAM_PER_TURN / 16)  /* a round place's normals: a sixteenth of a
                                              turn either side, the squares' eighth */
#define PI 3.14159265358979323846

struct hl_map {
    uint32_t capacity;
    uint32_t count;
    uint64_t version;       /* 0..HL_COUNT_MAX, where it stays (count.h) */
    hl_rng_t rng;
    hl_vector_t *vectors;   /* [capacity] */
    uint32_t *stamps;       /* [capacity] the stamp each vector was added under */
    uint32_t stamp;         /* ... vectors added now get this (hl_map_set_stamp) */
    uint32_t per_place;     /* the density bound; 0: none (and its index unallocated) */
    int32_t round_mm;       /* round places (round_places): their radius; 0: squares */
    hl_mapdisc_t discs;     /* ... the round places' index */
    hl_mapsq_t places;      /* ... or the squares' */
    uint32_t choices;       /* the evidence cull's draws; 1: the paper's random cull (and
                               what follows unallocated) */
    int32_t confirm_mm;
    uint16_t *support;      /* [capacity] how many later readings confirmed each vector */
    bool crowd;             /* cull the most crowded of `choices` instead (needs the
                               density bound's index; support and near unallocated) */
    hl_mapsq_t crowd_sq;    /* the crowding cull's squares (crowd_square_mm);
                               unallocated when it counts the density
                               bound's place and the 8 around it */
    hl_cellhash_t near;     /* the map by cells of confirm_mm, rebuilt for each scan */
};

void hl_map_params_default(hl_map_params_t *p)
{
    hl_slam_params_t s;     /* a tracker's map at the defaults (params_table.c's slam.*) */
    hl_slam_params_default(&s);
    hl_slam_map_params(&s, p);
}

static bool square_ok(int32_t mm)
{
    return mm >= HL_MAP_MIN_SQUARE_MM && mm <= HL_MAP_MAX_SQUARE_MM;
}

const char *hl_map_params_error(const hl_map_params_t *p)
{
    if (!p)
        return "no map parameters";
    if (p->capacity < 1 || p->capacity > HL_MAP_MAX_CAPACITY)
        return "map capacity must be in 1..1048576";
    if (p->per_place > HL_MAP_MAX_PER_PLACE)
        return "the density bound (per place) must be in 0..1000";
    if (p->per_place > 0 && !square_ok(p->square_mm))
        return "the density bound's square must be in 10..1000 mm";
    if (p->cull_choices < 1 || p->cull_choices > HL_MAP_MAX_CHOICES)
        return "the cull's choices must be in 1..64";
    if (p->cull_choices > 1 && !p->cull_crowded && (p->confirm_mm < 1 ||
                                                    p->confirm_mm > HL_MAP_MAX_SQUARE_MM))
        return "the evidence cull's confirm distance must be in 1..1000 mm";
    if (p->crowd_square_mm != 0 && !square_ok(p->crowd_square_mm))
        return "the crowding cull's square must be 0 or in 10..1000 mm";
    if (p->cull_crowded && (p->cull_choices < 2 || p->per_place == 0))
        return "the crowding cull needs 2 or more choices and a density bound";
    return NULL;
}

static bool set_density(hl_map_t *map, const hl_map_params_t *p);
static bool set_evidence(hl_map_t *map, uint32_t choices, int32_t confirm_mm);
static bool set_crowding(hl_map_t *map, uint32_t choices, int32_t square_mm);

hl_map_t *hl_map_create_with(const hl_map_params_t *p)
{
    if (hl_map_params_error(p))
        return NULL;
    hl_map_t *map = calloc(1, sizeof *map);
    if (!map)
        return NULL;
    map->vectors = calloc(p->capacity, sizeof *map->vectors);
    map->stamps = calloc(p->capacity, sizeof *map->stamps);
    if (!map->vectors || !map->stamps) {
        free(map->vectors);
        free(map->stamps);
        free(map);
        return NULL;
    }
    map->capacity = p->capacity;
    map->choices = 1;
    hl_rng_seed(&map->rng, p->seed);
    bool ok = p->per_place == 0 || set_density(map, p);
    if (ok && p->cull_choices > 1)
        ok = p->cull_crowded ? set_crowding(map, p->cull_choices, p->crowd_square_mm)
                             : set_evidence(map, p->cull_choices, p->confirm_mm);
    if (!ok) {
        hl_map_destroy(map);
        return NULL;
    }
    return map;
}

hl_map_t *hl_map_create(uint32_t capacity, uint64_t seed)
{
    hl_map_params_t p;
    hl_map_params_default(&p);
    p.capacity = capacity;
    p.seed = seed;
    return hl_map_create_with(&p);
}

void hl_map_destroy(hl_map_t *map)
{
    if (!map)
        return;
    hl_mapdisc_free(&map->discs);
    hl_mapsq_free(&map->places);
    hl_mapsq_free(&map->crowd_sq);
    hl_cellhash_free(&map->near);
    free(map->support);
    free(map->vectors);
    free(map->stamps);
    free(map);
}

/* The place indexes (the density bound's and the crowding cull's squares) follow every
 * write to a slot; these keep both in step. */
static void index_unlink(hl_map_t *map, uint32_t slot)
{
    if (map->round_mm)
        hl_mapdisc_unlink(&map->discs, slot);
    else if (map->per_place)
        hl_mapsq_unlink(&map->places, slot);
    if (map->crowd_sq.head)
        hl_mapsq_unlink(&map->crowd_sq, slot);
}

static void index_link(hl_map_t *map, uint32_t slot)
{
    if (map->round_mm)
        hl_mapdisc_link(&map->discs, map->vectors, slot);
    else if (map->per_place)
        hl_mapsq_link(&map->places, map->vectors, slot);
    if (map->crowd_sq.head)
        hl_mapsq_link(&map->crowd_sq, map->vectors, slot);
}

static void index_rebuild(hl_map_t *map)
{
    if (map->round_mm)
        hl_mapdisc_rebuild(&map->discs, map->vectors, map->count);
    else if (map->per_place)
        hl_mapsq_rebuild(&map->places, map->vectors, map->count);
    if (map->crowd_sq.head)
        hl_mapsq_rebuild(&map->crowd_sq, map->vectors, map->count);
}

void hl_map_clear(hl_map_t *map)
{
    map->count = 0;
    map->version = hl_count_next(map->version);
    index_rebuild(map);
}

void hl_map_swap(hl_map_t *a, hl_map_t *b)
{
    uint64_t newer = hl_count_next(a->version > b->version ? a->version : b->version);
    hl_map_t t = *a;
    *a = *b;
    *b = t;
    a->version = newer;
}

/* The evidence cull's support counts and neighbour hash (create time: the params were
 * checked, the map is empty). @return false when memory is short. */
static bool set_evidence(hl_map_t *map, uint32_t choices, int32_t confirm_mm)
{
    map->support = calloc(map->capacity, sizeof *map->support);
    if (!map->support || !hl_cellhash_init(&map->near, confirm_mm, map->capacity))
        return false;
    map->choices = choices;
    map->confirm_mm = confirm_mm;
    return true;
}

/* Counts, for every map vector, the vectors of @p v[0 .. n - 1] (one scan) that confirm
 * it: within confirm_mm, normals within CONFIRM_GATE_DEG. */
static void confirm(hl_map_t *map, const hl_vector_t *v, uint32_t n)
{
    const hl_cellhash_t *g = &map->near;
    const int64_t r2 = (int64_t)map->confirm_mm * map->confirm_mm;
    const int32_t gate = hl_bam_from_deg(CONFIRM_GATE_DEG);
    hl_cellhash_build(&map->near, map->vectors, map->count);
    for (uint32_t i = 0; i < n; i++) {
        int32_t cx = hl_cellhash_cell(g, v[i].x_mm), cy = hl_cellhash_cell(g, v[i].y_mm);
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                uint32_t b = hl_cellhash_bucket(g, cx + dx, cy + dy);
                for (uint32_t e = g->start[b]; e < g->start[b + 1]; e++) {
                    int64_t ex = v[i].x_mm - g->x[e], ey = v[i].y_mm - g->y[e];
                    int32_t dn = hl_bam_diff(v[i].normal, g->normal[e]);
                    uint16_t *s = &map->support[g->index[e]];
                    if (ex * ex + ey * ey <= r2 && (dn < 0 ? -dn : dn) <= gate && *s < UINT16_MAX)
                        (*s)++;
                }
            }
    }
}

/* The evidence cull's victim: the least confirmed of `choices` vectors drawn at random
 * (the first drawn among equals). */
static uint32_t least_confirmed(hl_map_t *map)
{
    uint32_t victim = hl_rng_below(&map->rng, map->count);
    for (uint32_t k = 1; k < map->choices; k++) {
        uint32_t c = hl_rng_below(&map->rng, map->count);
        if (map->support[c] < map->support[victim])
            victim = c;
    }
    return victim;
}

/* The crowding cull (create time, after the density bound). */
static bool set_crowding(hl_map_t *map, uint32_t choices, int32_t square_mm)
{
    if (square_mm > 0 && !hl_mapsq_init(&map->crowd_sq, map->capacity, square_mm))
        return false;
    map->choices = choices;
    map->crowd = true;
    return true;
}

/* How many map vectors share slot @p c's crowding square, or else its place or one of the
 * 8 squares around it (the density bound's places, mapsq.h), seen from the same side. */
static uint32_t crowding(const hl_map_t *map, uint32_t c)
{
    if (map->crowd_sq.head)
        return hl_mapsq_count(&map->crowd_sq, &map->vectors[c]);
    if (map->round_mm) {    /* round places: the disc of 3 x 3 of them, facing alike */
        uint32_t near[HL_MAP_NEAR_MAX];
        return hl_mapdisc_near(&map->discs, &map->vectors[c], 3 * map->round_mm, ROUND_GATE,
                               near, HL_MAP_NEAR_MAX);
    }
    int32_t side = map->places.square_mm;
    uint32_t n = 0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            hl_vector_t probe = map->vectors[c];
            int64_t x = (int64_t)probe.x_mm + dx * side, y = (int64_t)probe.y_mm + dy * side;
            if (x < -HL_COORD_MAX_MM || x > HL_COORD_MAX_MM || y < -HL_COORD_MAX_MM ||
                y > HL_COORD_MAX_MM)
                continue;
            probe.x_mm = (hl_mm_t)x;
            probe.y_mm = (hl_mm_t)y;
            n += hl_mapsq_count(&map->places, &probe);
        }
    return n;
}

/* The crowding cull's victim: the most crowded of `choices` vectors drawn at random (the
 * first drawn among equals). */
static uint32_t most_crowded(hl_map_t *map)
{
    uint32_t victim = hl_rng_below(&map->rng, map->count);
    uint32_t most = crowding(map, victim);
    for (uint32_t k = 1; k < map->choices; k++) {
        uint32_t c = hl_rng_below(&map->rng, map->count);
        uint32_t n = crowding(map, c);
        if (n > most) {
            victim = c;
            most = n;
        }
    }
    return victim;
}

/* The density bound's place index (create time). */
static bool set_density(hl_map_t *map, const hl_map_params_t *p)
{
    /* Round places: the disc of the square's area (28 mm for 50 mm squares), found in
     * squares of its diameter without sides, so that it reaches four at most. */
    map->round_mm = p->round_places ? (int32_t)lround(p->square_mm / sqrt(PI)) : 0;
    if (map->round_mm ? !hl_mapdisc_init(&map->discs, map->capacity, 2 * map->round_mm)
                      : !hl_mapsq_init(&map->places, map->capacity, p->square_mm))
        return false;
    map->per_place = p->per_place;
    return true;
}

/* Writes *v into slot `slot` (below count), keeping the place index in step. */
static void replace(hl_map_t *map, uint32_t slot, const hl_vector_t *v)
{
    index_unlink(map, slot);
    map->vectors[slot] = *v;
    map->stamps[slot] = map->stamp;
    if (map->support)
        map->support[slot] = 0;
    index_link(map, slot);
}

/* The density bound: a full place for @p v drops one of its vectors or @p v, uniformly
 * at random among them, as the paper's culling does over the whole map. @return whether
 * the place was full (v taken or dropped). */
static bool bound_place(hl_map_t *map, const hl_vector_t *v)
{
    uint32_t near[HL_MAP_NEAR_MAX], c;
    if (map->round_mm)
        c = hl_mapdisc_near(&map->discs, v, map->round_mm, ROUND_GATE, near, HL_MAP_NEAR_MAX);
    else
        c = hl_mapsq_count(&map->places, v);
    if (c < map->per_place)
        return false;
    uint32_t victim = hl_rng_below(&map->rng, c + 1);
    if (victim < c)
        replace(map, map->round_mm ? near[victim] : hl_mapsq_nth(&map->places, v, victim), v);
    return true;
}

bool hl_vector_in_range(const hl_vector_t *v)
{
    return v->x_mm >= -HL_COORD_MAX_MM && v->x_mm <= HL_COORD_MAX_MM &&
           v->y_mm >= -HL_COORD_MAX_MM && v->y_mm <= HL_COORD_MAX_MM &&
           v->range_mm <= HL_RANGE_MAX_MM;
}

hl_status_t hl_map_add(hl_map_t *map, const hl_vector_t *v)
{
    if (!map || !v)
        return HL_ERR_ARG;
    if (!hl_vector_in_range(v))
        return HL_ERR_RANGE;
    map->version = hl_count_next(map->version);
    if (map->per_place && bound_place(map, v))
        return HL_OK;
    if (map->count < map->capacity) {
        map->vectors[map->count] = *v;
        map->stamps[map->count] = map->stamp;
        if (map->support)
            map->support[map->count] = 0;
        index_link(map, map->count);
        map->count++;
        return HL_OK;
    }
    if (map->choices > 1) {
        replace(map, map->crowd ? most_crowded(map) : least_confirmed(map), v);
        return HL_OK;
    }
    /* Full: drop one of the capacity + 1 candidates uniformly at random (the paper's
     * culling). Index == capacity means the new vector itself is dropped. */
    uint32_t victim = hl_rng_below(&map->rng, map->capacity + 1);
    if (victim < map->capacity)
        replace(map, victim, v);
    return HL_OK;
}

bool hl_vector_from_reading(hl_pose_t pose, const hl_reading_t *r, hl_vector_t *out)
{
    if (!r->valid || r->range_mm < 0 || r->range_mm > HL_RANGE_MAX_MM)
        return false;
    hl_bam_t world_bearing = (hl_bam_t)(pose.theta + r->bearing);
    int32_t dx, dy;
    hl_polar_to_xy(r->range_mm, world_bearing, &dx, &dy);
    int64_t x = (int64_t)pose.x_mm + dx, y = (int64_t)pose.y_mm + dy;
    if (x < -HL_COORD_MAX_MM || x > HL_COORD_MAX_MM || y < -HL_COORD_MAX_MM ||
        y > HL_COORD_MAX_MM)
        return false;
    out->x_mm = (hl_mm_t)x;
    out->y_mm = (hl_mm_t)y;
    out->normal = hl_reading_normal(r, pose.theta);
    out->range_mm = (uint16_t)r->range_mm;
    return true;
}

void hl_vector_origin(const hl_vector_t *v, hl_mm_t *x_mm, hl_mm_t *y_mm)
{
    int32_t dx, dy;
    hl_polar_to_xy(v->range_mm, v->normal, &dx, &dy);
    *x_mm = v->x_mm + dx;
    *y_mm = v->y_mm + dy;
}

hl_status_t hl_map_add_scan(hl_map_t *map, const hl_scan_t *scan, hl_pose_t pose,
                            uint32_t *added)
{
    if (added)
        *added = 0;
    if (!map || !scan)
        return HL_ERR_ARG;
    if (!hl_pose_in_range(pose) || scan->count > HL_SCAN_MAX_READINGS)
        return HL_ERR_RANGE;
    uint32_t n = 0;
    if (map->support) {     /* the evidence cull */
        /* The scan's vectors first confirm what the map holds, then join it. */
        hl_vector_t v[HL_SCAN_MAX_READINGS];
        uint32_t nv = 0;
        for (uint32_t i = 0; i < scan->count; i++)
            nv += hl_vector_from_reading(pose, &scan->readings[i], &v[nv]);
        confirm(map, v, nv);
        for (uint32_t i = 0; i < nv; i++)
            n += hl_map_add(map, &v[i]) == HL_OK;
    } else {
        for (uint32_t i = 0; i < scan->count; i++) {
            hl_vector_t v;
            if (hl_vector_from_reading(pose, &scan->readings[i], &v) &&
                hl_map_add(map, &v) == HL_OK)
                n++;
        }
    }
    if (added)
        *added = n;
    return HL_OK;
}

uint32_t hl_map_count(const hl_map_t *map)
{
    return map->count;
}

uint32_t hl_map_capacity(const hl_map_t *map)
{
    return map->capacity;
}

uint64_t hl_map_version(const hl_map_t *map)
{
    return map->version;
}

const hl_vector_t *hl_map_vectors(const hl_map_t *map)
{
    return map->vectors;
}

hl_rng_t hl_map_rng(const hl_map_t *map)
{
    return map->rng;
}

hl_status_t hl_map_restore(hl_map_t *map, const hl_vector_t *vectors, uint32_t n,
                           uint64_t version, hl_rng_t rng)
{
    if (!map || (!vectors && n > 0))
        return HL_ERR_ARG;
    if (n > map->capacity)
        return HL_ERR_CAPACITY;
    if (version > (uint64_t)HL_COUNT_MAX)
        return HL_ERR_RANGE;
    /* Check everything before the first write, so that a refused restore leaves the map
     * as it was. */
    for (uint32_t i = 0; i < n; i++)
        if (!hl_vector_in_range(&vectors[i]))
            return HL_ERR_RANGE;
    if (n > 0)   /* memmove: the caller may hand back this map's own vectors */
        memmove(map->vectors, vectors, (size_t)n * sizeof *vectors);
    map->count = n;
    map->version = version;
    map->rng = rng;
    if (map->support)       /* not saved: a restored map learns it again */
        memset(map->support, 0, (size_t)map->capacity * sizeof *map->support);
    memset(map->stamps, 0, (size_t)map->capacity * sizeof *map->stamps);
    index_rebuild(map);
    return HL_OK;
}

void hl_map_set_stamp(hl_map_t *map, uint32_t stamp)
{
    map->stamp = stamp;
}

void hl_map_restore_stamps(hl_map_t *map, const uint32_t *stamps, uint32_t n)
{
    memcpy(map->stamps, stamps, (size_t)(n < map->count ? n : map->count) * sizeof *stamps);
}

const uint32_t *hl_map_stamps(const hl_map_t *map)
{
    return map->stamps;
}

size_t hl_map_mem_bytes(const hl_map_t *map)
{
    return sizeof *map + (size_t)map->capacity * (sizeof *map->vectors + sizeof *map->stamps) +
           hl_mapdisc_mem_bytes(&map->discs, map->capacity) +
           hl_mapsq_mem_bytes(&map->places, map->capacity) +
           hl_mapsq_mem_bytes(&map->crowd_sq, map->capacity) +
           (map->support ? (size_t)map->capacity * sizeof *map->support +
                               hl_cellhash_mem_bytes(&map->near) : 0);
}
