/* The simulation's clock and timeline (docs/design.md §7): time counted in whole fixed steps, the
 * triggers scheduled on it (sorted, fired at their step), an effect instance started (its
 * particles spawned into the pool, its light flashes made live point lights), and periodic
 * values reduced on the clock in double. */
#include <math.h>
#include <string.h>
#include "sim/sim.h"

/* Starts one instance: its particles, and its light flashes as live point lights; the host's
 * listener hears of it with the clock of its first step. */
sbfx_result sbfx_fire(sbfx *fx, int index, const float position[3], sbfx_trigger_origin origin)
{
    const sbfx_effect *e = &fx->scene->effects[index];
    sbfx_result r = sbfx_spawn_effect(fx, e, position);
    if (r != SBFX_OK) {
        fx->counters.triggers_refused++;
        return r;
    }
    fx->counters.triggers_fired++;
    if (fx->sim->trigger_listener)
        fx->sim->trigger_listener(e->name, position, fx->scene->desc.start_time + fx->sim->time, origin,
                                  fx->sim->trigger_listener_user);
    for (int i = 0; i < e->flash_count && fx->sim->flash_count < SBFX_MAX_LIVE_FLASHES; i++) {
        const sbfx_flash *f = &e->flashes[i];
        sbfx_live_flash *live = &fx->sim->flashes[fx->sim->flash_count++];
        live->identity = 0;
        live->start = fx->sim->time + f->delay;
        live->duration = f->duration;
        memcpy(live->color, f->color, sizeof(live->color));
        for (int k = 0; k < 3; k++) live->position[k] = position[k] + f->offset[k];
    }
    return SBFX_OK;
}

double sbfx_host_time(const sbfx *fx)
{
    return fx->scene->desc.start_time + fx->sim->time + fx->sim->accumulator;
}

/* Seconds from an instance's start until its last particle and flash have ended. */
static double effect_span(const sbfx_effect *e)
{
    double span = 0.0;
    for (int i = 0; i < e->emitter_count; i++)
        span = fmax(span, (double)e->emitters[i].delay + (double)e->emitters[i].life_max);
    for (int i = 0; i < e->flash_count; i++)
        span = fmax(span, (double)e->flashes[i].delay + (double)e->flashes[i].duration);
    return span;
}

sbfx_result sbfx_fire_identified(sbfx *fx, int index, const float position[3], uint64_t identity, double start)
{
    const sbfx_effect *e = &fx->scene->effects[index];
    double now = sbfx_host_time(fx);
    if (now - start >= effect_span(e) + fx->scene->desc.sim_step) {
        fx->triggers_expired++; /* all over already: a channel that joined after it ended */
        return SBFX_OK;
    }
    sbfx_result r = sbfx_spawn_identified(fx, e, position, identity, start);
    if (r != SBFX_OK) {
        fx->counters.triggers_refused++;
        return r;
    }
    fx->counters.triggers_fired++;
    sbfx_sync_identified(fx, now); /* a late one is drawn at its age from the next render on */
    if (fx->sim->trigger_listener)
        fx->sim->trigger_listener(e->name, position, start, SBFX_TRIGGER_CALL, fx->sim->trigger_listener_user);
    double elapsed_start = start - fx->scene->desc.start_time; /* flashes live on the elapsed clock */
    for (int i = 0; i < e->flash_count && fx->sim->flash_count < SBFX_MAX_LIVE_FLASHES; i++) {
        const sbfx_flash *f = &e->flashes[i];
        if (elapsed_start + f->delay + f->duration <= fx->sim->time) continue; /* over */
        sbfx_live_flash *live = &fx->sim->flashes[fx->sim->flash_count++];
        live->identity = identity;
        live->start = elapsed_start + f->delay;
        live->duration = f->duration;
        memcpy(live->color, f->color, sizeof(live->color));
        for (int k = 0; k < 3; k++) live->position[k] = position[k] + f->offset[k];
    }
    return SBFX_OK;
}

int sbfx_stop_instance(sbfx *fx, uint64_t identity)
{
    for (int i = 0; i < fx->sim->flash_count;) {
        if (fx->sim->flashes[i].identity == identity) fx->sim->flashes[i] = fx->sim->flashes[--fx->sim->flash_count];
        else i++;
    }
    return sbfx_retire_identified(fx, identity);
}

/* Adds a trigger of effect `index` at `seconds` (simulation time) to the timeline. */
sbfx_result sbfx_timeline_add(sbfx *fx, int index, double seconds, const float position[3],
                              sbfx_trigger_origin origin)
{
    const char *effect = fx->scene->effects[index].name;
    if (fx->sim->schedule_count == SBFX_MAX_SCHEDULE)
        return sbfx_fail(fx, SBFX_ERR_POOL_FULL, "schedule \"%s\": %d triggers already pending", effect, SBFX_MAX_SCHEDULE);
    /* Keep the queue sorted (stable: equal times fire in the order they were scheduled). */
    int at = fx->sim->schedule_count;
    while (at > fx->sim->next_scheduled && fx->sim->schedule[at - 1].time > seconds) {
        fx->sim->schedule[at] = fx->sim->schedule[at - 1];
        at--;
    }
    fx->sim->schedule[at] = (sbfx_scheduled){index, seconds, {position[0], position[1], position[2]}, origin};
    fx->sim->schedule_count++;
    return SBFX_OK;
}

/* The clock's place in a cycle of `period` seconds, in [0, 1): both parts reduced in double
 * (fmod is exact) before they meet, so a start a year in keeps the phase to the last bit, and a
 * start that is a whole number of periods gives bit for bit what a start at 0 gives. */
double sbfx_clock_phase(const sbfx *fx, double period)
{
    double p = fabs(period);
    double turns = fmod(fmod(fx->scene->desc.start_time, p) + fmod(fx->sim->time, p), p) / p;
    return turns < 1.0 ? turns : 0.0;
}

/* The detail animation loops every 4 s: its phase on the clock, in [0, 1) loops (the volume's
 * time axis wraps with REPEAT, so the jump from 1 back to 0 is seamless). */
double sbfx_detail_time(const sbfx *fx) { return sbfx_clock_phase(fx, SBFX_DETAIL_LOOP_SECONDS); }

/* Scheduled triggers due at the current step; a refused one is counted and dropped. */
static void fire_due(sbfx *fx)
{
    while (fx->sim->next_scheduled < fx->sim->schedule_count &&
           fx->sim->schedule[fx->sim->next_scheduled].time <= fx->sim->time + 1e-9) {
        const sbfx_scheduled *s = &fx->sim->schedule[fx->sim->next_scheduled++];
        sbfx_fire(fx, s->effect, s->position, s->origin);
    }
    if (fx->sim->next_scheduled == fx->sim->schedule_count) fx->sim->next_scheduled = fx->sim->schedule_count = 0;
}

static void expire_flashes(sbfx *fx)
{
    for (int i = 0; i < fx->sim->flash_count;) {
        if (fx->sim->time >= fx->sim->flashes[i].start + fx->sim->flashes[i].duration)
            fx->sim->flashes[i] = fx->sim->flashes[--fx->sim->flash_count];
        else
            i++;
    }
}

/* Advances the clock by dt in whole steps: the triggers due at each step fired, the particles
 * simulated, expired flashes dropped. */
void sbfx_timeline_advance(sbfx *fx, double dt)
{
    /* Time is counted in whole steps (step_index * step), so no rounding drift accumulates. */
    double step = fx->scene->desc.sim_step;
    /* A stall (debugger, suspended board) must not make the simulation spin: cap the debt. */
    fx->sim->accumulator = fmin(fx->sim->accumulator + dt, 0.25 + step);
    fx->sim->particles_simulated = 0;
    fx->sim->emitted_current = false; /* the fire lights are gathered again when asked */
    fx->counters.emitted_lights = 0;
    while (fx->sim->accumulator >= step) {
        fire_due(fx);
        fx->sim->particles_simulated += fx->sim->pool.alive;
        sbfx_simulate_step(fx, (float)step);
        fx->sim->accumulator -= step;
        fx->sim->step_index++;
        fx->sim->time = (double)fx->sim->step_index * step;
        expire_flashes(fx);
    }
    sbfx_sync_identified(fx, sbfx_host_time(fx)); /* identified instances step on their own grids */
}
