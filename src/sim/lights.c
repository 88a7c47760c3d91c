/* Scene lights that move: orbiting point lights are placed from the simulation time (so they
 * are deterministic whatever the frame times, like the particles), and a test entry point that
 * replaces the lights. */
#include <math.h>
#include <string.h>
#include "module.h"

void sbfx_orbit_lights(sbfx *fx)
{
    for (int i = 0; i < fx->light_count; i++) {
        sbfx_scene_light *l = &fx->lights[i];
        const sbfx_orbit *o = &l->orbit;
        if (!l->point || !o->on) continue;
        /* the phase is reduced in double: sin/cos of a huge angle would lose it */
        double turns = sbfx_clock_phase(fx, o->period);
        if (o->period < 0) turns = -turns;
        double a = 2.0 * M_PI * turns + o->phase;
        l->vector[0] = o->center[0] + o->radius * (float)cos(a);
        l->vector[1] = o->center[1];
        l->vector[2] = o->center[2] - o->radius * (float)sin(a);
    }
}

/* The phase shaders' light loop is unrolled by the compiler (a Mali counts every iteration:
 * docs/gpus.md), so it is sized at load: the scene's lights and the flashes of one effect
 * instance. More flashes at once than that: the brightest are lit (passes.c). */
int sbfx_light_slots_of_scene(const sbfx *fx)
{
    int flashes = 0;
    for (int e = 0; e < fx->effect_count; e++)
        if (fx->effects[e].flash_count > flashes) flashes = fx->effects[e].flash_count;
    int slots = fx->light_count + flashes;
    return slots < SBFX_SHADER_LIGHTS ? slots : SBFX_SHADER_LIGHTS;
}

/* Test and tool entry points may set more lights than the scene has: the particle programs
 * are made again, with the larger loop, the next time the current level is applied. */
void sbfx_light_slots_reserve(sbfx *fx, int count)
{
    if (count <= fx->light_slots) return;
    fx->light_slots = count;
    bool built = false;
    for (int v = 0; v < SBFX_VARIANTS; v++) {
        sbfx_variant *var = &fx->gl.variants[v];
        for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) {
            if (!var->particle[m].id) continue;
            sbfx_program_delete(fx, var->particle[m].id);
            var->particle[m].id = 0;
            fx->counters.programs--;
        }
        built = built || var->built;
        var->built = false;
    }
    if (!built) return;   /* before load: the programs are made with the new size */
    sbfx_result r = sbfx_quality_apply(fx, &fx->current);
    if (r != SBFX_OK) sbfx_log(fx, SBFX_LOG_ERROR, "rebuilding the particle programs for %d lights failed", count);
}

void sbfx_set_lights(sbfx *fx, const sbfx_view_light *lights, int count, const float ambient[3])
{
    if (count < 0) count = 0;
    if (count > SBFX_SHADER_LIGHTS) count = SBFX_SHADER_LIGHTS;
    sbfx_light_slots_reserve(fx, count);
    fx->light_count = count;
    for (int i = 0; i < count; i++) {
        sbfx_scene_light *l = &fx->lights[i];
        memset(l, 0, sizeof(*l));
        l->point = lights[i].vector[3] > 0.5f;
        memcpy(l->vector, lights[i].vector, sizeof(l->vector));
        memcpy(l->color, lights[i].color, sizeof(l->color));
        float len = sqrtf(l->vector[0] * l->vector[0] + l->vector[1] * l->vector[1] +
                          l->vector[2] * l->vector[2]);
        if (!l->point && len > 0.0f)
            for (int k = 0; k < 3; k++) l->vector[k] /= len; /* the shader takes unit directions */
    }
    memcpy(fx->ambient, ambient, sizeof(fx->ambient));
}
