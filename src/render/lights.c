/* The frame's lights (docs/design.md §2): the scene's lights and the live light flashes in view
 * space, as the particle shaders get them (particles.c), and the test and tool entry points
 * that read or replace them. */
#include <math.h>
#include <string.h>
#include "render/render.h"

/* The lights of this frame in view space: the scene's, then the live flashes (fading out
 * linearly over their duration). */
static void to_view(const float m[16], const float v[3], float w, float out[4])
{
    for (int r = 0; r < 3; r++) out[r] = m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * w;
    out[3] = w;
}

void sbfx_gather_lights(const sbfx *fx, const float view[16], frame_lights *out)
{
    out->count = 0;
    for (int i = 0; i < fx->scene->light_count && out->count < SBFX_SHADER_LIGHTS; i++, out->count++) {
        const sbfx_scene_light *l = &fx->scene->lights[i];
        to_view(view, l->vector, l->point ? 1.0f : 0.0f, out->vector[out->count]);
        memcpy(out->color[out->count], l->color, sizeof(l->color));
    }
    /* live flashes, brightest first, as many as the shaders' light slots hold (scene/plan.c) */
    int order[SBFX_MAX_LIVE_FLASHES], lit = 0;
    float weight[SBFX_MAX_LIVE_FLASHES];
    for (int i = 0; i < fx->sim->flash_count; i++) {
        const sbfx_live_flash *f = &fx->sim->flashes[i];
        double t = (fx->sim->time - f->start) / f->duration;
        if (t < 0.0 || t >= 1.0) continue;
        float w = (f->color[0] + f->color[1] + f->color[2]) * (float)(1.0 - t);
        int at = lit++;
        for (; at > 0 && weight[at - 1] < w; at--) order[at] = order[at - 1], weight[at] = weight[at - 1];
        order[at] = i, weight[at] = w;
    }
    for (int j = 0; j < lit && out->count < fx->scene->light_slots; j++, out->count++) {
        const sbfx_live_flash *f = &fx->sim->flashes[order[j]];
        double t = (fx->sim->time - f->start) / f->duration;
        to_view(view, f->position, 1.0f, out->vector[out->count]);
        for (int k = 0; k < 3; k++) out->color[out->count][k] = f->color[k] * (float)(1.0 - t);
    }
}

int sbfx_frame_lights(const sbfx *fx, const float view[16], sbfx_view_light *out, int capacity)
{
    frame_lights lights;
    sbfx_gather_lights(fx, view, &lights);
    int n = lights.count < capacity ? lights.count : capacity;
    for (int i = 0; i < n; i++) {
        memcpy(out[i].vector, lights.vector[i], sizeof(out[i].vector));
        memcpy(out[i].color, lights.color[i], sizeof(out[i].color));
    }
    return n;
}

void sbfx_frame_ambient(const sbfx *fx, float ambient[3]) { memcpy(ambient, fx->scene->ambient, 3 * sizeof(float)); }

/* ---- entry points for tests and tools that replace the scene's lights ---- */

void sbfx_set_light(sbfx *fx, const float direction[3], const float color[3], const float ambient[3])
{
    sbfx_light_slots_reserve(fx, 1);
    fx->scene->light_count = 1;
    fx->scene->lights[0].point = false;
    fx->scene->lights[0].orbit.on = false;
    memcpy(fx->scene->lights[0].vector, direction, 3 * sizeof(float));
    sbfx_normalize3(fx->scene->lights[0].vector);
    memcpy(fx->scene->lights[0].color, color, 3 * sizeof(float));
    memcpy(fx->scene->ambient, ambient, 3 * sizeof(float));
}

void sbfx_set_lights(sbfx *fx, const sbfx_view_light *lights, int count, const float ambient[3])
{
    if (count < 0) count = 0;
    if (count > SBFX_SHADER_LIGHTS) count = SBFX_SHADER_LIGHTS;
    sbfx_light_slots_reserve(fx, count);
    fx->scene->light_count = count;
    for (int i = 0; i < count; i++) {
        sbfx_scene_light *l = &fx->scene->lights[i];
        memset(l, 0, sizeof(*l));
        l->point = lights[i].vector[3] > 0.5f;
        memcpy(l->vector, lights[i].vector, sizeof(l->vector));
        memcpy(l->color, lights[i].color, sizeof(l->color));
        float len = sqrtf(l->vector[0] * l->vector[0] + l->vector[1] * l->vector[1] +
                          l->vector[2] * l->vector[2]);
        if (!l->point && len > 0.0f)
            for (int k = 0; k < 3; k++) l->vector[k] /= len; /* the shader takes unit directions */
    }
    memcpy(fx->scene->ambient, ambient, sizeof(fx->scene->ambient));
}
