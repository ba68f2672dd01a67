/* status.c - text for hl_status_t. */
#include "houghloc/status.h"

const char *hl_status_str(hl_status_t s)
{
    switch (s) {
    case HL_OK: return "ok";
    case HL_ERR_ARG: return "invalid argument";
    case HL_ERR_RANGE: return "input out of range";
    case HL_ERR_NOMEM: return "out of memory";
    case HL_ERR_EMPTY: return "nothing to work with";
    case HL_ERR_CAPACITY: return "exceeds the capacity allocated at start";
    case HL_ERR_OS: return "operating-system error";
    case HL_ERR_PARSE: return "malformed input";
    }
    return "unknown status";
}
