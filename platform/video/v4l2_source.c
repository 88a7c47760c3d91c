/* V4L2 capture: mmap streaming, newest frame wins, never blocks (the fd is O_NONBLOCK). */
#include "video/v4l2_source.h"

#include <errno.h>
#include <fcntl.h>
#include <linux/videodev2.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#define ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))
#define BUFFERS_WANTED 4

static const uint32_t preferred[] = {
    V4L2_PIX_FMT_GREY, V4L2_PIX_FMT_NV12, V4L2_PIX_FMT_NV21, V4L2_PIX_FMT_YUV420,
    V4L2_PIX_FMT_YVU420, V4L2_PIX_FMT_NV16, V4L2_PIX_FMT_NV61, V4L2_PIX_FMT_NV12M,
    V4L2_PIX_FMT_NV21M, V4L2_PIX_FMT_YUV420M, V4L2_PIX_FMT_YUYV, V4L2_PIX_FMT_YVYU,
    V4L2_PIX_FMT_UYVY, V4L2_PIX_FMT_VYUY,
};

static int xioctl(int fd, unsigned long request, void *arg)
{
    int r;
    do r = ioctl(fd, request, arg);
    while (r == -1 && errno == EINTR);
    return r;
}

static void fourcc_text(uint32_t f, char out[5])
{
    for (int i = 0; i < 4; i++) {
        char c = (char)((f >> (8 * i)) & 0xff);
        out[i] = c >= 32 && c < 127 ? c : '?';
    }
    out[4] = '\0';
}

/* "VIDIOC_X failed: why" into err; returns -errno. */
static int fail(const struct v4l2_source *s, const char *what, char *err, size_t n)
{
    int rc = -errno;
    snprintf(err, n, "video %s: %s: %s", s->path, what, strerror(errno));
    return rc ? rc : -EIO;
}

static bool mplane(const struct v4l2_source *s)
{
    return s->buf_type == V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE;
}

static int open_node(struct v4l2_source *s, char *err, size_t n)
{
    s->fd = open(s->path, O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (s->fd < 0) return fail(s, "cannot open it", err, n);
    struct stat st;
    if (fstat(s->fd, &st) != 0) return fail(s, "fstat", err, n);
    if (!S_ISCHR(st.st_mode)) {
        snprintf(err, n, "video %s: not a device node", s->path);
        return -ENOTTY;
    }
    return 0;
}

static int query_caps(struct v4l2_source *s, char *err, size_t n)
{
    struct v4l2_capability cap;
    memset(&cap, 0, sizeof(cap));
    if (xioctl(s->fd, VIDIOC_QUERYCAP, &cap) != 0)
        return fail(s, "VIDIOC_QUERYCAP (is it a V4L2 device?)", err, n);
    snprintf(s->card, sizeof(s->card), "%s", (const char *)cap.card);
    uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
    if (caps & V4L2_CAP_VIDEO_CAPTURE) s->buf_type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    else if (caps & V4L2_CAP_VIDEO_CAPTURE_MPLANE) s->buf_type = V4L2_BUF_TYPE_VIDEO_CAPTURE_MPLANE;
    else {
        snprintf(err, n, "video %s (%s): not a video capture device (capabilities 0x%08x)",
                 s->path, s->card, caps);
        return -ENOTTY;
    }
    if (!(caps & V4L2_CAP_STREAMING)) {
        snprintf(err, n, "video %s (%s): no streaming I/O", s->path, s->card);
        return -ENOTTY;
    }
    return 0;
}

static int rank(uint32_t fourcc)
{
    for (size_t i = 0; i < ARRAY_SIZE(preferred); i++)
        if (preferred[i] == fourcc) return (int)i;
    return -1;
}

/* The most preferred luma format the device offers; the offered list goes into err if none. */
static int choose_format(struct v4l2_source *s, uint32_t *out, char *err, size_t n)
{
    int best = -1;
    char offered[160] = "";
    for (uint32_t i = 0; i < 256; i++) {
        struct v4l2_fmtdesc d = {.index = i, .type = s->buf_type};
        if (xioctl(s->fd, VIDIOC_ENUM_FMT, &d) != 0) break;
        int r = rank(d.pixelformat);
        if (r >= 0 && (best < 0 || r < best)) best = r;
        char f[5];
        fourcc_text(d.pixelformat, f);
        size_t used = strlen(offered);
        if (used + 6 < sizeof(offered)) snprintf(offered + used, sizeof(offered) - used, " %s", f);
    }
    if (best < 0) {
        snprintf(err, n, "video %s (%s): no 8-bit luma format among:%s", s->path, s->card,
                 offered[0] ? offered : " (none listed)");
        return -EINVAL;
    }
    *out = preferred[best];
    return 0;
}

static void read_format(struct v4l2_source *s, const struct v4l2_format *f)
{
    if (mplane(s)) {
        s->fourcc = f->fmt.pix_mp.pixelformat;
        s->width = (int)f->fmt.pix_mp.width;
        s->height = (int)f->fmt.pix_mp.height;
        s->stride = (int)f->fmt.pix_mp.plane_fmt[0].bytesperline;
        s->planes = f->fmt.pix_mp.num_planes ? f->fmt.pix_mp.num_planes : 1;
    } else {
        s->fourcc = f->fmt.pix.pixelformat;
        s->width = (int)f->fmt.pix.width;
        s->height = (int)f->fmt.pix.height;
        s->stride = (int)f->fmt.pix.bytesperline;
        s->planes = 1;
    }
}

static int set_format(struct v4l2_source *s, int want_w, int want_h, char *err, size_t n)
{
    uint32_t fourcc = 0;
    int rc = choose_format(s, &fourcc, err, n);
    if (rc) return rc;
    struct v4l2_format f = {.type = s->buf_type};
    if (xioctl(s->fd, VIDIOC_G_FMT, &f) != 0) return fail(s, "VIDIOC_G_FMT", err, n);
    if (mplane(s)) {
        f.fmt.pix_mp.pixelformat = fourcc;
        if (want_w > 0) f.fmt.pix_mp.width = (uint32_t)want_w, f.fmt.pix_mp.height = (uint32_t)want_h;
        f.fmt.pix_mp.field = V4L2_FIELD_NONE;
    } else {
        f.fmt.pix.pixelformat = fourcc;
        if (want_w > 0) f.fmt.pix.width = (uint32_t)want_w, f.fmt.pix.height = (uint32_t)want_h;
        f.fmt.pix.field = V4L2_FIELD_NONE;
    }
    if (xioctl(s->fd, VIDIOC_S_FMT, &f) != 0) return fail(s, "VIDIOC_S_FMT", err, n);
    read_format(s, &f);
    if (!luma_layout(s->fourcc, &s->step, &s->offset) || s->width < 1 || s->height < 1) {
        char got[5];
        fourcc_text(s->fourcc, got);
        snprintf(err, n, "video %s (%s): the driver set %dx%d %s, not a luma format", s->path,
                 s->card, s->width, s->height, got);
        return -EINVAL;
    }
    if (s->stride < s->width * s->step) s->stride = s->width * s->step;
    return 0;
}

static void init_buffer(const struct v4l2_source *s, struct v4l2_buffer *b,
                        struct v4l2_plane planes[VIDEO_MAX_PLANES], uint32_t index)
{
    memset(b, 0, sizeof(*b));
    b->type = s->buf_type;
    b->memory = V4L2_MEMORY_MMAP;
    b->index = index;
    if (mplane(s)) {
        memset(planes, 0, sizeof(struct v4l2_plane) * VIDEO_MAX_PLANES);
        b->m.planes = planes;
        b->length = (uint32_t)s->planes;
    }
}

static int map_buffer(struct v4l2_source *s, uint32_t i, char *err, size_t n)
{
    struct v4l2_buffer b;
    struct v4l2_plane planes[VIDEO_MAX_PLANES];
    init_buffer(s, &b, planes, i);
    if (xioctl(s->fd, VIDIOC_QUERYBUF, &b) != 0) return fail(s, "VIDIOC_QUERYBUF", err, n);
    size_t length = mplane(s) ? planes[0].length : b.length;
    off_t offset = mplane(s) ? (off_t)planes[0].m.mem_offset : (off_t)b.m.offset;
    void *p = mmap(NULL, length, PROT_READ | PROT_WRITE, MAP_SHARED, s->fd, offset);
    if (p == MAP_FAILED) return fail(s, "mmap of a capture buffer", err, n);
    s->buffers[i].start = p;
    s->buffers[i].length = length;
    s->buffer_count = (int)i + 1;
    if (xioctl(s->fd, VIDIOC_QBUF, &b) != 0) return fail(s, "VIDIOC_QBUF", err, n);
    return 0;
}

static int start_streaming(struct v4l2_source *s, char *err, size_t n)
{
    struct v4l2_requestbuffers req = {.count = BUFFERS_WANTED, .type = s->buf_type,
                                      .memory = V4L2_MEMORY_MMAP};
    if (xioctl(s->fd, VIDIOC_REQBUFS, &req) != 0) return fail(s, "VIDIOC_REQBUFS (mmap)", err, n);
    if (req.count < 2 || req.count > V4L2_SOURCE_BUFFERS) {
        snprintf(err, n, "video %s: the driver gave %u buffers, need 2..%d", s->path, req.count,
                 V4L2_SOURCE_BUFFERS);
        return -ENOMEM;
    }
    for (uint32_t i = 0; i < req.count; i++) {
        int rc = map_buffer(s, i, err, n);
        if (rc) return rc;
    }
    int type = (int)s->buf_type;
    if (xioctl(s->fd, VIDIOC_STREAMON, &type) != 0) return fail(s, "VIDIOC_STREAMON", err, n);
    s->streaming = true;
    return 0;
}

int v4l2_source_open(struct v4l2_source *s, const char *path, int want_width, int want_height,
                     char *err, size_t n)
{
    memset(s, 0, sizeof(*s));
    s->fd = -1;
    s->held = -1;
    snprintf(s->path, sizeof(s->path), "%s", path);
    int rc = open_node(s, err, n);
    if (rc == 0) rc = query_caps(s, err, n);
    if (rc == 0) rc = set_format(s, want_width, want_height, err, n);
    if (rc == 0) rc = start_streaming(s, err, n);
    if (rc) v4l2_source_close(s);
    return rc;
}

static int requeue(struct v4l2_source *s, int index, char *err, size_t n)
{
    struct v4l2_buffer b;
    struct v4l2_plane planes[VIDEO_MAX_PLANES];
    init_buffer(s, &b, planes, (uint32_t)index);
    if (xioctl(s->fd, VIDIOC_QBUF, &b) != 0) return fail(s, "VIDIOC_QBUF", err, n);
    return 0;
}

/* Dequeues one buffer: 1 with *index and *bytes, 0 when none is ready, or -errno. */
static int dequeue(struct v4l2_source *s, int *index, size_t *bytes, char *err, size_t n)
{
    struct v4l2_buffer b;
    struct v4l2_plane planes[VIDEO_MAX_PLANES];
    init_buffer(s, &b, planes, 0);
    if (xioctl(s->fd, VIDIOC_DQBUF, &b) != 0) {
        if (errno == EAGAIN) return 0;
        return fail(s, "VIDIOC_DQBUF", err, n);
    }
    if (b.index >= (uint32_t)s->buffer_count) {
        snprintf(err, n, "video %s: VIDIOC_DQBUF returned buffer %u of %d", s->path, b.index,
                 s->buffer_count);
        return -EIO;
    }
    *index = (int)b.index;
    *bytes = mplane(s) ? planes[0].bytesused : b.bytesused;
    if (b.flags & V4L2_BUF_FLAG_ERROR) *bytes = 0; /* a damaged frame: skipped */
    return 1;
}

int v4l2_source_latest(struct v4l2_source *s, struct luma_view *view, char *err, size_t n)
{
    if (s->fd < 0 || !s->streaming || s->held >= 0) return -EINVAL;
    int newest = -1, index = -1;
    size_t newest_bytes = 0, bytes = 0;
    for (int i = 0; i < s->buffer_count; i++) {
        int rc = dequeue(s, &index, &bytes, err, n);
        if (rc < 0) return rc;
        if (rc == 0) break;
        if (newest >= 0 && (rc = requeue(s, newest, err, n)) != 0) return rc;
        if (bytes == 0) {
            if ((rc = requeue(s, index, err, n)) != 0) return rc;
            continue;
        }
        newest = index;
        newest_bytes = bytes;
    }
    if (newest < 0) return 0;
    s->held = newest;
    size_t length = s->buffers[newest].length;
    *view = (struct luma_view){
        .data = s->buffers[newest].start,
        .bytes = newest_bytes < length ? newest_bytes : length,
        .width = s->width, .height = s->height, .stride = s->stride,
        .step = s->step, .offset = s->offset,
    };
    return 1;
}

int v4l2_source_release(struct v4l2_source *s, char *err, size_t n)
{
    if (s->held < 0) return 0;
    int index = s->held;
    s->held = -1;
    return requeue(s, index, err, n);
}

void v4l2_source_close(struct v4l2_source *s)
{
    if (s->streaming) {
        int type = (int)s->buf_type;
        xioctl(s->fd, VIDIOC_STREAMOFF, &type); /* fails harmlessly on a device that is gone */
        s->streaming = false;
    }
    for (int i = 0; i < s->buffer_count; i++)
        if (s->buffers[i].start) munmap(s->buffers[i].start, s->buffers[i].length);
    s->buffer_count = 0;
    if (s->fd >= 0) close(s->fd);
    s->fd = -1;
    s->held = -1;
}

void v4l2_source_describe(const struct v4l2_source *s, char *out, size_t n)
{
    char f[5];
    fourcc_text(s->fourcc, f);
    snprintf(out, n, "%dx%d %s%s (%s)", s->width, s->height, f, mplane(s) ? " mplane" : "",
             s->card[0] ? s->card : "?");
}
