/* The fire luminance ratios (fire_metric.h). */
#include "fire_metric.h"

#include <math.h>
#include <stdlib.h>

static double srgb_decode(uint8_t v)
{
    double x = v / 255.0;
    return x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4);
}

double fire_metric_luminance(const uint8_t *rgb)
{
    return 0.2126 * srgb_decode(rgb[0]) + 0.7152 * srgb_decode(rgb[1]) + 0.0722 * srgb_decode(rgb[2]);
}

static int changed(const uint8_t *a, const uint8_t *b)
{
    for (int k = 0; k < 3; k++)
        if (abs((int)a[k] - (int)b[k]) > FIRE_METRIC_LEVELS) return 1;
    return 0;
}

void fire_metric_mask(const uint8_t *out, const uint8_t *no_fire, int width, int height, uint8_t *mask)
{
    size_t n = (size_t)width * (size_t)height;
    for (size_t i = 0; i < n; i++) mask[i] = (uint8_t)changed(out + 4 * i, no_fire + 4 * i);
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int fire_metric_ratios(const uint8_t *out, const uint8_t *background, const uint8_t *mask, int width, int height,
                       fire_ratios *r)
{
    size_t n = (size_t)width * (size_t)height;
    *r = (fire_ratios){NAN, NAN, 0};
    double *ratios = malloc((n ? n : 1) * sizeof(double));
    if (!ratios) return -1;
    for (size_t i = 0; i < n; i++) {
        if ((mask && !mask[i]) || !changed(out + 4 * i, background + 4 * i)) continue;
        /* a black background pixel: its ratio is taken against one level of light */
        double back = fmax(fire_metric_luminance(background + 4 * i), srgb_decode(1));
        ratios[r->pixels++] = fire_metric_luminance(out + 4 * i) / back;
    }
    if (r->pixels > 0) {
        qsort(ratios, (size_t)r->pixels, sizeof(double), compare_doubles);
        r->median = ratios[r->pixels / 2];
        r->p90 = ratios[(long)(0.9 * (double)(r->pixels - 1))];
    }
    free(ratios);
    return r->pixels > 0 ? 0 : -1;
}

double fire_metric_pink_share(const uint8_t *out, const uint8_t *background, const uint8_t *mask, int width,
                              int height, long *pink, long *reddish)
{
    size_t n = (size_t)width * (size_t)height;
    *pink = *reddish = 0;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *p = out + 4 * i;
        if ((mask && !mask[i]) || !changed(p, background + 4 * i)) continue;
        if ((int)p[0] - (int)p[1] <= FIRE_METRIC_REDDISH) continue;
        ++*reddish;
        if (p[2] > p[1]) ++*pink;
    }
    return *reddish > 0 ? (double)*pink / (double)*reddish : NAN;
}
