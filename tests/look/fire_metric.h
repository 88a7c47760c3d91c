/* Does fire read as light? (issue 17 item 2, docs/design.md §8; docs/look-fire.md)
 *
 * Luminance Y of the sRGB output, linearised (IEC 61966-2-1 decode), Rec. 709 weights. Fire
 * pixels: where the output differs from a background-only render of the same view by more than
 * 4 levels in some channel (and, if a mask is given, where the mask is non-zero: e.g. where the
 * fire's own emission changes the picture, for effects that also hold smoke and dust). For each
 * fire pixel the ratio Y(output) / Y(background) — how much brighter than the sky behind it the
 * fire shows; the median and the 90th percentile of those ratios. Pure C, no GL: the bench's
 * look.csv writer and the tests call it with images they read back. */
#ifndef SBFX_FIRE_METRIC_H
#define SBFX_FIRE_METRIC_H

#include <stdint.h>

#define FIRE_METRIC_LEVELS 4   /* a pixel the effect changes by more than this many levels */

typedef struct fire_ratios {
    double median, p90;  /* of Y(out) / Y(background) over the fire pixels; NAN if none */
    long pixels;         /* fire pixels counted */
} fire_ratios;

/* Y of an 8-bit sRGB-encoded pixel (rgb), linearised. */
double fire_metric_luminance(const uint8_t *rgb);

/* mask[i] = 1 where out and no_fire (the same frame with the fire's emission off) differ by more
 * than FIRE_METRIC_LEVELS in some channel: the pixels the fire's own light changes. */
void fire_metric_mask(const uint8_t *out, const uint8_t *no_fire, int width, int height, uint8_t *mask);

/* out, background: width*height RGBA8 pixels in the same row order; mask: NULL or width*height
 * bytes. Fills *r; returns 0, or -1 when there is no fire pixel or no memory (r then has NAN
 * ratios and its pixel count). */
int fire_metric_ratios(const uint8_t *out, const uint8_t *background, const uint8_t *mask, int width, int height,
                       fire_ratios *r);

/* Pink fire edges (issue 27): among the fire pixels (as for the ratios) that are reddish (red
 * above green by more than FIRE_METRIC_REDDISH levels), the share whose blue exceeds their green.
 * A black body below 6500 K, tone-mapped channel by channel, never has blue above green (the
 * bound's derivation is in docs/look-fire.md), so these are red light added to a blue sky that
 * the fire does not darken enough. pink / reddish counted; returns the share, NAN if no reddish. */
#define FIRE_METRIC_REDDISH 24
double fire_metric_pink_share(const uint8_t *out, const uint8_t *background, const uint8_t *mask, int width,
                              int height, long *pink, long *reddish);

#endif
