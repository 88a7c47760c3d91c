/* A V4L2 capture device as a source of luma frames: open, format negotiation, mmap streaming
 * with a fixed set of buffers, non-blocking dequeue of the newest frame.
 *
 * Formats, in order of preference: GREY, NV12, NV21, YUV420, YVU420, NV16, NV61, NV12M,
 * NV21M, YUV420M, YUYV, YVYU, UYVY, VYUY: anything whose plane 0 carries 8-bit luma (luma.h).
 * Single-planar (USB/UVC cameras, vivid) and multi-planar (most SoC ISPs: rkisp1, i.MX ISI)
 * capture are both handled; only plane 0 is read.
 *
 * Errors: 0 or a negative errno with a message naming the device and the ioctl:
 *   -ENOENT/-ENODEV  no such device, or it went away
 *   -ENOTTY          not a V4L2 capture device, or no streaming
 *   -EINVAL          no luma format offered
 *   -EBUSY           used by another program */
#ifndef SBFX_V4L2_SOURCE_H
#define SBFX_V4L2_SOURCE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "video/luma.h"

#define V4L2_SOURCE_BUFFERS 8  /* 4 are asked for; a driver may insist on more */

struct v4l2_source {
    int fd;                   /* -1 when closed */
    char path[128];
    char card[32];            /* the driver's name for the device */
    uint32_t buf_type;        /* V4L2_BUF_TYPE_VIDEO_CAPTURE or _MPLANE */
    uint32_t fourcc;
    int width, height, stride;
    int planes;               /* memory planes per buffer (multi-planar formats) */
    int step, offset;         /* luma layout of plane 0 */
    struct { void *start; size_t length; } buffers[V4L2_SOURCE_BUFFERS];
    int buffer_count;
    int held;                 /* index of the buffer lent out by v4l2_source_latest, or -1 */
    bool streaming;
};

/* Opens and starts streaming; asks for about want_width x want_height (0: the driver's size). */
int v4l2_source_open(struct v4l2_source *s, const char *path, int want_width, int want_height,
                     char *err, size_t n);
/* The newest complete frame, if one arrived since the last call (older ones go straight back
 * to the driver). 1 with *view set (valid until v4l2_source_release), 0 when nothing new,
 * or a negative errno when the device failed (-ENODEV: it went away). Never blocks. */
int v4l2_source_latest(struct v4l2_source *s, struct luma_view *view, char *err, size_t n);
/* Gives the frame from v4l2_source_latest back to the driver. */
int v4l2_source_release(struct v4l2_source *s, char *err, size_t n);
/* Stops streaming, unmaps, closes; safe on a closed or half-opened source. */
void v4l2_source_close(struct v4l2_source *s);
/* "640x360 YUYV" */
void v4l2_source_describe(const struct v4l2_source *s, char *out, size_t n);

#endif
