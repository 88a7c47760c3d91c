/* Scene lights that move: orbiting point lights are placed from the simulation time (so they
 * are deterministic whatever the frame times, like the particles). */
#include <math.h>
#include "sim/sim.h"

void sbfx_orbit_lights(sbfx *fx)
{
    for (int i = 0; i < fx->scene->light_count; i++) {
        sbfx_scene_light *l = &fx->scene->lights[i];
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
