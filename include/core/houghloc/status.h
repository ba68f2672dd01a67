/* status.h - the one status enum every houghloc library function returns. */
#ifndef HOUGHLOC_STATUS_H
#define HOUGHLOC_STATUS_H

#include "houghloc/export.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum hl_status {
    HL_OK = 0,
    HL_ERR_ARG = -1,     /* caller bug: NULL pointer or parameter out of its range */
    HL_ERR_RANGE = -2,   /* input outside the documented fixed-point range */
    HL_ERR_NOMEM = -3,   /* allocation failed (init only) */
    HL_ERR_EMPTY = -4,   /* nothing to work with: empty map, no valid reading, no vote */
    HL_ERR_CAPACITY = -5,/* a buffer sized at init is too small for this input */
    HL_ERR_OS = -6,      /* operating-system error; errno is kept */
    HL_ERR_PARSE = -7,   /* malformed text or bytes from outside */
} hl_status_t;

/** A short constant English description, e.g. "input out of range". */
HL_API const char *hl_status_str(hl_status_t s);

#ifdef __cplusplus
}
#endif
#endif
