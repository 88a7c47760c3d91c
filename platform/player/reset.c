/* GPU resets. The player's context asks for reset notification (gl_reset.h); once per frame it
 * asks whether the GPU was reset. A reset context is lost with everything in it, so then:
 *   - the camera feed is stopped (it pushes into sbfx), sbfx and the test scene are destroyed
 *     (their GL names die with the lost context; deleting them there is harmless);
 *   - the display makes a new context (and its own framebuffer) in place of the old one: the
 *     DRM output, its mode and the buffers on screen stay as they are;
 *   - the test scene, sbfx (sbfx_create with the same scene and options) and the camera feed
 *     are made again, and the loop goes on with the next frame.
 * Lost: the effects in flight (their particles lived in the old module), the camera frames in
 * the detail ring (refilled as frames come), the scene's timeline triggers still ahead (the new
 * module does not replay the timeline). Kept: the scene and options, the player's clock (the
 * camera and frame times go on; --trigger entries still ahead are scheduled on the new module
 * relative to now), the GPIO lines and their filters, the counters, and the module's clock: the
 * new module starts where the lost one stopped (desc.start_time), so its periodic animations
 * (detail loop, orbits) go on in phase. */
#include <stdio.h>
#include <stdlib.h>

#include "player/player.h"

#define INJECT_ENV "SBFX_PLAY_INJECT_GPU_RESET"

void player_reset_setup(struct player *p)
{
    p->reset.inject_frame = -1;
    const char *inject = getenv(INJECT_ENV);
    if (inject && *inject) gl_reset_inject(&p->reset, atoi(inject));
    gl_reset_init(&p->reset, p->display->robust_context);
}

static void say(struct player *p, const char *what, int frame, GLenum status)
{
    char msg[384];
    snprintf(msg, sizeof(msg), "GPU reset before frame %d (%s): %s", frame, gl_reset_name(status),
             what);
    player_log(msg, p);
}

static int remake(struct player *p, char *err, size_t n)
{
    struct display *d = p->display;
    int rc = d->ops->reset_context(d, err, n);
    if (rc) return rc;
    gl_reset_init(&p->reset, d->robust_context);
    rc = test_scene_create(&p->scene, d->width, d->height, err, n);
    if (rc) return rc;
    p->scene_made = true;
    p->recovering = true;
    rc = player_create_fx(p, err, n);
    p->recovering = false;
    return rc;
}

int player_check_gpu_reset(struct player *p, int frame, char *err, size_t n)
{
    GLenum status = gl_reset_status(&p->reset, frame);
    if (status == GL_NO_ERROR) return 0;
    say(p, "the GL context is lost; making it again with sbfx (effects in flight are lost)",
        frame, status);
    p->fx_time_lost = p->fx_created_at + sbfx_elapsed(p->fx);
    p->fx_clock_lost = sbfx_time(p->fx);
    bool camera = p->detail.camera_on;
    detail_close(&p->detail);
    sbfx_destroy(p->fx);
    p->fx = NULL;
    test_scene_destroy(&p->scene);
    p->scene_made = false;
    char why[768];
    int rc = remake(p, why, sizeof(why));
    if (rc) {
        snprintf(err, n, "after a GPU reset: %s", why);
        return rc;
    }
    p->gpu_resets++;
    if (detail_open_clip(p->fx, player_log, p, why, sizeof(why)) != 0) {
        player_log(why, p);
        player_log("the detail clip did not come back after the GPU reset: procedural detail", p);
    }
    if (camera &&
        detail_open_camera(&p->detail, p->fx, p->opt->video, &p->board, player_log, p, why, sizeof(why)) != 0) {
        player_log(why, p);
        player_log("the camera did not come back after the GPU reset: procedural detail", p);
    }
    char msg[160];
    snprintf(msg, sizeof(msg), "recovered at t=%.3f s: a new context (reset notification %s), "
             "its GL objects and sbfx", p->sim_time, p->reset.status ? p->reset.extension : "none");
    player_log(msg, p);
    return 0;
}
