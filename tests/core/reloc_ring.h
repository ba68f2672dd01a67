/* reloc_ring.h - the global search the reloc tests use on the test kit's ideal ring. */
#ifndef TESTS_CORE_RELOC_RING_H
#define TESTS_CORE_RELOC_RING_H

#include "houghloc-internal/reloc.h"

/* The default search but for its heading stage: an ideal ring's normals are its beams'
 * directions, which tell nothing of heading, so every heading window is searched. */
static inline hl_reloc_t *ring_reloc(void)
{
    hl_reloc_params_t p;
    hl_reloc_params_default(&p);
    p.headings = 18;
    hl_loc_params_t fine;
    hl_loc_params_default(&fine);
    return hl_reloc_create(&p, &fine);
}

#endif
