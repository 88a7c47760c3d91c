/* The video's luma into detail slices (input_detail.h). */
#include "input_detail.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int input_detail_start(struct input_detail *d, int size, char *err, size_t n)
{
    memset(d, 0, sizeof(*d));
    if (size < 1 || size > LUMA_MAX_SIZE) {
        snprintf(err, n, "detail slices of %d texels: the input can feed 1 .. %d", size, LUMA_MAX_SIZE);
        return -1;
    }
    size_t count = (size_t)size * size;
    d->size = size;
    d->luma = malloc(count);
    d->values = malloc(count * sizeof(*d->values));
    d->slice = malloc(count * sizeof(*d->slice));
    if (!d->luma || !d->values || !d->slice) {
        snprintf(err, n, "out of memory for %dx%d detail slices", size, size);
        input_detail_stop(d);
        return -1;
    }
    /* the read-back is already size x size: one pixel per box, the normalisation is the player's */
    if (luma_resampler_init(&d->resampler, size, size, size, d->values, err, n) != 0) {
        input_detail_stop(d);
        return -1;
    }
    input_detail_set_weights(d, 0.2126, 0.0722);
    return 0;
}

void input_detail_set_weights(struct input_detail *d, double kr, double kb)
{
    d->kr = kr;
    d->kb = kb;
}

static uint64_t hash_bytes(const uint8_t *b, size_t count)
{
    uint64_t h = UINT64_C(1469598103934665603); /* FNV-1a */
    for (size_t i = 0; i < count; i++) h = (h ^ b[i]) * UINT64_C(1099511628211);
    return h;
}

void input_detail_take(const uint8_t *rgba, void *user)
{
    struct input_detail *d = user;
    size_t count = (size_t)d->size * d->size;
    double kg = 1.0 - d->kr - d->kb;
    for (size_t i = 0; i < count; i++) {
        const uint8_t *p = rgba + 4 * i;
        d->luma[i] = (uint8_t)lrint(d->kr * p[0] + kg * p[1] + d->kb * p[2]);
    }
    const struct luma_view view = {.data = d->luma, .bytes = count, .width = d->size, .height = d->size,
                                   .stride = d->size, .step = 1};
    if (luma_to_slice(&d->resampler, &view, d->slice) != 0) return;
    uint64_t h = hash_bytes(d->luma, count);
    if (d->slices > 0 && h != d->last_hash) d->distinct++;
    d->last_hash = h;
    d->slices++;
    d->ready = true;
}

void input_detail_stop(struct input_detail *d)
{
    free(d->luma);
    free(d->values);
    free(d->slice);
    memset(d, 0, sizeof(*d));
}
