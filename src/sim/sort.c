/* Back-to-front order for alpha blending: LSD radix sort (3 passes of 11 bits) on the view
 * distance. O(n), stable, no allocation: the scratch arrays are sized at load. */
#include <math.h>
#include <string.h>
#include "sim/sim.h"

#define RADIX_BITS 11
#define RADIX_SIZE (1u << RADIX_BITS)

/* Distances are finite and >= 0, so their IEEE bits order like the values; inverting them
 * gives far-to-near. */
static uint32_t descending_key(float distance)
{
    uint32_t bits;
    memcpy(&bits, &distance, sizeof(bits));
    return ~bits;
}

void sbfx_sort_back_to_front(sbfx *fx, int count)
{
    uint32_t *src = fx->sim->order, *dst = fx->sim->order_tmp;
    for (int i = 0; i < count; i++) {
        const float *c = fx->sim->view[i].center;
        fx->sim->sort_keys[i] = sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        src[i] = (uint32_t)i;
    }
    for (int shift = 0; shift < 32; shift += RADIX_BITS) {
        uint32_t histogram[RADIX_SIZE] = {0};
        for (int i = 0; i < count; i++)
            histogram[(descending_key(fx->sim->sort_keys[src[i]]) >> shift) & (RADIX_SIZE - 1)]++;
        uint32_t sum = 0;
        for (uint32_t b = 0; b < RADIX_SIZE; b++) {
            uint32_t n = histogram[b];
            histogram[b] = sum;
            sum += n;
        }
        for (int i = 0; i < count; i++) {
            uint32_t key = descending_key(fx->sim->sort_keys[src[i]]);
            dst[histogram[(key >> shift) & (RADIX_SIZE - 1)]++] = src[i];
        }
        uint32_t *t = src;
        src = dst;
        dst = t;
    }
    /* Three passes leave the result in order_tmp: swap the roles of the arrays. */
    if (src != fx->sim->order) {
        fx->sim->order_tmp = fx->sim->order;
        fx->sim->order = src;
    }
}
