/*
 * params.h (internal) - what hl_params_t holds, and params.h's table as the core keeps
 * it (src/core/params_table.c): each key's field, storage and numeric range. The stage
 * modules take their tunables' defaults from it (hl_params_fill_defaults); the laboratory
 * and the tests reach the values with hl_params_slam.
 */
#ifndef HOUGHLOC_INTERNAL_PARAMS_H
#define HOUGHLOC_INTERNAL_PARAMS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc-internal/slam_params.h"
#include "houghloc/params.h"

#ifdef __cplusplus
extern "C" {
#endif

/* How a key's value is stored in hl_slam_params_t. */
typedef enum hl_param_store {
    HL_PARAM_STORE_NONE = 0,    /* slam.profile (the body's), a fixed key (nowhere) */
    HL_PARAM_STORE_I32,
    HL_PARAM_STORE_U16,
    HL_PARAM_STORE_U32,
    HL_PARAM_STORE_U64,
    HL_PARAM_STORE_DOUBLE,
    HL_PARAM_STORE_BOOL,
    HL_PARAM_STORE_BAM,         /* hl_bam_t, written in degrees */
} hl_param_store_t;

typedef struct hl_param_entry {
    hl_param_info_t info;       /* what hl_params_info returns */
    hl_param_store_t store;
    size_t offset;              /* of the field in hl_slam_params_t */
    double min, max;            /* numbers: the range, in the written unit */
    bool zero_ok;               /* ... and 0 besides (off) */
} hl_param_entry_t;

extern const hl_param_entry_t hl_param_table[];
extern const size_t hl_param_table_len;
extern const hl_param_preset_t hl_param_presets[];
extern const size_t hl_param_presets_len;

/* What hl_params_t holds. */
typedef struct hl_params_body {
    hl_slam_params_t slam;
    uint32_t profile;           /* index into hl_param_presets */
    char why[HL_PARAMS_WHY_LEN];    /* "" when the last call succeeded */
} hl_params_body_t;

/** The values of @p p, to read or change directly (the laboratory, the tests). */
static inline hl_slam_params_t *hl_params_slam(hl_params_t *p)
{
    return &((hl_params_body_t *)(void *)p->private_.bytes)->slam;
}
static inline const hl_slam_params_t *hl_params_slam_const(const hl_params_t *p)
{
    return &((const hl_params_body_t *)(const void *)p->private_.bytes)->slam;
}

/** The table's entry for @p key, or NULL. */
const hl_param_entry_t *hl_param_find(const char *key);

/**
 * Writes the table's defaults of the fields that lie within [@p base, @p base + @p size)
 * of hl_slam_params_t into @p dst, which stands for that part of it: a stage module's
 * params (@p base = offsetof(hl_slam_params_t, loc), ...), or the whole struct (0).
 */
void hl_params_fill_defaults(void *dst, size_t base, size_t size);

#ifdef __cplusplus
}
#endif
#endif
