/* Detail from a recorded clip (seed figure 6, docs/design.md §2.4, docs/detail-clips.md): a video file
 * decoded with FFmpeg's libavformat/libavcodec (libswscale for the luma), its frames made into a
 * loop without a seam and written into sbfx's detail volume through sbfx_detail_push_slice.
 *
 * Steps, each callable alone (the tests check them one by one):
 * 1. clip_decode: the clip's first frames, each centre-cropped to a square and box-filtered to
 *    size x size luma means (luma.h), in [0, 255];
 * 2. clip_loop: those frames into `slices` loop slices. The loop is made of the first Lc frames,
 *    the crossfade's C frames after them blended into its head (slice k < C is
 *    w clip[k] + (1 - w) clip[Lc + k], w = k / C), so the step from the last slice to the first
 *    is the clip's own step from frame Lc - 1 to Lc (slice 0 is frame Lc). With enough frames Lc = slices
 *    and C = slices / 4 (one clip frame per slice); a shorter clip gives C = n / 5, Lc = n - C,
 *    and the loop is resampled in time (linear, wrapping) to `slices`;
 * 3. clip_normalise: every slice through the curve the camera and the procedural volume share
 *    (luma_curve) with the mean and spread of the whole loop, to half-float bits.
 * clip_detail_load does all three for a module and pushes one full turn of the ring.
 *
 * Everything is allocated in clip_detail_load and freed before it returns; nothing happens per
 * frame. A missing, unreadable, truncated or non-video file is an error naming the file. */
#ifndef SBFX_CLIP_DETAIL_H
#define SBFX_CLIP_DETAIL_H

#include <stddef.h>
#include <stdint.h>

#include "sbfx.h"

#define CLIP_MIN_FRAMES 2 /* a loop needs at least two frames */

struct clip_info {
    int width, height;        /* the clip's picture */
    char codec[32], container[32];
    double fps;               /* the stream's average frame rate (0: unknown) */
    int frames;               /* frames decoded (at most slices + slices / 4) */
    int loop_frames;          /* Lc: clip frames in the loop */
    int crossfade;            /* C: frames blended into the loop's head */
    double seam;              /* RMS difference of the normalised slices across the loop point */
    double step_median;       /* ... and of the other consecutive slices: median */
    double step_max;          /* ... and largest */
    double decode_ms, total_ms;
};

/* Up to max_frames frames of the clip as size x size box means, frame after frame, into out
 * (max_frames * size * size floats). *frames gets the count; info (optional) the stream's facts.
 * 0, or a negative errno-style code with a message naming the file. */
int clip_decode(const char *path, int size, int max_frames, float *out, int *frames,
                struct clip_info *info, char *err, size_t n);

/* n frames of size x size values -> `slices` loop slices (out: slices * size * size); see above.
 * Returns 0, or -EINVAL when n < CLIP_MIN_FRAMES. loop_frames / crossfade may be NULL. */
int clip_loop(const float *frames, int n, int size, int slices, float *out, int *loop_frames,
              int *crossfade);

/* count values -> half-float bits through luma_curve with the values' own mean and spread. */
void clip_normalise(const float *values, size_t count, uint16_t *out);

/* RMS difference between consecutive half-float slices (the ring's order, wrapping): the seam
 * (last -> first) and the median and largest of the others. */
void clip_seam(const uint16_t *slices, int size, int count, double *seam, double *median,
               double *max);

/* Decodes the clip at path, loops it and pushes it into fx's detail volume (one full turn, so
 * slice k of the loop is ring slice k of a module that has had no slice pushed yet).
 * 0, or a negative code with a message naming the file; the volume is untouched then. */
int clip_detail_load(sbfx *fx, const char *path, struct clip_info *info, char *err, size_t n);

/* "smoke.mp4: h264 in mov,mp4,m4a,3gp,3g2,mj2 640x360, 40 frames -> 32 slices (loop of 32,
 * crossfade 8), seam 0.012 (median step 0.011), 35 ms" */
void clip_describe(const char *path, const struct clip_info *info, char *out, size_t n);

#endif
