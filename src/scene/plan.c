/* The plan (plan.h): the desc with its defaults, checked; the scene as the module keeps it; what
 * the module builds for it (the passes a frame runs, a particle's instance data). Made once per
 * load (sbfx_create, sbfx_set_scene) by the top, before anything is made on the GPU. */
#include <math.h>
#include <string.h>
#include "scene/plan.h"
#include "scene/scene_tables.h"

/* Zero means "default": filled in one place. The desc's own fields win over the scene's. */
sbfx_desc sbfx_desc_with_defaults(const sbfx_desc *in)
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
        /* the phase: the desc decides where it names either form, else the scene */
        if (!d.analytic_phase && !d.table_phase) d.analytic_phase = s->analytic_phase, d.table_phase = s->table_phase;
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
    sbfx_phase_resolve(&d.analytic_phase, &d.table_phase);
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

sbfx_result sbfx_desc_validate(sbfx *fx, const sbfx_desc *d)
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

/* What sbfx_set_scene plans each reload from: the desc as given, without the scene (it may be
 * freed) and with the ladder's names copied (so may they). */
sbfx_result sbfx_keep_host_desc(sbfx *fx, const sbfx_desc *desc)
{
    fx->scene->host_desc = desc ? *desc : (sbfx_desc){0};
    fx->scene->host_desc.scene = NULL;
    fx->scene->host_desc.ladder = NULL;
    if (!desc || !desc->ladder) {
        fx->scene->host_desc.ladder_count = 0;
        return SBFX_OK;
    }
    for (int i = 0; i < desc->ladder_count && i < SBFX_LADDER_MAX; i++) {
        if (!desc->ladder[i] || strlen(desc->ladder[i]) >= sizeof(fx->scene->host_ladder[i]))
            return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "ladder[%d]: not a quality level name", i);
        strcpy(fx->scene->host_ladder[i], desc->ladder[i]);
    }
    return SBFX_OK;
}


/* What the module keeps of a scene: media, lights, effects, the post chain; then the plan. */
void sbfx_scene_adopt(sbfx *fx, const sbfx_scene *scene)
{
    memcpy(fx->scene->media, scene->media, sizeof(fx->scene->media));
    fx->scene->light_count = scene->light_count;
    for (int i = 0; i < scene->light_count; i++) {
        const sbfx_light *l = &scene->lights[i];
        fx->scene->lights[i].point = l->type == SBFX_LIGHT_POINT;
        memcpy(fx->scene->lights[i].vector, l->vector, sizeof(l->vector));
        memcpy(fx->scene->lights[i].color, l->color, sizeof(l->color));
        fx->scene->lights[i].orbit = l->orbit;
        if (!fx->scene->lights[i].point) sbfx_normalize3(fx->scene->lights[i].vector);
    }
    memcpy(fx->scene->ambient, scene->ambient, sizeof(fx->scene->ambient));
    memcpy(fx->scene->effects, scene->effects, sizeof(fx->scene->effects));
    fx->scene->post = scene->post;
    fx->scene->early_termination = scene->early_termination;
    fx->scene->effect_count = scene->effect_count;
    fx->scene->light_slots = sbfx_light_slots_of_scene(fx);
    for (int e = 0; e < fx->scene->effect_count; e++)
        for (int i = 0; i < fx->scene->effects[e].emitter_count; i++)
            fx->scene->uses_medium[fx->scene->effects[e].emitters[i].medium] = true;
    fx->scene->plan.distortion = fx->scene->uses_medium[SBFX_HEAT];
    fx->scene->plan.particle_velocity = fx->scene->post.blur == SBFX_BLUR_VELOCITY;
    fx->scene->plan.motion_target = fx->scene->plan.particle_velocity || fx->scene->post.dof;
    fx->scene->plan.owns_scene = fx->scene->plan.distortion || fx->scene->post.blur != SBFX_BLUR_NONE || fx->scene->post.dof;
    fx->scene->instance_floats = 8;
    fx->scene->instance_previous = fx->scene->plan.particle_velocity ? (fx->scene->instance_floats += 4, 8) : 0;
    /* a slot for the per-particle light when a declared level uses it (bit-identical frames
     * either way: levels without it do not read it) */
    fx->scene->instance_light = sbfx_declared_any(fx, sbfx_quality_uses_light_slot) ? (fx->scene->instance_floats += 4) - 4 : 0;
    fx->scene->plan.fire_light = sbfx_fire_lights_media(fx);
    fx->scene->instance_fire = fx->scene->plan.fire_light ? (fx->scene->instance_floats += 8) - 8 : 0;
}

int sbfx_effect_index(const sbfx *fx, const char *name)
{
    for (int i = 0; i < fx->scene->effect_count; i++)
        if (strcmp(fx->scene->effects[i].name, name) == 0) return i;
    return -1;
}


/* The phase shaders' light loop is unrolled by the compiler (a Mali counts every iteration:
 * docs/gpus.md), so it is sized at load: the scene's lights and the flashes of one effect
 * instance. More flashes at once than that: the brightest are lit (render/lights.c). */
int sbfx_light_slots_of_scene(const sbfx *fx)
{
    int flashes = 0;
    for (int e = 0; e < fx->scene->effect_count; e++)
        if (fx->scene->effects[e].flash_count > flashes) flashes = fx->scene->effects[e].flash_count;
    int slots = fx->scene->light_count + flashes;
    return slots < SBFX_SHADER_LIGHTS ? slots : SBFX_SHADER_LIGHTS;
}

/* Fire lights its dust and smoke where it emits and they scatter (the phase model's and lit
 * media alike). */
bool sbfx_fire_lights_media(const sbfx *fx)
{
    const sbfx_medium_params *fire = &fx->scene->media[SBFX_FIRE];
    if (!fx->scene->uses_medium[SBFX_FIRE] || !(fire->emissivity > 0.0f || fire->emission_scale > 0.0f)) return false;
    for (int m = SBFX_DUST; m <= SBFX_SMOKE; m++)
        if (fx->scene->uses_medium[m] && fx->scene->media[m].albedo > 0.0f) return true;
    return false;
}

bool sbfx_declared_any(const sbfx *fx, bool (*uses)(const sbfx *, const sbfx_quality *))
{
    for (int i = 0; i < fx->scene->declared_count; i++)
        if (uses(fx, &fx->scene->declared[i])) return true;
    return false;
}

bool sbfx_quality_uses_light_slot(const sbfx *fx, const sbfx_quality *q) { return q->light_per_particle; }

bool sbfx_fire_lit(const sbfx *fx) { return fx->scene->plan.fire_light; }

sbfx_medium_params *sbfx_media(sbfx *fx) { return fx->scene->media; }
const sbfx_desc *sbfx_get_desc(const sbfx *fx) { return &fx->scene->desc; }
