/* Module lifetime, errors and the public entry points that are not rendering. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "module.h"
#include "scene/scene.h"

static void normalize3(float v[3]);

/* Zero means "default": filled in one place. The desc's own fields win over the scene's. */
static sbfx_desc desc_with_defaults(const sbfx_desc *in)
{
    sbfx_desc d = in ? *in : (sbfx_desc){0};
    if (d.scene) {
        const sbfx_desc *s = &d.scene->render;
        if (!d.target_divisor) d.target_divisor = s->target_divisor;
        if (!d.target_format) d.target_format = s->target_format;
        if (!d.upsample) d.upsample = s->upsample;
        if (!d.opacity) d.opacity = s->opacity;
        if (!d.seed) d.seed = s->seed;
        if (!d.max_particles) d.max_particles = s->max_particles;
        if (!(d.sim_step > 0)) d.sim_step = s->sim_step;
        if (!(d.blackbody_max_kelvin > 0)) d.blackbody_max_kelvin = s->blackbody_max_kelvin;
        d.light_per_particle = d.light_per_particle || s->light_per_particle;
        d.analytic_blackbody = d.analytic_blackbody || s->analytic_blackbody;
        d.analytic_phase = d.analytic_phase || s->analytic_phase;
        if (!d.detail_format) d.detail_format = s->detail_format;
        if (!d.tone_map) d.tone_map = s->tone_map;
        if (!(d.exposure > 0)) d.exposure = s->exposure;
        if (!(d.white_luminance > 0)) d.white_luminance = s->white_luminance;
        if (d.frame_budget_ms == 0) d.frame_budget_ms = s->frame_budget_ms;
        if (!d.ladder) d.ladder = s->ladder, d.ladder_count = s->ladder_count;
        if (!d.shadow_map_size) d.shadow_map_size = s->shadow_map_size;
    }
    if (!d.target_divisor) d.target_divisor = 4;
    if (!d.upsample) d.upsample = SBFX_UPSAMPLE_NEAREST_DEPTH;
    if (!d.opacity) d.opacity = SBFX_OPACITY_EXACT;
    if (!d.seed) d.seed = 1;
    if (!d.max_particles) d.max_particles = 2048;
    if (!(d.blackbody_max_kelvin > 0)) d.blackbody_max_kelvin = (float)SBFX_DEFAULT_MAX_KELVIN;
    if (!d.detail_size) d.detail_size = 128;
    if (!d.detail_frames) d.detail_frames = 32;
    if (!d.detail_format) d.detail_format = SBFX_DETAIL_R16F;
    if (!d.tone_map) d.tone_map = SBFX_TONE_MAP_FILMIC;
    if (!(d.exposure > 0)) d.exposure = 1.0f;
    if (!(d.white_luminance > 0)) d.white_luminance = (float)SBFX_DEFAULT_WHITE_LUMINANCE;
    if (!(d.sim_step > 0)) d.sim_step = 1.0f / 120.0f;
    return d;
}

static bool is_power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

static sbfx_result validate_desc(sbfx *fx, const sbfx_desc *d)
{
    if (d->target_divisor != 1 && d->target_divisor != 2 && d->target_divisor != 4 &&
        d->target_divisor != 8)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT,
                         "target_divisor %d: use 1, 2, 4 or 8", d->target_divisor);
    if ((unsigned)d->target_format >= SBFX_FORMAT_COUNT || (unsigned)d->upsample >= SBFX_UPSAMPLE_COUNT ||
        (unsigned)d->opacity >= SBFX_OPACITY_COUNT || (unsigned)d->detail_format >= SBFX_DETAIL_COUNT ||
        (unsigned)d->tone_map >= SBFX_TONE_MAP_COUNT)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "unknown target format, upsample, opacity mode, detail format "
                         "or tone map");
    if (!(d->exposure <= 1e4f))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "exposure %g: use a scale above 0 and at most 1e4",
                         (double)d->exposure);
    if (!(d->white_luminance >= 1.0f && d->white_luminance <= 1e9f))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "white_luminance %g cd/m^2: use 1 .. 1e9 (a daylight "
                         "scene: about 1e4)", (double)d->white_luminance);
    if (d->max_particles < 1 || d->max_particles > (1 << 20))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "max_particles %d: use 1 .. 1048576",
                         d->max_particles);
    if (!is_power_of_two(d->detail_size) || !is_power_of_two(d->detail_frames) ||
        d->detail_size < 4 || d->detail_frames < 4 || d->detail_size > 256 || d->detail_frames > 256)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT,
                         "detail volume %dx%dx%d: use powers of two from 4 to 256",
                         d->detail_size, d->detail_size, d->detail_frames);
    if (!(d->start_time >= 0.0 && d->start_time <= SBFX_MAX_START_TIME))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "start_time %g s: use 0 .. %g s",
                         d->start_time, SBFX_MAX_START_TIME);
    if (!(d->frame_budget_ms >= 0.0f && d->frame_budget_ms <= 1e4f))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "frame_budget_ms %g: use a time in milliseconds above 0 "
                         "and at most 10000 (0: no budget)", (double)d->frame_budget_ms);
    if (d->ladder_count < 0 || d->ladder_count > SBFX_LADDER_MAX || (d->ladder_count > 0 && !d->ladder))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "ladder: %d levels%s: use 1 .. %d names", d->ladder_count,
                         d->ladder ? "" : " and no names", SBFX_LADDER_MAX);
    if (d->lod_particles < 0 || d->lod_particles > (1 << 20))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "lod_particles %d: use 0 (all) .. 1048576", d->lod_particles);
    if (d->shadow_map_size < 0)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "shadow_map_size %d: use texels per side (256), or 0 "
                         "for none", d->shadow_map_size);
    if (!(d->sim_step <= 0.1f))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "sim_step %g s: use at most 0.1 s",
                         (double)d->sim_step);
    return SBFX_OK;
}

/* Copies what the module keeps of a scene: media, lights, effects, the timeline. */
static void adopt_scene(sbfx *fx, const sbfx_scene *scene)
{
    memcpy(fx->media, scene->media, sizeof(fx->media));
    fx->light_count = scene->light_count;
    for (int i = 0; i < scene->light_count; i++) {
        const sbfx_light *l = &scene->lights[i];
        fx->lights[i].point = l->type == SBFX_LIGHT_POINT;
        memcpy(fx->lights[i].vector, l->vector, sizeof(l->vector));
        memcpy(fx->lights[i].color, l->color, sizeof(l->color));
        fx->lights[i].orbit = l->orbit;
        if (!fx->lights[i].point) normalize3(fx->lights[i].vector);
    }
    memcpy(fx->ambient, scene->ambient, sizeof(fx->ambient));
    memcpy(fx->effects, scene->effects, sizeof(fx->effects));
    fx->post = scene->post;
    fx->effect_count = scene->effect_count;
    fx->light_slots = sbfx_light_slots_of_scene(fx);
    for (int e = 0; e < fx->effect_count; e++)
        for (int i = 0; i < fx->effects[e].emitter_count; i++)
            fx->uses_medium[fx->effects[e].emitters[i].medium] = true;
    fx->plan.distortion = fx->uses_medium[SBFX_HEAT];
    fx->plan.particle_velocity = fx->post.blur == SBFX_BLUR_VELOCITY;
    fx->plan.motion_target = fx->plan.particle_velocity || fx->post.dof;
    fx->plan.owns_scene = fx->plan.distortion || fx->post.blur != SBFX_BLUR_NONE || fx->post.dof;
    fx->instance_floats = 8;
    fx->instance_previous = fx->plan.particle_velocity ? (fx->instance_floats += 4, 8) : 0;
    /* a slot for the per-particle light when a declared level uses it (bit-identical frames
     * either way: levels without it do not read it) */
    fx->instance_light = sbfx_declared_any(fx, sbfx_quality_uses_light_slot) ? (fx->instance_floats += 4) - 4 : 0;
    fx->plan.fire_light = sbfx_fire_lights_media(fx);
    fx->instance_fire = fx->plan.fire_light ? (fx->instance_floats += 8) - 8 : 0;
    if (!fx->desc.ignore_timeline)
        for (int i = 0; i < scene->timeline_count; i++) {
            const sbfx_timeline_entry *t = &scene->timeline[i];
            sbfx_schedule(fx, fx->effects[t->effect].name, fx->time + t->time, t->position); /* from now: a reload's timeline starts again */
        }
}

/* Everything made on the GPU at load, inside one save and restore of what it changes: the
 * program, vertex array and buffer bindings, the unpack state, and unit 0 (active texture,
 * 2D, 3D and 2D-array bindings, sampler). Targets follow the first frame's size. */
static sbfx_result load_gl(sbfx *fx)
{
    const sbfx_gl_units unit0 = {1u, 1u, 1u};
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_OBJECTS | SBFX_GL_SAVE_UNPACK, &unit0);
    sbfx_result r = sbfx_samplers_create(fx);
    if (r == SBFX_OK) r = sbfx_luts_create(fx);
    if (r == SBFX_OK) r = sbfx_programs_create(fx);
    if (r == SBFX_OK) r = sbfx_post_programs_create(fx);
    if (r == SBFX_OK) sbfx_budget_gl_init(fx);
    if (r == SBFX_OK) r = sbfx_shadow_create(fx);
    sbfx_gl_state_restore(&saved);
    return r;
}

/* Deleting sbfx's own objects changes no binding a host can hold. */
static void destroy_gl(sbfx *fx)
{
    sbfx_budget_gl_destroy(fx);
    sbfx_shadow_destroy(fx);
    sbfx_targets_destroy(fx);
    sbfx_post_destroy(fx);
    sbfx_programs_destroy(fx);
    sbfx_luts_destroy(fx);
    sbfx_samplers_destroy(fx);
}

sbfx_result sbfx_reload(sbfx *fx)
{
    destroy_gl(fx);
    memset(&fx->gl, 0, sizeof(fx->gl));
    fx->object_count = 0;
    fx->counters.programs = fx->counters.textures = fx->counters.framebuffers = 0;
    fx->counters.gpu_bytes = 0;
    return load_gl(fx);
}

static sbfx_result load(sbfx *fx)
{
    sbfx_result r;
    sbfx_scene *builtin = NULL;
    const sbfx_scene *scene = fx->desc.scene;
    if (!scene) {
        if (!(builtin = sbfx_calloc(fx, 1, sizeof(*builtin))))
            return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "out of memory");
        sbfx_scene_builtin(builtin);
        scene = builtin;
    }
    adopt_scene(fx, scene);
    sbfx_free(fx, builtin);
    sbfx_orbit_lights(fx); /* where orbiting lights are at t = 0 */
    fx->tone_curve = sbfx_tone_curve_for(fx->desc.tone_map);
    if ((r = sbfx_context_check(fx)) != SBFX_OK) return r;
    if ((r = sbfx_pool_create(fx, fx->desc.max_particles)) != SBFX_OK) return r;
    if ((r = sbfx_fire_lights_create(fx)) != SBFX_OK) return r;
    sbfx_gl_enter(fx);
    r = load_gl(fx);
    sbfx_gl_leave(fx, "sbfx_create");
    return r;
}

/* Plan: the desc with its defaults and the scene's render settings, checked, and the levels it
 * declares. */
static sbfx_result plan(sbfx *fx, const sbfx_desc *desc)
{
    fx->desc = desc_with_defaults(desc);
    sbfx_result r = validate_desc(fx, &fx->desc);
    if (r == SBFX_OK) r = sbfx_budget_init(fx);
    fx->desc.ladder = NULL; /* parsed: the scene's names may go away */
    fx->desc.ladder_count = 0;
    return r;
}

sbfx_result sbfx_module_build(sbfx *fx, const sbfx_desc *desc)
{
    sbfx_result r = plan(fx, desc);
    return r == SBFX_OK ? load(fx) : r;
}

void sbfx_module_release(sbfx *fx)
{
    destroy_gl(fx);
    sbfx_fire_lights_destroy(fx);
    sbfx_pool_destroy(fx);
}

/* What sbfx_set_scene plans each reload from: the desc as given, without the scene (it may be
 * freed) and with the ladder's names copied (so may they). */
static sbfx_result keep_host_desc(sbfx *fx, const sbfx_desc *desc)
{
    fx->host_desc = desc ? *desc : (sbfx_desc){0};
    fx->host_desc.scene = NULL;
    fx->host_desc.ladder = NULL;
    if (!desc || !desc->ladder) {
        fx->host_desc.ladder_count = 0;
        return SBFX_OK;
    }
    for (int i = 0; i < desc->ladder_count && i < SBFX_LADDER_MAX; i++) {
        if (!desc->ladder[i] || strlen(desc->ladder[i]) >= sizeof(fx->host_ladder[i]))
            return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "ladder[%d]: not a quality level name", i);
        strcpy(fx->host_ladder[i], desc->ladder[i]);
    }
    return SBFX_OK;
}

sbfx_result sbfx_create(const sbfx_desc *desc, sbfx **out)
{
    if (!out) return SBFX_ERR_INVALID_ARGUMENT;
    *out = NULL;
    sbfx *fx = calloc(1, sizeof(*fx));
    if (!fx) return SBFX_ERR_OUT_OF_MEMORY;
    fx->desc.log = desc ? desc->log : NULL; /* for keep_host_desc's message */
    fx->desc.log_user = desc ? desc->log_user : NULL;
    sbfx_result r = keep_host_desc(fx, desc);
    if (r == SBFX_OK) r = sbfx_precision_from_env(fx); /* once: a reload keeps what create read */
    if (r == SBFX_OK) r = sbfx_module_build(fx, desc);
    if (r != SBFX_OK) {
        /* Hand the message to the caller's log before the handle goes away. */
        sbfx_destroy(fx);
        return r;
    }
    fx->loaded = true;
    *out = fx;
    return SBFX_OK;
}

void sbfx_destroy(sbfx *fx)
{
    if (!fx) return;
    sbfx_module_release(fx);
    free(fx);
}

static int find_effect(const sbfx *fx, const char *name)
{
    for (int i = 0; i < fx->effect_count; i++)
        if (strcmp(fx->effects[i].name, name) == 0) return i;
    return -1;
}

bool sbfx_has_effect(const sbfx *fx, const char *effect)
{
    return fx && effect && find_effect(fx, effect) >= 0;
}

const char *sbfx_effect_name(const sbfx *fx, int index)
{
    return fx && index >= 0 && index < fx->effect_count ? fx->effects[index].name : NULL;
}

static bool position_valid(const float p[3])
{
    return p && isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

/* Starts one instance: its particles, and its light flashes as live point lights. */
sbfx_result sbfx_fire(sbfx *fx, int index, const float position[3])
{
    const sbfx_effect *e = &fx->effects[index];
    sbfx_result r = sbfx_spawn_effect(fx, e, position);
    if (r != SBFX_OK) {
        fx->counters.triggers_refused++;
        return r;
    }
    fx->counters.triggers_fired++;
    for (int i = 0; i < e->flash_count && fx->flash_count < SBFX_MAX_LIVE_FLASHES; i++) {
        const sbfx_flash *f = &e->flashes[i];
        sbfx_live_flash *live = &fx->flashes[fx->flash_count++];
        live->start = fx->time + f->delay;
        live->duration = f->duration;
        memcpy(live->color, f->color, sizeof(live->color));
        for (int k = 0; k < 3; k++) live->position[k] = position[k] + f->offset[k];
    }
    return SBFX_OK;
}

sbfx_result sbfx_trigger(sbfx *fx, const char *effect, const float position[3])
{
    if (!fx || !effect || !position) return SBFX_ERR_INVALID_ARGUMENT;
    if (!position_valid(position))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "trigger \"%s\": position is not finite", effect);
    int index = find_effect(fx, effect);
    if (index < 0) return sbfx_fail(fx, SBFX_ERR_UNKNOWN_EFFECT, "trigger: no effect named \"%s\"", effect);
    return sbfx_fire(fx, index, position);
}

sbfx_result sbfx_schedule(sbfx *fx, const char *effect, double seconds, const float position[3])
{
    if (!fx || !effect) return SBFX_ERR_INVALID_ARGUMENT;
    if (!position_valid(position) || !isfinite(seconds) || seconds < 0)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "schedule \"%s\": time or position is not finite", effect);
    int index = find_effect(fx, effect);
    if (index < 0) return sbfx_fail(fx, SBFX_ERR_UNKNOWN_EFFECT, "schedule: no effect named \"%s\"", effect);
    if (fx->schedule_count == SBFX_MAX_SCHEDULE)
        return sbfx_fail(fx, SBFX_ERR_POOL_FULL, "schedule \"%s\": %d triggers already pending", effect, SBFX_MAX_SCHEDULE);
    /* Keep the queue sorted (stable: equal times fire in the order they were scheduled). */
    int at = fx->schedule_count;
    while (at > fx->next_scheduled && fx->schedule[at - 1].time > seconds) {
        fx->schedule[at] = fx->schedule[at - 1];
        at--;
    }
    fx->schedule[at] = (sbfx_scheduled){index, seconds, {position[0], position[1], position[2]}};
    fx->schedule_count++;
    return SBFX_OK;
}

double sbfx_time(const sbfx *fx) { return fx ? fx->desc.start_time + fx->time : 0.0; }

double sbfx_elapsed(const sbfx *fx) { return fx ? fx->time : 0.0; }

/* The clock's place in a cycle of `period` seconds, in [0, 1): both parts reduced in double
 * (fmod is exact) before they meet, so a start a year in keeps the phase to the last bit, and a
 * start that is a whole number of periods gives bit for bit what a start at 0 gives. */
double sbfx_clock_phase(const sbfx *fx, double period)
{
    double p = fabs(period);
    double turns = fmod(fmod(fx->desc.start_time, p) + fmod(fx->time, p), p) / p;
    return turns < 1.0 ? turns : 0.0;
}

/* Scheduled triggers due at the current step; a refused one is counted and dropped. */
static void fire_due(sbfx *fx)
{
    while (fx->next_scheduled < fx->schedule_count &&
           fx->schedule[fx->next_scheduled].time <= fx->time + 1e-9) {
        const sbfx_scheduled *s = &fx->schedule[fx->next_scheduled++];
        sbfx_fire(fx, s->effect, s->position);
    }
    if (fx->next_scheduled == fx->schedule_count) fx->next_scheduled = fx->schedule_count = 0;
}

static void expire_flashes(sbfx *fx)
{
    for (int i = 0; i < fx->flash_count;) {
        if (fx->time >= fx->flashes[i].start + fx->flashes[i].duration)
            fx->flashes[i] = fx->flashes[--fx->flash_count];
        else
            i++;
    }
}

sbfx_result sbfx_update(sbfx *fx, double dt)
{
    if (!fx) return SBFX_ERR_INVALID_ARGUMENT;
    if (!(dt >= 0.0) || !isfinite(dt))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "sbfx_update: dt %g is not a finite time >= 0", dt);
    /* Time is counted in whole steps (step_index * step), so no rounding drift accumulates. */
    double step = fx->desc.sim_step;
    /* A stall (debugger, suspended board) must not make the simulation spin: cap the debt. */
    fx->accumulator = fmin(fx->accumulator + dt, 0.25 + step);
    fx->particles_simulated = 0;
    fx->emitted_current = false; /* the fire lights are gathered again when asked */
    fx->counters.emitted_lights = 0;
    while (fx->accumulator >= step) {
        fire_due(fx);
        fx->particles_simulated += fx->pool.alive;
        sbfx_simulate_step(fx, (float)step);
        fx->accumulator -= step;
        fx->step_index++;
        fx->time = (double)fx->step_index * step;
        expire_flashes(fx);
    }
    sbfx_orbit_lights(fx);
    return SBFX_OK;
}

void sbfx_stats(const sbfx *fx, sbfx_counters *out)
{
    if (!fx || !out) return;
    *out = fx->counters;
    out->particles_simulated = fx->particles_simulated;
    out->particles_alive = fx->pool.alive;
    out->heap_allocs_after_load = fx->heap_allocs_after_load;
}

sbfx_medium_params *sbfx_media(sbfx *fx) { return fx->media; }
const sbfx_desc *sbfx_get_desc(const sbfx *fx) { return &fx->desc; }

void sbfx_set_light(sbfx *fx, const float direction[3], const float color[3], const float ambient[3])
{
    sbfx_light_slots_reserve(fx, 1);
    fx->light_count = 1;
    fx->lights[0].point = false;
    fx->lights[0].orbit.on = false;
    memcpy(fx->lights[0].vector, direction, 3 * sizeof(float));
    normalize3(fx->lights[0].vector);
    memcpy(fx->lights[0].color, color, 3 * sizeof(float));
    memcpy(fx->ambient, ambient, 3 * sizeof(float));
}

/* ---- host helpers: the look-at matrix (projections: projection.c) ---- */
static void normalize3(float v[3])
{
    float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (len > 0) v[0] /= len, v[1] /= len, v[2] /= len;
}

static void cross3(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

void sbfx_look_at(float m[16], const float eye[3], const float target[3], const float up[3])
{
    float f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]}, s[3], u[3];
    normalize3(f);
    cross3(f, up, s);
    normalize3(s);
    cross3(s, f, u);
    const float rows[3][3] = {{s[0], s[1], s[2]}, {u[0], u[1], u[2]}, {-f[0], -f[1], -f[2]}};
    memset(m, 0, 16 * sizeof(float));
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++) m[c * 4 + r] = rows[r][c];
        m[12 + r] = -(rows[r][0] * eye[0] + rows[r][1] * eye[1] + rows[r][2] * eye[2]);
    }
    m[15] = 1.0f;
}
