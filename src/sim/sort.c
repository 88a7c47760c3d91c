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

/* Ties in the view distance (an emitter that spawns its particles at one point) are drawn in the
 * order the pool holds them, which depends on the order triggers came in. With identified
 * instances in the frame (sbfx_trigger_identified) that order must not matter: a first sort by
 * a key made of the particle's own random detail window (drawn from its identity's stream)
 * orders the ties the same in every process. Without them the frame is sorted as it always was. */
static uint32_t tie_key(const sbfx_view_particle *v)
{
    uint32_t h = 2166136261u, bits[3];
    memcpy(bits, v->detail, sizeof(bits));
    for (int k = 0; k < 3; k++) h = (h ^ bits[k]) * 16777619u;
    return h;
}

/* Three stable LSD passes of 11 bits over keys[src[i]], from src into dst; returns the array that
 * holds the result (src or dst: three passes swap them an odd number of times). */
static uint32_t *radix_passes(const uint32_t *keys, uint32_t *src, uint32_t *dst, int count)
{
    for (int shift = 0; shift < 32; shift += RADIX_BITS) {
        uint32_t histogram[RADIX_SIZE] = {0};
        for (int i = 0; i < count; i++) histogram[(keys[src[i]] >> shift) & (RADIX_SIZE - 1)]++;
        uint32_t sum = 0;
        for (uint32_t b = 0; b < RADIX_SIZE; b++) {
            uint32_t n = histogram[b];
            histogram[b] = sum;
            sum += n;
        }
        for (int i = 0; i < count; i++) {
            uint32_t key = keys[src[i]];
            dst[histogram[(key >> shift) & (RADIX_SIZE - 1)]++] = src[i];
        }
        uint32_t *t = src;
        src = dst;
        dst = t;
    }
    return src;
}

void sbfx_sort_back_to_front(sbfx *fx, int count)
{
    uint32_t *src = fx->sim->order, *dst = fx->sim->order_tmp;
    uint32_t *keys = (uint32_t *)fx->sim->sort_keys; /* the float's bits, as descending_key makes them */
    for (int i = 0; i < count; i++) src[i] = (uint32_t)i;
    if (fx->sim->view_identified) {
        for (int i = 0; i < count; i++) keys[i] = tie_key(&fx->sim->view[i]);
        uint32_t *sorted = radix_passes(keys, src, dst, count);
        dst = sorted == src ? dst : src;
        src = sorted;
    }
    for (int i = 0; i < count; i++) {
        const float *c = fx->sim->view[i].center;
        keys[i] = descending_key(sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]));
    }
    uint32_t *sorted = radix_passes(keys, src, dst, count);
    /* the result is in one of the two arrays: that one becomes `order` */
    if (sorted != fx->sim->order) {
        fx->sim->order_tmp = fx->sim->order;
        fx->sim->order = sorted;
    }
}
