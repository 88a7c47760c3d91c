/* FNV-1a, 64 bits (Fowler, Noll, Vo): what names how a GL object was made (gl/objects.h). */
#include "base/hash.h"

uint64_t sbfx_hash64(uint64_t key, const void *data, size_t size)
{
    const unsigned char *b = data;
    if (!key) key = 1469598103934665603ull;
    for (size_t i = 0; i < size; i++) key = (key ^ b[i]) * 1099511628211ull;
    return key;
}
