/* The particle, as the pool keeps it and as a frame sees it (sim/sim.h says what the room is for). */
#ifndef SBFX_SIM_PARTICLES_H
#define SBFX_SIM_PARTICLES_H

#include <stdbool.h>
#include <stdint.h>
#include "sbfx.h"

/* Particle pool, structure of arrays, sized once at load. Live particles are [0, alive). */
typedef struct sbfx_pool {
    int capacity, alive;
    float *pos;        /* 3 per particle, world space */
    float *vel;        /* 3 per particle */
    float *age, *life; /* age < 0: waiting for its emitter's delay */
    float *radius0, *radius1;
    float *intensity0, *intensity1, *fade_in;
    float *drag, *buoyancy;
    float *detail;     /* 3 per particle: window u, v, time offset */
    uint8_t *medium;
    /* identified instances (sbfx_trigger_identified): each particle steps on its instance's own
     * grid, start + j * step, not the module's; NAN for the others, which step with the module */
    double *start;     /* the instance's start on the clock (sbfx_time) */
    uint32_t *steps;   /* steps simulated since then */
    uint64_t *identity; /* its instance's identity (0: none) */
} sbfx_pool;

/* A particle as the renderer sees it: view space, already validated. */
typedef struct sbfx_view_particle {
    float center[3];  /* view space, center[2] < 0 in front of the camera */
    float radius;
    float detail[3];  /* detail window origin (u, v) and time offset */
    float intensity;  /* density scale in [0,1]; fire also cools as it falls */
    sbfx_medium medium;
    float previous_center[3]; /* view-space centre one frame ago, as seen then (velocity blur) */
} sbfx_view_particle;

/* True when every input of the particle is finite and the radius is positive. */
bool sbfx_view_particle_valid(const sbfx_view_particle *p);
/* A live particle's radius and intensity at its age (what the renderer draws). */
void sbfx_pool_particle_shape(const sbfx_pool *p, int i, float *radius, float *intensity);

#endif
