/* A video clip -> a seamless loop in sbfx's detail volume (FFmpeg's libraries). */
#include "video/clip_detail.h"

#include <errno.h>
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libswscale/swscale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "video/luma.h"

#define CLIP_MAX_SIDE 16384 /* larger pictures are refused, not allocated */

/* What one decode holds open; all of it freed by decoder_close. */
struct decoder {
    AVFormatContext *format;
    AVCodecContext *codec;
    AVPacket *packet;
    AVFrame *frame;
    struct SwsContext *sws;
    uint8_t *gray;            /* width * height luma of the current frame */
    int stream, width, height;
    struct luma_resampler resampler;
};

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

static int fail_av(const char *path, const char *what, int code, char *err, size_t n)
{
    char why[AV_ERROR_MAX_STRING_SIZE] = "";
    av_strerror(code, why, sizeof(why));
    snprintf(err, n, "detail clip %s: %s: %s", path, what, why);
    return code < 0 ? code : -EINVAL;
}

static void decoder_close(struct decoder *d)
{
    sws_freeContext(d->sws);
    av_frame_free(&d->frame);
    av_packet_free(&d->packet);
    avcodec_free_context(&d->codec);
    avformat_close_input(&d->format);
    free(d->gray);
    memset(d, 0, sizeof(*d));
}

static int open_codec(struct decoder *d, const char *path, char *err, size_t n)
{
    const AVCodec *codec = NULL;
    int rc = av_find_best_stream(d->format, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
    if (rc < 0) return fail_av(path, "no video stream FFmpeg can decode", rc, err, n);
    d->stream = rc;
    d->codec = avcodec_alloc_context3(codec);
    if (!d->codec) return fail_av(path, "out of memory for the decoder", AVERROR(ENOMEM), err, n);
    rc = avcodec_parameters_to_context(d->codec, d->format->streams[d->stream]->codecpar);
    if (rc >= 0) rc = avcodec_open2(d->codec, codec, NULL);
    if (rc < 0) return fail_av(path, "cannot open its video decoder", rc, err, n);
    d->width = d->codec->width;
    d->height = d->codec->height;
    if (d->width < 1 || d->height < 1 || d->width > CLIP_MAX_SIDE || d->height > CLIP_MAX_SIDE) {
        snprintf(err, n, "detail clip %s: picture size %dx%d is out of range (1..%d)", path,
                 d->width, d->height, CLIP_MAX_SIDE);
        return -EINVAL;
    }
    return 0;
}

static int decoder_open(struct decoder *d, const char *path, int size, float *values,
                        struct clip_info *info, char *err, size_t n)
{
    memset(d, 0, sizeof(*d));
    int rc = avformat_open_input(&d->format, path, NULL, NULL);
    if (rc < 0) return fail_av(path, "cannot open it", rc, err, n);
    rc = avformat_find_stream_info(d->format, NULL);
    if (rc < 0) return fail_av(path, "cannot read its streams", rc, err, n);
    rc = open_codec(d, path, err, n);
    if (rc) return rc;
    d->packet = av_packet_alloc();
    d->frame = av_frame_alloc();
    d->gray = malloc((size_t)d->width * d->height);
    if (!d->packet || !d->frame || !d->gray)
        return fail_av(path, "out of memory for its frames", AVERROR(ENOMEM), err, n);
    rc = luma_resampler_init(&d->resampler, size, d->width, d->height, values, err, n);
    if (rc) return rc;
    AVRational rate = d->format->streams[d->stream]->avg_frame_rate;
    info->width = d->width;
    info->height = d->height;
    info->fps = rate.den > 0 ? av_q2d(rate) : 0.0;
    snprintf(info->codec, sizeof(info->codec), "%s", d->codec->codec->name);
    snprintf(info->container, sizeof(info->container), "%s", d->format->iformat->name);
    return 0;
}

/* The decoded frame's luma (any pixel format, converted to 8-bit grey) -> box means in out. */
static int take_frame(struct decoder *d, const char *path, float *out, char *err, size_t n)
{
    AVFrame *f = d->frame;
    if (f->width != d->width || f->height != d->height) {
        snprintf(err, n, "detail clip %s: the picture changes size (%dx%d -> %dx%d)", path,
                 d->width, d->height, f->width, f->height);
        return -EINVAL;
    }
    d->sws = sws_getCachedContext(d->sws, f->width, f->height, (enum AVPixelFormat)f->format,
                                  d->width, d->height, AV_PIX_FMT_GRAY8, SWS_POINT, NULL, NULL, NULL);
    if (!d->sws) {
        snprintf(err, n, "detail clip %s: cannot convert pixel format %s to luma", path,
                 av_get_pix_fmt_name((enum AVPixelFormat)f->format));
        return -EINVAL;
    }
    uint8_t *planes[4] = {d->gray};
    int strides[4] = {d->width};
    sws_scale(d->sws, (const uint8_t *const *)f->data, f->linesize, 0, f->height, planes, strides);
    struct luma_view view = {.data = d->gray, .bytes = (size_t)d->width * d->height,
                             .width = d->width, .height = d->height, .stride = d->width, .step = 1};
    float *means = d->resampler.values;
    d->resampler.values = out;
    int rc = luma_box_means(&d->resampler, &view);
    d->resampler.values = means;
    return rc;
}

/* Receives what the decoder has; 1 when `max_frames` are in. */
static int drain(struct decoder *d, const char *path, float *out, int max_frames, int *frames,
                 char *err, size_t n)
{
    size_t slice = (size_t)d->resampler.size * d->resampler.size;
    for (;;) {
        int rc = avcodec_receive_frame(d->codec, d->frame);
        if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF) return 0;
        if (rc < 0) return fail_av(path, "cannot decode a frame", rc, err, n);
        rc = take_frame(d, path, out + (size_t)*frames * slice, err, n);
        av_frame_unref(d->frame);
        if (rc) return rc;
        if (++*frames == max_frames) return 1;
    }
}

static int decode_frames(struct decoder *d, const char *path, float *out, int max_frames,
                         int *frames, char *err, size_t n)
{
    int rc = 0;
    while (rc == 0) {
        int got = av_read_frame(d->format, d->packet);
        if (got == AVERROR_EOF) break;
        if (got < 0) return fail_av(path, "cannot read it", got, err, n);
        if (d->packet->stream_index == d->stream) {
            rc = avcodec_send_packet(d->codec, d->packet);
            if (rc < 0) rc = fail_av(path, "its video data is damaged", rc, err, n);
            else rc = drain(d, path, out, max_frames, frames, err, n);
        }
        av_packet_unref(d->packet);
    }
    if (rc == 0) { /* end of file: what the decoder still holds */
        avcodec_send_packet(d->codec, NULL);
        rc = drain(d, path, out, max_frames, frames, err, n);
    }
    return rc < 0 ? rc : 0;
}

int clip_decode(const char *path, int size, int max_frames, float *out, int *frames,
                struct clip_info *info, char *err, size_t n)
{
    struct clip_info scratch;
    if (!info) info = &scratch;
    memset(info, 0, sizeof(*info));
    *frames = 0;
    if (!path || !path[0] || size < 1 || size > LUMA_MAX_SIZE || max_frames < 1 || !out) {
        snprintf(err, n, "detail clip %s: bad arguments (size %d, %d frames)", path ? path : "(null)",
                 size, max_frames);
        return -EINVAL;
    }
    av_log_set_level(AV_LOG_QUIET); /* the error message says what failed */
    float *means = malloc((size_t)size * size * sizeof(*means));
    struct decoder d;
    int rc = means ? decoder_open(&d, path, size, means, info, err, n)
                   : fail_av(path, "out of memory", AVERROR(ENOMEM), err, n);
    double t0 = now_ms();
    if (rc == 0) rc = decode_frames(&d, path, out, max_frames, frames, err, n);
    info->decode_ms = now_ms() - t0;
    if (rc == 0 && *frames < CLIP_MIN_FRAMES) {
        snprintf(err, n, "detail clip %s: %d video frame%s decoded, a loop needs at least %d", path,
                 *frames, *frames == 1 ? "" : "s", CLIP_MIN_FRAMES);
        rc = -EINVAL;
    }
    if (means) decoder_close(&d);
    free(means);
    info->frames = *frames;
    return rc;
}

/* ---- the loop ---- */

int clip_loop(const float *frames, int n, int size, int slices, float *out, int *loop_frames,
              int *crossfade)
{
    if (n < CLIP_MIN_FRAMES || size < 1 || slices < 1) return -EINVAL;
    int c = slices / 4 > 0 ? slices / 4 : 1, lc = slices;
    if (n < slices + c) {
        c = n / 5 > 0 ? n / 5 : 1;
        lc = n - c;
    }
    size_t texels = (size_t)size * size;
    for (int s = 0; s < slices; s++) {
        /* slice s sits at loop time s * lc / slices, between loop frames k0 and k0 + 1 */
        double t = (double)s * lc / slices;
        int k0 = (int)t;
        float f = (float)(t - k0);
        int k[2] = {k0 % lc, (k0 + 1) % lc};
        float *o = out + (size_t)s * texels;
        for (size_t i = 0; i < texels; i++) {
            float v[2];
            for (int j = 0; j < 2; j++) {
                float head = frames[(size_t)k[j] * texels + i];
                float w = (float)k[j] / (float)c;
                v[j] = k[j] < c ? w * head + (1.0f - w) * frames[(size_t)(lc + k[j]) * texels + i] : head;
            }
            o[i] = v[0] + f * (v[1] - v[0]);
        }
    }
    if (loop_frames) *loop_frames = lc;
    if (crossfade) *crossfade = c;
    return 0;
}

void clip_normalise(const float *values, size_t count, uint16_t *out)
{
    double sum = 0.0, sum2 = 0.0;
    for (size_t i = 0; i < count; i++) {
        sum += values[i];
        sum2 += (double)values[i] * values[i];
    }
    double mean = count ? sum / (double)count : 0.0;
    double var = count ? sum2 / (double)count - mean * mean : 0.0;
    float spread = var > 0.0 ? (float)sqrt(var) : 0.0f;
    for (size_t i = 0; i < count; i++) out[i] = luma_half_bits(luma_curve(values[i], (float)mean, spread));
}

static float half_value(uint16_t bits)
{
    _Float16 h;
    memcpy(&h, &bits, sizeof(h));
    return (float)h;
}

static double slice_rms(const uint16_t *a, const uint16_t *b, size_t texels)
{
    double sum = 0.0;
    for (size_t i = 0; i < texels; i++) {
        double d = (double)half_value(a[i]) - half_value(b[i]);
        sum += d * d;
    }
    return sqrt(sum / (double)texels);
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void clip_seam(const uint16_t *slices, int size, int count, double *seam, double *median, double *max)
{
    size_t texels = (size_t)size * size;
    double steps[1024];
    int m = 0;
    *seam = *median = *max = 0.0;
    if (count < 2) return;
    *seam = slice_rms(slices + (size_t)(count - 1) * texels, slices, texels);
    for (int k = 0; k + 1 < count && m < 1024; k++, m++)
        steps[m] = slice_rms(slices + (size_t)k * texels, slices + (size_t)(k + 1) * texels, texels);
    qsort(steps, (size_t)m, sizeof(steps[0]), compare_double);
    *median = m % 2 ? steps[m / 2] : 0.5 * (steps[m / 2 - 1] + steps[m / 2]);
    *max = steps[m - 1];
}

/* ---- into the module ---- */

static int push_turn(sbfx *fx, const uint16_t *halves, int size, int slices, const char *path,
                     char *err, size_t n)
{
    for (int k = 0; k < slices; k++) {
        if (sbfx_detail_push_slice(fx, halves + (size_t)k * size * size, size) != SBFX_OK) {
            snprintf(err, n, "detail clip %s: cannot write the detail volume: %s", path,
                     sbfx_last_error(fx));
            return -EIO;
        }
    }
    return 0;
}

int clip_detail_load(sbfx *fx, const char *path, struct clip_info *info, char *err, size_t n)
{
    struct clip_info scratch;
    if (!info) info = &scratch;
    double t0 = now_ms();
    int size = 0, slices = 0;
    sbfx_detail_dimensions(fx, &size, &slices);
    if (size < 1 || size > LUMA_MAX_SIZE || slices < 1) {
        snprintf(err, n, "detail clip %s: the detail volume is %dx%dx%d, cannot feed it", path, size,
                 size, slices);
        return -EINVAL;
    }
    int max_frames = slices + (slices / 4 > 0 ? slices / 4 : 1), frames = 0;
    size_t texels = (size_t)size * size;
    float *decoded = malloc((size_t)max_frames * texels * sizeof(*decoded));
    float *loop = malloc((size_t)slices * texels * sizeof(*loop));
    uint16_t *halves = malloc((size_t)slices * texels * sizeof(*halves));
    int rc = decoded && loop && halves ? 0 : fail_av(path, "out of memory", AVERROR(ENOMEM), err, n);
    if (rc == 0) rc = clip_decode(path, size, max_frames, decoded, &frames, info, err, n);
    if (rc == 0) {
        clip_loop(decoded, frames, size, slices, loop, &info->loop_frames, &info->crossfade);
        clip_normalise(loop, (size_t)slices * texels, halves);
        clip_seam(halves, size, slices, &info->seam, &info->step_median, &info->step_max);
        rc = push_turn(fx, halves, size, slices, path, err, n);
    }
    free(decoded);
    free(loop);
    free(halves);
    info->total_ms = now_ms() - t0;
    return rc;
}

void clip_describe(const char *path, const struct clip_info *info, char *out, size_t n)
{
    const char *name = strrchr(path, '/');
    snprintf(out, n, "%s: %s in %s %dx%d, %d frames -> loop of %d (crossfade %d), seam %.4f "
             "(consecutive slices: median %.4f, max %.4f), %.0f ms",
             name ? name + 1 : path, info->codec, info->container, info->width, info->height,
             info->frames, info->loop_frames, info->crossfade, info->seam, info->step_median,
             info->step_max, info->total_ms);
}
