/* What a scene file says to its host: sbfx_scene_host (sbfx-play's test scene reads it). */
#include <math.h>
#include <string.h>
#include "scene/scene.h"

bool sbfx_scene_host_get(const sbfx_scene *scene, sbfx_scene_host *out)
{
    if (!out) return false;
    *out = (sbfx_scene_host){.exposure = 1.0f};
    if (!scene) return false;
    out->host_lights = scene->host_lights;
    out->host_shadows = scene->host_shadows;
    out->has_sky = scene->has_sky;
    memcpy(out->sky, scene->sky, sizeof(out->sky));
    memcpy(out->ambient, scene->ambient, sizeof(out->ambient));
    out->exposure = scene->render.exposure > 0.0f ? scene->render.exposure : 1.0f;
    for (int i = 0; i < scene->light_count && !out->has_sun; i++) {
        const sbfx_light *l = &scene->lights[i];
        if (l->type != SBFX_LIGHT_DIRECTIONAL) continue;
        float len = sqrtf(l->vector[0] * l->vector[0] + l->vector[1] * l->vector[1] + l->vector[2] * l->vector[2]);
        for (int k = 0; k < 3; k++) out->sun_direction[k] = l->vector[k] / len; /* parse refused length 0 */
        memcpy(out->sun_color, l->color, sizeof(out->sun_color));
        out->has_sun = true;
    }
    return out->has_sky;
}
