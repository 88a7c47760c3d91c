/* Every heap allocation of the module goes through here, so "nothing allocated per frame"
 * is a number a test can assert (heap_allocs_after_load). */
#include <stdlib.h>
#include "base/base.h"

void *sbfx_calloc(sbfx *fx, size_t count, size_t size)
{
    if (fx->loaded) fx->heap_allocs_after_load++;
    return calloc(count, size);
}

void sbfx_free(sbfx *fx, void *p)
{
    (void)fx;
    free(p);
}
