/* The spectrum exponent of the picture's fine structure: see look_metrics.h. */
#include "look_metrics.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

int look_scale(int i) { return 2 << i; }

static double srgb_to_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

void look_luminance(const uint8_t *rgba, size_t n, double *y)
{
    double table[256];
    for (int i = 0; i < 256; i++) table[i] = srgb_to_linear(i / 255.0);
    for (size_t i = 0; i < n; i++)
        y[i] = 0.2126 * table[rgba[4 * i]] + 0.7152 * table[rgba[4 * i + 1]] + 0.0722 * table[rgba[4 * i + 2]];
}

/* Largest minus smallest of channel c over the 3x3 neighbourhood of (x, y), clamped. */
static int span3x3(const uint8_t *rgba, int w, int h, int x, int y, int c)
{
    int lo = 255, hi = 0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            int xx = x + dx < 0 ? 0 : x + dx >= w ? w - 1 : x + dx;
            int yy = y + dy < 0 ? 0 : y + dy >= h ? h - 1 : y + dy;
            int v = rgba[4 * ((size_t)yy * w + xx) + c];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
    return hi - lo;
}

static bool effect_changes(const uint8_t *out, const uint8_t *bg)
{
    for (int c = 0; c < 3; c++)
        if (abs((int)out[c] - (int)bg[c]) > LOOK_CHANGE_LEVELS) return true;
    return false;
}

static bool background_smooth(const uint8_t *bg, int w, int h, int x, int y)
{
    for (int c = 0; c < 3; c++)
        if (span3x3(bg, w, h, x, y, c) > LOOK_SMOOTH_LEVELS) return false;
    return true;
}

size_t look_effect_mask(const uint8_t *out_rgba, const uint8_t *background_rgba, int width, int height,
                        uint8_t *mask)
{
    size_t count = 0;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            size_t i = (size_t)y * width + x;
            mask[i] = effect_changes(out_rgba + 4 * i, background_rgba + 4 * i) &&
                      background_smooth(background_rgba, width, height, x, y);
            count += mask[i];
        }
    return count;
}

/* Chebyshev distance to the nearest pixel outside the mask (the image's border counts as
 * outside): two passes of the 8-neighbour chamfer with unit weights, exact for this metric. */
static void chessboard_distance(const uint8_t *mask, int w, int h, int *d)
{
    const int far = w + h;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * w + x;
            if (!mask[i]) { d[i] = 0; continue; }
            int best = far;
            if (x == 0 || y == 0) best = 1;
            else {
                int n[4] = {d[i - 1], d[i - w], d[i - w - 1], x + 1 < w ? d[i - w + 1] : 0};
                for (int k = 0; k < 4; k++) best = n[k] + 1 < best ? n[k] + 1 : best;
            }
            d[i] = best;
        }
    for (int y = h - 1; y >= 0; y--)
        for (int x = w - 1; x >= 0; x--) {
            size_t i = (size_t)y * w + x;
            if (!d[i]) continue;
            int best = d[i];
            if (x == w - 1 || y == h - 1) best = 1;
            else {
                int n[4] = {d[i + 1], d[i + w], d[i + w + 1], x > 0 ? d[i + w - 1] : 0};
                for (int k = 0; k < 4; k++) best = n[k] + 1 < best ? n[k] + 1 : best;
            }
            d[i] = best;
        }
}

/* Separable Gaussian of standard deviation sigma (radius 4 sigma, clamped at the border).
 * Both passes sweep whole rows per tap (tap outer, pixel inner): each pixel still sums its taps
 * in the order -r..r, so the result is bit for bit the per-pixel loop's, but the vertical pass
 * reads rows in order instead of a column per pixel (issue 26: test_gl_look spent most of its time
 * here, 266 million strided reads per blur at the 32 px scale). */
static void blur_row(const double *k, int r, const double *in, int w, double *acc)
{
    for (int x = 0; x < w; x++) acc[x] = 0.0;
    for (int i = -r; i <= r; i++) {
        double ki = k[i + r];
        int lo = -i > 0 ? -i : 0, hi = w - i < w ? w - i : w; /* x + i inside [0, w) */
        if (lo > w) lo = w;
        if (hi < 0) hi = 0;
        for (int x = 0; x < lo; x++) acc[x] += ki * in[0];
        for (int x = lo; x < hi; x++) acc[x] += ki * in[x + i];
        for (int x = hi > lo ? hi : lo; x < w; x++) acc[x] += ki * in[w - 1];
    }
}

static void gaussian_blur(const double *in, int w, int h, double sigma, double *tmp, double *out)
{
    int r = (int)ceil(4.0 * sigma);
    double *k = malloc(sizeof(double) * (size_t)(2 * r + 1)), sum = 0.0;
    if (!k) return;
    for (int i = -r; i <= r; i++) sum += k[i + r] = exp(-0.5 * i * i / (sigma * sigma));
    for (int i = 0; i <= 2 * r; i++) k[i] /= sum;
    for (int y = 0; y < h; y++) blur_row(k, r, in + (size_t)y * w, w, tmp + (size_t)y * w);
    for (int y = 0; y < h; y++) {
        double *acc = out + (size_t)y * w;
        for (int x = 0; x < w; x++) acc[x] = 0.0;
        for (int i = -r; i <= r; i++) {
            int yy = y + i < 0 ? 0 : y + i >= h ? h - 1 : y + i;
            const double *row = tmp + (size_t)yy * w;
            double ki = k[i + r];
            for (int x = 0; x < w; x++) acc[x] += ki * row[x];
        }
    }
    free(k);
}

double look_beta_fit(const double energy[LOOK_SCALES], int first, int last)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (int i = first; i <= last; i++) {
        if (!(energy[i] > 0.0) || !isfinite(energy[i])) return NAN;
        double x = log((double)look_scale(i)), y = log(energy[i]);
        sx += x, sy += y, sxx += x * x, sxy += x * y, n++;
    }
    double den = n * sxx - sx * sx;
    return n >= 2 && den > 0 ? 2.0 + (n * sxy - sx * sy) / den : NAN;
}

int look_measure(const double *y, const uint8_t *mask, int width, int height, look_spectrum *out)
{
    size_t n = (size_t)width * height;
    double *blur[2] = {malloc(n * sizeof(double)), malloc(n * sizeof(double))};
    double *tmp = malloc(n * sizeof(double));
    int *dist = malloc(n * sizeof(int));
    int rc = -1;
    memset(out, 0, sizeof(*out));
    if (!blur[0] || !blur[1] || !tmp || !dist) goto done;
    chessboard_distance(mask, width, height, dist);
    for (size_t i = 0; i < n; i++) out->mask_pixels += mask[i] != 0;
    gaussian_blur(y, width, height, 1.0, tmp, blur[0]); /* G_{s/2} of s = 2 */
    for (int s = 0; s < LOOK_SCALES; s++) {
        double *fine = blur[s & 1], *coarse = blur[(s + 1) & 1];
        gaussian_blur(y, width, height, look_scale(s), tmp, coarse);
        double sum = 0.0;
        size_t count = 0;
        for (size_t i = 0; i < n; i++)
            if (dist[i] > 2 * look_scale(s)) {
                double d = fine[i] - coarse[i];
                sum += d * d;
                count++;
            }
        out->energy[s] = count ? sum / (double)count : NAN;
        out->pixels[s] = count;
    }
    out->beta = look_beta_fit(out->energy, 1, LOOK_SCALES - 1);
    out->beta_coarse = look_beta_fit(out->energy, 2, LOOK_SCALES - 1);
    rc = 0;
done:
    free(blur[0]);
    free(blur[1]);
    free(tmp);
    free(dist);
    return rc;
}

int look_measure_rgba(const uint8_t *out_rgba, const uint8_t *background_rgba, int width, int height,
                      look_spectrum *out)
{
    size_t n = (size_t)width * height;
    uint8_t *mask = malloc(n);
    double *y = malloc(n * sizeof(double));
    int rc = -1;
    if (mask && y) {
        look_effect_mask(out_rgba, background_rgba, width, height, mask);
        look_luminance(out_rgba, n, y);
        rc = look_measure(y, mask, width, height, out);
    }
    free(mask);
    free(y);
    return rc;
}

double look_band_fine(const look_spectrum *s) { return s->energy[1] + s->energy[2]; }
double look_band_coarse(const look_spectrum *s) { return s->energy[3] + s->energy[4]; }
