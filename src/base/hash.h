/* The ground floor's hash (base/hash.c). */
#ifndef SBFX_BASE_HASH_H
#define SBFX_BASE_HASH_H

#include <stddef.h>
#include <stdint.h>

/* FNV-1a over size bytes of data, continuing from key (0: from the start): a key names a
 * recipe (shader names and defines, a target's size, formats and filter); two different ones
 * share a key with odds of about 2^-64. */
uint64_t sbfx_hash64(uint64_t key, const void *data, size_t size);

#endif
