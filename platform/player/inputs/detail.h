/* Detail feeds (inputs.h): what fills the module's detail volume instead of its procedural one —
 * a V4L2 camera (platform/video/live_detail.h), serviced once a frame, and the scene's video
 * clip (platform/video/clip_detail.h), decoded once into the volume. */
#ifndef SBFX_PLAYER_DETAIL_H
#define SBFX_PLAYER_DETAIL_H

#include "player/inputs/inputs.h"
#include "player/options/board.h"
#include "video/live_detail.h"

struct detail_feed {
    struct live_detail camera;   /* its counters are --stats' video_* keys */
    bool camera_on;
};

/* The camera --video names, else the board's where the scene asks for camera detail (source
 * "v4l2"); none: logged when the scene asks for one. */
int detail_open_camera(struct detail_feed *d, sbfx *fx, const char *video_flag, const struct board_profile *b,
                       input_log_fn log, void *user, char *err, size_t n);
/* The scene's detail clip, if it names one, decoded into the volume: 0, or an error naming the
 * file. */
int detail_open_clip(sbfx *fx, input_log_fn log, void *user, char *err, size_t n);
/* Takes the camera's newest frame if one arrived (once per frame: a camera faster than the
 * display does not cost more uploads), notices losses, retries; never blocks. */
void detail_service(struct detail_feed *d, int64_t now_ns);
void detail_close(struct detail_feed *d);

#endif
