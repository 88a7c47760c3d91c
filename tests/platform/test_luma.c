/* Camera luma -> detail slices (platform/video/luma.c): layouts, crop, normalisation, bounds. */
#include <errno.h>
#include <linux/videodev2.h>
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "video/luma.h"

#define W 64
#define H 48
#define S 16

static float half_value(uint16_t bits)
{
    _Float16 h;
    memcpy(&h, &bits, sizeof(h));
    return (float)h;
}

static void slice_stats(const uint16_t *slice, int count, double *mean, double *lo, double *hi)
{
    double sum = 0.0;
    *lo = 1e9, *hi = -1e9;
    for (int i = 0; i < count; i++) {
        double v = half_value(slice[i]);
        sum += v;
        if (v < *lo) *lo = v;
        if (v > *hi) *hi = v;
    }
    *mean = sum / count;
}

static uint8_t pattern(int x, int y)
{
    return (uint8_t)((x * 7 + y * 13) % 200 + 20);
}

CHECK_TEST(grey_gradient_is_normalised)
{
    static uint8_t grey[W * H];
    static float values[S * S];
    static uint16_t slice[S * S];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) grey[y * W + x] = (uint8_t)(x * 4);
    struct luma_resampler r;
    char err[256];
    CHECK(luma_resampler_init(&r, S, W, H, values, err, sizeof(err)) == 0, "%s", err);
    struct luma_view v = {.data = grey, .bytes = sizeof(grey), .width = W, .height = H, .stride = W, .step = 1};
    CHECK(luma_to_slice(&r, &v, slice) == 0);
    double mean, lo, hi;
    slice_stats(slice, S * S, &mean, &lo, &hi);
    CHECK_NEAR(mean, 0.5, 0.02);
    CHECK(lo > 0.0 && hi < 1.0 && hi - lo > 0.3, "range %g..%g", lo, hi);
    /* left to right the luma grows, so the slice does too */
    CHECK(half_value(slice[0]) < half_value(slice[S - 1]));
}

CHECK_TEST(yuyv_uyvy_and_grey_agree)
{
    static uint8_t grey[W * H], yuyv[W * H * 2], uyvy[W * H * 2];
    static float values[S * S];
    static uint16_t a[S * S], b[S * S], c[S * S];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            uint8_t l = pattern(x, y);
            grey[y * W + x] = l;
            yuyv[(y * W + x) * 2] = l, yuyv[(y * W + x) * 2 + 1] = 128;
            uyvy[(y * W + x) * 2] = 90, uyvy[(y * W + x) * 2 + 1] = l;
        }
    int step, offset;
    CHECK(luma_layout(V4L2_PIX_FMT_UYVY, &step, &offset) && step == 2 && offset == 1);
    CHECK(luma_layout(V4L2_PIX_FMT_NV12, &step, &offset) && step == 1 && offset == 0);
    CHECK(!luma_layout(V4L2_PIX_FMT_RGB24, &step, &offset));
    struct luma_resampler r;
    char err[256];
    struct luma_view g = {grey, sizeof(grey), W, H, W, 1, 0};
    struct luma_view y2 = {yuyv, sizeof(yuyv), W, H, W * 2, 2, 0};
    struct luma_view u2 = {uyvy, sizeof(uyvy), W, H, W * 2, 2, 1};
    CHECK(luma_resampler_init(&r, S, W, H, values, err, sizeof(err)) == 0);
    CHECK(luma_to_slice(&r, &g, a) == 0);
    CHECK(luma_resampler_init(&r, S, W, H, values, err, sizeof(err)) == 0);
    CHECK(luma_to_slice(&r, &y2, b) == 0);
    CHECK(luma_resampler_init(&r, S, W, H, values, err, sizeof(err)) == 0);
    CHECK(luma_to_slice(&r, &u2, c) == 0);
    CHECK(memcmp(a, b, sizeof(a)) == 0, "GREY and YUYV slices differ");
    CHECK(memcmp(a, c, sizeof(a)) == 0, "GREY and UYVY slices differ");
}

CHECK_TEST(flat_picture_is_half)
{
    static uint8_t grey[W * H];
    static float values[S * S];
    static uint16_t slice[S * S];
    memset(grey, 77, sizeof(grey));
    struct luma_resampler r;
    char err[256];
    CHECK(luma_resampler_init(&r, S, W, H, values, err, sizeof(err)) == 0);
    struct luma_view v = {grey, sizeof(grey), W, H, W, 1, 0};
    CHECK(luma_to_slice(&r, &v, slice) == 0);
    for (int i = 0; i < S * S; i++) CHECK(half_value(slice[i]) == 0.5f, "texel %d", i);
}

CHECK_TEST(crop_is_centred_square)
{
    /* a wide frame whose left and right quarters are black and the centre bright: the crop
     * sees only the centre, so the slice is flat */
    static uint8_t grey[W * H];
    static float values[S * S];
    static uint16_t slice[S * S];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) grey[y * W + x] = (x < (W - H) / 2 || x >= (W + H) / 2) ? 0 : 200;
    struct luma_resampler r;
    char err[256];
    CHECK(luma_resampler_init(&r, S, W, H, values, err, sizeof(err)) == 0);
    struct luma_view v = {grey, sizeof(grey), W, H, W, 1, 0};
    CHECK(luma_to_slice(&r, &v, slice) == 0);
    for (int i = 0; i < S * S; i++) CHECK(half_value(slice[i]) == 0.5f, "texel %d sees the border", i);
}

CHECK_TEST(bad_views_are_rejected)
{
    static uint8_t grey[W * H];
    static float values[S * S];
    static uint16_t slice[S * S];
    struct luma_resampler r;
    char err[256];
    CHECK(luma_resampler_init(&r, 0, W, H, values, err, sizeof(err)) == -EINVAL);
    CHECK(luma_resampler_init(&r, LUMA_MAX_SIZE + 1, W, H, values, err, sizeof(err)) == -EINVAL);
    CHECK(luma_resampler_init(&r, S, W, H, values, err, sizeof(err)) == 0);
    struct luma_view shortv = {grey, sizeof(grey) - 1, W, H, W, 1, 0};
    CHECK(luma_to_slice(&r, &shortv, slice) == -EINVAL, "a short buffer must not be read");
    struct luma_view other = {grey, sizeof(grey), W / 2, H, W, 1, 0};
    CHECK(luma_to_slice(&r, &other, slice) == -EINVAL, "another frame size must be rejected");
    struct luma_view null = {NULL, sizeof(grey), W, H, W, 1, 0};
    CHECK(luma_to_slice(&r, &null, slice) == -EINVAL);
}

CHECK_TEST(tiny_frame_upsamples)
{
    static uint8_t grey[4 * 3] = {0, 50, 100, 150, 10, 60, 110, 160, 20, 70, 120, 170};
    static float values[S * S];
    static uint16_t slice[S * S];
    struct luma_resampler r;
    char err[256];
    CHECK(luma_resampler_init(&r, S, 4, 3, values, err, sizeof(err)) == 0);
    struct luma_view v = {grey, sizeof(grey), 4, 3, 4, 1, 0};
    CHECK(luma_to_slice(&r, &v, slice) == 0);
    for (int i = 0; i < S * S; i++) CHECK_FINITE(half_value(slice[i]));
}

CHECK_TEST(half_bits_round_to_nearest_even)
{
    CHECK(luma_half_bits(0.0f) == 0x0000);
    CHECK(luma_half_bits(0.5f) == 0x3800);
    CHECK(luma_half_bits(1.0f) == 0x3c00);
    /* 1 + 2^-11 is halfway between 1 and the next half (1 + 2^-10): even mantissa wins */
    CHECK(luma_half_bits(1.0f + 1.0f / 2048.0f) == 0x3c00);
    CHECK(luma_half_bits(1.0f + 3.0f / 2048.0f) == 0x3c02);
}

int main(int argc, char **argv)
{
    return check_main_args(argc, argv);
}
