/* Image comparison and statistics of the accuracy benchmark: see bench_metrics.h. */
#include "bench_metrics.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void bench_error_add(bench_error *e, const uint8_t *gpu_rgba, const double *ref_rgb, const uint8_t *edge,
                     size_t n)
{
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            double d = fabs((double)gpu_rgba[4 * i + k] - ref_rgb[3 * i + k]);
            e->sum_abs += d;
            e->sum_sq += d * d;
            e->max_abs = fmax(e->max_abs, d);
            e->count++;
            if (edge && edge[i]) {
                e->edge_sum_abs += d;
                e->edge_sum_sq += d * d;
                e->edge_max_abs = fmax(e->edge_max_abs, d);
                e->edge_count++;
            }
        }
}

double bench_error_mean(const bench_error *e)
{
    return e->count ? e->sum_abs / (double)e->count : 0.0;
}

double bench_error_edge_mean(const bench_error *e)
{
    return e->edge_count ? e->edge_sum_abs / (double)e->edge_count : 0.0;
}

double bench_psnr(double sum_sq, size_t count)
{
    if (!count) return NAN;
    double mse = sum_sq / (double)count;
    return mse > 0.0 ? 10.0 * log10(255.0 * 255.0 / mse) : INFINITY;
}

static double inverse_at(const double *distance, int width, int x, int y)
{
    return 1.0 / distance[(size_t)y * width + x];
}

/* Second difference of 1/z across (x, y) along one axis, relative to 1/z there. */
static bool discontinuity(const double *distance, int width, int height, int x, int y, int dx, int dy,
                          double relative)
{
    int x0 = x - dx, y0 = y - dy, x1 = x + dx, y1 = y + dy;
    if (x0 < 0 || y0 < 0 || x1 >= width || y1 >= height) return false;
    double c = inverse_at(distance, width, x, y);
    double second = inverse_at(distance, width, x0, y0) - 2.0 * c + inverse_at(distance, width, x1, y1);
    return fabs(second) > relative * c;
}

static void dilate_mask(const uint8_t *in, int width, int height, int radius, uint8_t *out)
{
    /* separable: a square structuring element is a row pass then a column pass */
    uint8_t *rows = calloc((size_t)width * height, 1);
    if (!rows) {
        memcpy(out, in, (size_t)width * height);
        return;
    }
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            uint8_t v = 0;
            for (int k = -radius; k <= radius && !v; k++)
                if (x + k >= 0 && x + k < width) v = in[(size_t)y * width + x + k];
            rows[(size_t)y * width + x] = v;
        }
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            uint8_t v = 0;
            for (int k = -radius; k <= radius && !v; k++)
                if (y + k >= 0 && y + k < height) v = rows[(size_t)(y + k) * width + x];
            out[(size_t)y * width + x] = v;
        }
    free(rows);
}

void bench_edge_mask(const double *distance, int width, int height, double relative, int dilate,
                     uint8_t *mask)
{
    uint8_t *raw = calloc((size_t)width * height, 1);
    if (!raw) {
        memset(mask, 0, (size_t)width * height);
        return;
    }
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            raw[(size_t)y * width + x] = discontinuity(distance, width, height, x, y, 1, 0, relative) ||
                                         discontinuity(distance, width, height, x, y, 0, 1, relative);
    dilate_mask(raw, width, height, dilate, mask);
    free(raw);
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void bench_stats(double *values, int n, double *median, double *min, double *max)
{
    if (n <= 0) {
        *median = *min = *max = NAN;
        return;
    }
    qsort(values, (size_t)n, sizeof(double), compare_doubles);
    *min = values[0];
    *max = values[n - 1];
    *median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

void bench_pareto(const double *ms, const double *err, const bool *include, int n, bool *pareto)
{
    for (int i = 0; i < n; i++) {
        pareto[i] = include[i];
        for (int j = 0; j < n && pareto[i]; j++) {
            if (j == i || !include[j]) continue;
            bool no_worse = ms[j] <= ms[i] && err[j] <= err[i];
            bool better = ms[j] < ms[i] || err[j] < err[i];
            if (no_worse && better) pareto[i] = false;
        }
    }
}

FILE *bench_open_out(const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof(path), "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "bench: %s: %s\n", path, strerror(errno));
        exit(1);
    }
    return f;
}
