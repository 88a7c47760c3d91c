/* The test scene as the scene file describes it: its daylight (sun or moon, ambient, sky),
 * shaded by the smoke (render.host_shadows: sbfx_render_shadow_map from the first directional
 * light) and lit by the fire (render.host_lights). */
#include <errno.h>
#include <stdio.h>

#include "player/player.h"

static int shadow(struct player *p, char *err, size_t n)
{
    sbfx_shadow_map map;
    sbfx_result r = sbfx_render_shadow_map(p->fx, p->host.sun_direction, &map);
    if (r != SBFX_OK) {
        snprintf(err, n, "sbfx_render_shadow_map at t=%.4f s: %s: %s", p->sim_time, sbfx_result_string(r),
                 sbfx_last_error(p->fx));
        return -EIO;
    }
    test_scene_set_shadow(&p->scene, map.texture, map.view_projection);
    return 0;
}

static int lights(struct player *p, char *err, size_t n)
{
    sbfx_point_light lights[SBFX_MAX_POINT_LIGHTS];
    int count = sbfx_emitted_lights(p->fx, lights, SBFX_MAX_POINT_LIGHTS);
    if (count < 0) {
        snprintf(err, n, "sbfx_emitted_lights at t=%.4f s: %s: %s", p->sim_time, sbfx_result_string((sbfx_result)count),
                 sbfx_last_error(p->fx));
        return -EIO;
    }
    test_scene_set_point_lights(&p->scene, lights, count);
    return 0;
}

int player_host_prepare(struct player *p, double t, char *err, size_t n)
{
    test_scene_set_daylight(&p->scene, &p->host);
    bool shadows = p->host.host_shadows && p->host.has_sun;
    if (!shadows && !p->host.host_lights) return 0;
    int rc = player_update(p, t, err, n);
    if (rc == 0 && shadows) rc = shadow(p, err, n);
    if (rc == 0 && p->host.host_lights) rc = lights(p, err, n);
    return rc;
}
