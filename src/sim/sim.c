/* Particle pool (structure of arrays, sized once) and the fixed-step simulation.
 * Live particles are packed in [0, alive); a dying particle is replaced by the last one. */
#include <math.h>
#include <string.h>
#include "sim/sim.h"

#define POOL_FLOATS_PER_PARTICLE 20 /* pos 3, vel 3, age, life, r0, r1, i0, i1, fade, drag, buoy, detail 3, pad 2 */

sbfx_result sbfx_pool_create(sbfx *fx, int capacity)
{
    sbfx_pool *p = &fx->sim->pool;
    float *block = sbfx_calloc(fx, (size_t)capacity * POOL_FLOATS_PER_PARTICLE, sizeof(float));
    p->medium = sbfx_calloc(fx, (size_t)capacity, 1);
    fx->sim->view = sbfx_calloc(fx, (size_t)capacity, sizeof(*fx->sim->view));
    fx->sim->sort_keys = sbfx_calloc(fx, (size_t)capacity, sizeof(float));
    fx->sim->order = sbfx_calloc(fx, (size_t)capacity, sizeof(uint32_t));
    fx->sim->order_tmp = sbfx_calloc(fx, (size_t)capacity, sizeof(uint32_t));
    fx->sim->instances = sbfx_calloc(fx, (size_t)capacity * fx->scene->instance_floats, sizeof(float));
    p->start = sbfx_calloc(fx, (size_t)capacity, sizeof(double));
    p->steps = sbfx_calloc(fx, (size_t)capacity, sizeof(uint32_t));
    p->identity = sbfx_calloc(fx, (size_t)capacity, sizeof(uint64_t));
    if (!block || !p->medium || !p->start || !p->steps || !p->identity || !fx->sim->view || !fx->sim->sort_keys || !fx->sim->order || !fx->sim->order_tmp ||
        !fx->sim->instances) {
        sbfx_free(fx, block);
        return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "cannot allocate a pool of %d particles", capacity);
    }
    size_t n = (size_t)capacity;
    p->pos = block;
    p->vel = p->pos + 3 * n;
    p->age = p->vel + 3 * n;
    p->life = p->age + n;
    p->radius0 = p->life + n;
    p->radius1 = p->radius0 + n;
    p->intensity0 = p->radius1 + n;
    p->intensity1 = p->intensity0 + n;
    p->fade_in = p->intensity1 + n;
    p->drag = p->fade_in + n;
    p->buoyancy = p->drag + n;
    p->detail = p->buoyancy + n;
    p->capacity = capacity;
    p->alive = 0;
    return SBFX_OK;
}

void sbfx_pool_destroy(sbfx *fx)
{
    sbfx_free(fx, fx->sim->pool.pos);
    sbfx_free(fx, fx->sim->pool.medium);
    sbfx_free(fx, fx->sim->pool.start);
    sbfx_free(fx, fx->sim->pool.steps);
    sbfx_free(fx, fx->sim->pool.identity);
    sbfx_free(fx, fx->sim->view);
    sbfx_free(fx, fx->sim->sort_keys);
    sbfx_free(fx, fx->sim->order);
    sbfx_free(fx, fx->sim->order_tmp);
    sbfx_free(fx, fx->sim->instances);
    sbfx_free(fx, fx->sim->lod_work);
    fx->sim->lod_work = NULL;
    memset(&fx->sim->pool, 0, sizeof(fx->sim->pool));
}

sbfx_result sbfx_lod_create(sbfx *fx)
{
    fx->sim->lod_work = sbfx_calloc(fx, 1, lod_work_size(fx->sim->pool.capacity));
    if (!fx->sim->lod_work) return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "out of memory");
    lod_init(&fx->sim->lod, fx->sim->lod_work, fx->sim->pool.capacity);
    return SBFX_OK;
}

static void random_direction(sbfx_rng *rng, float upward, float out[3])
{
    /* Uniform on the sphere, folded into the upper hemisphere, bent toward +y by `upward`. */
    double z = sbfx_rng_range(rng, -1.0, 1.0), a = sbfx_rng_range(rng, 0.0, 6.283185307179586);
    double s = sqrt(1.0 - z * z);
    double v[3] = {s * cos(a), fabs(z), s * sin(a)};
    v[1] = v[1] * (1.0 - upward) + upward;
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++) out[i] = (float)(v[i] / len);
}

static void spawn_one(sbfx *fx, const sbfx_emitter *e, const float origin[3], sbfx_rng *rng)
{
    sbfx_pool *p = &fx->sim->pool;
    int i = p->alive++;
    float dir[3];
    random_direction(rng, e->upward, dir);
    float offset = (float)(e->spawn_radius * cbrt(sbfx_rng_uniform(rng)));
    float speed = (float)sbfx_rng_range(rng, e->speed_min, e->speed_max);
    float size = 1.0f + (float)sbfx_rng_range(rng, -e->radius_jitter, e->radius_jitter);
    for (int k = 0; k < 3; k++) {
        p->pos[3 * i + k] = origin[k] + dir[k] * offset;
        p->vel[3 * i + k] = dir[k] * speed;
        p->detail[3 * i + k] = (float)sbfx_rng_uniform(rng);
    }
    p->age[i] = -e->delay;
    p->life[i] = (float)sbfx_rng_range(rng, e->life_min, e->life_max);
    p->radius0[i] = e->radius_start * size;
    p->radius1[i] = e->radius_end * size;
    p->intensity0[i] = e->intensity_start;
    p->intensity1[i] = e->intensity_end;
    p->fade_in[i] = e->fade_in;
    p->drag[i] = e->drag;
    p->buoyancy[i] = e->buoyancy;
    p->medium[i] = (uint8_t)e->medium;
    p->start[i] = NAN; /* steps with the module (sbfx_spawn_identified says otherwise) */
    p->steps[i] = 0;
    p->identity[i] = 0;
}

static sbfx_result pool_room(sbfx *fx, const sbfx_effect *effect)
{
    int needed = 0;
    for (int i = 0; i < effect->emitter_count; i++) needed += effect->emitters[i].count;
    if (fx->sim->pool.alive + needed > fx->sim->pool.capacity)
        return sbfx_fail(fx, SBFX_ERR_POOL_FULL,
                         "trigger \"%s\" refused: needs %d particles, %d of %d are in use",
                         effect->name, needed, fx->sim->pool.alive, fx->sim->pool.capacity);
    return SBFX_OK;
}

static void spawn_all(sbfx *fx, const sbfx_effect *effect, const float position[3], sbfx_rng *rng)
{
    for (int i = 0; i < effect->emitter_count; i++)
        for (int n = 0; n < effect->emitters[i].count; n++)
            spawn_one(fx, &effect->emitters[i], position, rng);
}

sbfx_result sbfx_spawn_effect(sbfx *fx, const sbfx_effect *effect, const float position[3])
{
    sbfx_result r = pool_room(fx, effect);
    if (r != SBFX_OK) return r;
    /* Each trigger draws from its own stream: same seed + same trigger order = same particles. */
    sbfx_rng rng;
    sbfx_rng_seed(&rng, ((uint64_t)fx->scene->desc.seed << 32) ^ fx->sim->trigger_count++);
    spawn_all(fx, effect, position, &rng);
    return SBFX_OK;
}

sbfx_result sbfx_spawn_identified(sbfx *fx, const sbfx_effect *effect, const float position[3],
                                  uint64_t identity, double start)
{
    sbfx_result r = pool_room(fx, effect);
    if (r != SBFX_OK) return r;
    /* The stream is the identity's alone (an odd multiplier: one identity, one stream), so the
     * order triggers arrive in, and the triggers a process missed, change nothing. */
    sbfx_rng rng;
    sbfx_rng_seed(&rng, identity * 0xD1B54A32D192ED03ull);
    int first = fx->sim->pool.alive;
    spawn_all(fx, effect, position, &rng);
    for (int i = first; i < fx->sim->pool.alive; i++) {
        fx->sim->pool.start[i] = start;
        fx->sim->pool.identity[i] = identity;
    }
    return SBFX_OK;
}

static void retire(sbfx_pool *p, int i)
{
    int last = --p->alive;
    if (i == last) return;
    for (int k = 0; k < 3; k++) {
        p->pos[3 * i + k] = p->pos[3 * last + k];
        p->vel[3 * i + k] = p->vel[3 * last + k];
        p->detail[3 * i + k] = p->detail[3 * last + k];
    }
    p->age[i] = p->age[last];
    p->life[i] = p->life[last];
    p->radius0[i] = p->radius0[last];
    p->radius1[i] = p->radius1[last];
    p->intensity0[i] = p->intensity0[last];
    p->intensity1[i] = p->intensity1[last];
    p->fade_in[i] = p->fade_in[last];
    p->drag[i] = p->drag[last];
    p->buoyancy[i] = p->buoyancy[last];
    p->medium[i] = p->medium[last];
    p->start[i] = p->start[last];
    p->steps[i] = p->steps[last];
    p->identity[i] = p->identity[last];
}

int sbfx_retire_identified(sbfx *fx, uint64_t identity)
{
    sbfx_pool *p = &fx->sim->pool;
    int removed = 0;
    for (int i = 0; i < p->alive;) {
        if (p->identity[i] == identity) {
            retire(p, i); /* the last particle moved into slot i is looked at next */
            removed++;
        } else {
            i++;
        }
    }
    return removed;
}

/* One step of particle i; false when it died (retired: slot i holds another particle now). */
static bool step_particle(sbfx_pool *p, int i, float h)
{
    float age = p->age[i] + h;
    p->age[i] = age;
    if (age >= p->life[i]) {
        retire(p, i);
        return false;
    }
    if (age > 0.0f) {
        float damping = 1.0f / (1.0f + p->drag[i] * h); /* implicit drag: stable for any h */
        float *v = &p->vel[3 * i], *x = &p->pos[3 * i];
        v[0] *= damping;
        v[1] = (v[1] + p->buoyancy[i] * h) * damping;
        v[2] *= damping;
        x[0] += v[0] * h;
        x[1] += v[1] * h;
        x[2] += v[2] * h;
    }
    return true;
}

void sbfx_simulate_step(sbfx *fx, float h)
{
    sbfx_pool *p = &fx->sim->pool;
    for (int i = 0; i < p->alive;) {
        if (!isnan(p->start[i])) i++; /* identified: on its own grid (sbfx_sync_identified) */
        else if (step_particle(p, i, h)) i++;
        /* else the particle moved into slot i is processed next */
    }
}

/* Steps of an identified instance's grid in (start, now]: a tolerance of a millionth of a step
 * keeps a frame exactly on a step (k / fps, a multiple of it) on the same side in every process. */
static double grid_steps(double start, double now, double step)
{
    return floor((now - start) / step + 1e-6);
}

void sbfx_sync_identified(sbfx *fx, double now)
{
    sbfx_pool *p = &fx->sim->pool;
    double step = fx->scene->desc.sim_step;
    for (int i = 0; i < p->alive;) {
        if (isnan(p->start[i])) {
            i++;
            continue;
        }
        double target = grid_steps(p->start[i], now, step);
        bool alive = true;
        /* a particle dies by life - delay in steps: the catch-up is bounded by that */
        while (alive && (double)p->steps[i] < target) {
            p->steps[i]++;
            alive = step_particle(p, i, (float)step);
            fx->sim->particles_simulated++;
        }
        if (alive) i++;
    }
}

/* FNV-1a over the live particles' state: equal hashes mean bit-identical simulations. */
uint64_t sbfx_state_hash(const sbfx *fx)
{
    const sbfx_pool *p = &fx->sim->pool;
    uint64_t h = 1469598103934665603ull;
    const struct { const void *data; size_t size; } parts[] = {
        {p->pos, 3 * sizeof(float)}, {p->vel, 3 * sizeof(float)}, {p->age, sizeof(float)},
        {p->life, sizeof(float)}, {p->radius0, sizeof(float)}, {p->detail, 3 * sizeof(float)},
        {p->medium, 1}};
    for (size_t k = 0; k < ARRAY_SIZE(parts); k++) {
        const unsigned char *bytes = parts[k].data;
        for (size_t i = 0; i < (size_t)p->alive * parts[k].size; i++) h = (h ^ bytes[i]) * 1099511628211ull;
    }
    return h ^ (uint64_t)p->alive;
}
