/* Camera luma -> half-float detail slices: box filter, automatic gain and contrast, tanh. */
#include "video/luma.h"

#include <errno.h>
#include <linux/videodev2.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define OUTPUT_GAIN 0.45f  /* the procedural volume's curve (src/tables/detail_gen.c) */
#define SMOOTHING 0.2f     /* weight of a new frame's mean and spread */
#define FLAT_SPREAD 0.5f   /* below half a luma level the picture is flat: all 0.5 */

bool luma_layout(uint32_t fourcc, int *step, int *offset)
{
    switch (fourcc) {
    case V4L2_PIX_FMT_GREY:
    case V4L2_PIX_FMT_NV12:
    case V4L2_PIX_FMT_NV21:
    case V4L2_PIX_FMT_NV16:
    case V4L2_PIX_FMT_NV61:
    case V4L2_PIX_FMT_NV12M:
    case V4L2_PIX_FMT_NV21M:
    case V4L2_PIX_FMT_YUV420:
    case V4L2_PIX_FMT_YVU420:
    case V4L2_PIX_FMT_YUV420M:
        *step = 1, *offset = 0;
        return true;
    case V4L2_PIX_FMT_YUYV:
    case V4L2_PIX_FMT_YVYU:
        *step = 2, *offset = 0;
        return true;
    case V4L2_PIX_FMT_UYVY:
    case V4L2_PIX_FMT_VYUY:
        *step = 2, *offset = 1;
        return true;
    default:
        return false;
    }
}

/* Box edges of `size` texels over a centred square of `side` pixels starting at `start`; every
 * box holds at least one pixel, also when the frame is smaller than the slice. */
static void plan_axis(int *edges, int size, int start, int side)
{
    for (int i = 0; i <= size; i++) edges[i] = start + (int)((long long)i * side / size);
}

int luma_resampler_init(struct luma_resampler *r, int size, int width, int height, float *values,
                        char *err, size_t n)
{
    if (size < 1 || size > LUMA_MAX_SIZE || width < 1 || height < 1 || !values) {
        snprintf(err, n, "detail slice %d texels from a %dx%d frame: sizes out of range (1..%d)",
                 size, width, height, LUMA_MAX_SIZE);
        return -EINVAL;
    }
    memset(r, 0, sizeof(*r));
    r->size = size;
    r->width = width;
    r->height = height;
    r->values = values;
    int side = width < height ? width : height;
    plan_axis(r->x0, size, (width - side) / 2, side);
    plan_axis(r->y0, size, (height - side) / 2, side);
    return 0;
}

static int box_step(int length)
{
    int step = length / LUMA_MAX_SAMPLES;
    return step > 1 ? step : 1;
}

/* Mean luma of the box [x0, x1) x [y0, y1), sampled on a grid of at most LUMA_MAX_SAMPLES
 * (+1) points per axis; an empty box reads its first pixel. */
static float box_mean(const struct luma_view *v, int x0, int x1, int y0, int y1)
{
    if (x1 <= x0) x1 = x0 + 1;
    if (y1 <= y0) y1 = y0 + 1;
    int sx = box_step(x1 - x0), sy = box_step(y1 - y0);
    unsigned sum = 0, count = 0;
    for (int y = y0; y < y1; y += sy) {
        const uint8_t *row = v->data + (size_t)y * v->stride + v->offset;
        for (int x = x0; x < x1; x += sx, count++) sum += row[(size_t)x * v->step];
    }
    return (float)sum / (float)count;
}

static void sample_boxes(struct luma_resampler *r, const struct luma_view *v)
{
    int size = r->size;
    for (int j = 0; j < size; j++) {
        int y0 = r->y0[j], y1 = r->y0[j + 1];
        if (y0 >= v->height) y0 = v->height - 1;
        for (int i = 0; i < size; i++) {
            int x0 = r->x0[i], x1 = r->x0[i + 1];
            if (x0 >= v->width) x0 = v->width - 1;
            r->values[(size_t)j * size + i] = box_mean(v, x0, x1, y0, y1);
        }
    }
}

/* Mean and standard deviation of this slice, blended into the running ones. */
static void update_stats(struct luma_resampler *r)
{
    size_t count = (size_t)r->size * r->size;
    double sum = 0.0, sum2 = 0.0;
    for (size_t i = 0; i < count; i++) {
        sum += r->values[i];
        sum2 += (double)r->values[i] * r->values[i];
    }
    double mean = sum / (double)count;
    double var = sum2 / (double)count - mean * mean;
    float spread = var > 0.0 ? (float)sqrt(var) : 0.0f;
    float w = r->have_stats ? SMOOTHING : 1.0f;
    r->mean += w * ((float)mean - r->mean);
    r->spread += w * (spread - r->spread);
    r->have_stats = true;
}

uint16_t luma_half_bits(float v)
{
    _Float16 h = (_Float16)v;
    uint16_t bits;
    memcpy(&bits, &h, sizeof(bits));
    return bits;
}

static bool view_fits(const struct luma_resampler *r, const struct luma_view *v)
{
    if (!v->data || v->width != r->width || v->height != r->height) return false;
    if (v->step < 1 || v->offset < 0 || v->stride < (v->width - 1) * v->step + v->offset + 1)
        return false;
    size_t last = (size_t)(v->height - 1) * v->stride + (size_t)(v->width - 1) * v->step + v->offset;
    return last < v->bytes;
}

int luma_box_means(struct luma_resampler *r, const struct luma_view *view)
{
    if (!r->values || !view_fits(r, view)) return -EINVAL;
    sample_boxes(r, view);
    return 0;
}

float luma_curve(float value, float mean, float spread)
{
    float gain = spread > FLAT_SPREAD ? OUTPUT_GAIN / spread : 0.0f;
    return 0.5f + 0.5f * tanhf(gain * (value - mean));
}

int luma_to_slice(struct luma_resampler *r, const struct luma_view *view, uint16_t *out)
{
    if (!out || luma_box_means(r, view) != 0) return -EINVAL;
    update_stats(r);
    size_t count = (size_t)r->size * r->size;
    for (size_t i = 0; i < count; i++) out[i] = luma_half_bits(luma_curve(r->values[i], r->mean, r->spread));
    return 0;
}
