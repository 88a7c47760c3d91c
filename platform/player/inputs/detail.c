/* Detail feeds (detail.h): the V4L2 camera and the scene's video clip. */
#include <stdio.h>

#include "player/inputs/detail.h"
#include "video/clip_detail.h"

static const char *camera_device(const sbfx *fx, const char *video_flag, const struct board_profile *b)
{
    if (video_flag) return video_flag;
    if (b->video_device[0] && sbfx_wants_live_detail(fx)) return b->video_device;
    return NULL;
}

int detail_open_camera(struct detail_feed *d, sbfx *fx, const char *video_flag, const struct board_profile *b,
                       input_log_fn log, void *user, char *err, size_t n)
{
    const char *device = camera_device(fx, video_flag, b);
    if (!device) {
        if (sbfx_wants_live_detail(fx))
            log("the scene asks for camera detail (source \"v4l2\") but neither --video nor "
                "the board names a camera: procedural detail", user);
        return 0;
    }
    const struct live_detail_desc desc = {
        .device = device, .width = b->video_width, .height = b->video_height,
    };
    int rc = live_detail_start(&d->camera, fx, &desc, log, user, err, n);
    d->camera_on = rc == 0;
    return rc;
}

int detail_open_clip(sbfx *fx, input_log_fn log, void *user, char *err, size_t n)
{
    const char *clip = sbfx_detail_clip(fx);
    if (!clip) return 0;
    struct clip_info info;
    int rc = clip_detail_load(fx, clip, &info, err, n);
    if (rc) return rc;
    char msg[512];
    clip_describe(clip, &info, msg, sizeof(msg));
    log(msg, user);
    return 0;
}

void detail_service(struct detail_feed *d, int64_t now_ns)
{
    if (d->camera_on) live_detail_service(&d->camera, now_ns);
}

void detail_close(struct detail_feed *d)
{
    if (d->camera_on) live_detail_stop(&d->camera);
    d->camera_on = false;
}
