/* The seed's media and the built-in explosion (16 dust, 115 fire, 28 smoke particles). */
#include <string.h>
#include "scene/model.h"

void sbfx_default_media(sbfx_medium_params media[SBFX_MEDIUM_COUNT])
{
    /* Seed §3.1: dust a = 0.9, smoke a = 0.2, both tau = 0.4; g = 0 "gives satisfactory
     * results". Fire (§3.2) is a black body: albedo 0. Detail window 0.8 of the 128-texel
     * volume: about 100 texels across a particle, features down to a few pixels (docs/look.md). */
    media[SBFX_DUST] = (sbfx_medium_params){
        .albedo = 0.9f, .tau = 0.4f, .phase_g = 0.0f, .color = {0.80f, 0.70f, 0.56f},
        .detail_strength = 0.8f, .detail_window = 0.8f};
    media[SBFX_SMOKE] = (sbfx_medium_params){
        .albedo = 0.2f, .tau = 0.4f, .phase_g = 0.0f, .color = {1.0f, 1.0f, 1.0f},
        .detail_strength = 0.8f, .detail_window = 0.8f};
    media[SBFX_FIRE] = (sbfx_medium_params){
        .albedo = 0.0f, .tau = 0.4f, .phase_g = 0.0f, .color = {1.0f, 1.0f, 1.0f},
        .detail_strength = 1.0f, .detail_window = 0.8f,
        .t0 = 1100.0f, .t1 = 900.0f, .cooling = 0.45f, .emissivity = 1.0f, .soot = SBFX_FIRE_SOOT_DEFAULT};
    /* Heat: shimmer of up to 1% of the image, noise a quarter of the volume per particle. */
    media[SBFX_HEAT] = (sbfx_medium_params){
        .albedo = 0.0f, .tau = 1.0f, .color = {1.0f, 1.0f, 1.0f}, .detail_strength = 1.0f,
        .detail_window = 0.25f, .heat_strength = 0.01f};
    /* Lighting defaults for media a scene switches to "lit" (the lit-smoke seed's w = 0.6). */
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) {
        media[m].wrap = 0.6f;
        media[m].translucency = 1.0f;
        media[m].steps_min = 4, media[m].steps_max = 16;
        media[m].texture_size = 128, media[m].texture_variants = 4;
    }
}

void sbfx_builtin_explosion(sbfx_effect *out)
{
    memset(out, 0, sizeof(*out));
    strcpy(out->name, "explosion");
    out->emitter_count = 3;
    /* Fire: a fast burst that rises, slows under drag and cools as it thins. */
    out->emitters[0] = (sbfx_emitter){
        .medium = SBFX_FIRE, .count = 115, .delay = 0.0f, .spawn_radius = 0.45f,
        .speed_min = 2.0f, .speed_max = 5.0f, .upward = 0.45f, .life_min = 1.2f, .life_max = 2.4f,
        .radius_start = 0.35f, .radius_end = 0.95f, .radius_jitter = 0.3f, .drag = 2.2f,
        .buoyancy = 1.8f, .intensity_start = 1.0f, .intensity_end = 0.0f, .fade_in = 0.06f};
    /* Smoke: follows the fire, grows and thins for the rest of the 3 s. */
    out->emitters[1] = (sbfx_emitter){
        .medium = SBFX_SMOKE, .count = 28, .delay = 0.2f, .spawn_radius = 0.7f,
        .speed_min = 0.8f, .speed_max = 2.2f, .upward = 0.7f, .life_min = 2.2f, .life_max = 2.8f,
        .radius_start = 0.6f, .radius_end = 1.9f, .radius_jitter = 0.25f, .drag = 1.0f,
        .buoyancy = 1.1f, .intensity_start = 1.0f, .intensity_end = 0.0f, .fade_in = 0.2f};
    /* Dust: thrown sideways along the ground, swirling and settling. */
    out->emitters[2] = (sbfx_emitter){
        .medium = SBFX_DUST, .count = 16, .delay = 0.0f, .spawn_radius = 0.5f,
        .speed_min = 2.5f, .speed_max = 4.5f, .upward = 0.1f, .life_min = 2.0f, .life_max = 3.0f,
        .radius_start = 0.6f, .radius_end = 1.6f, .radius_jitter = 0.2f, .drag = 1.6f,
        .buoyancy = 0.15f, .intensity_start = 0.9f, .intensity_end = 0.0f, .fade_in = 0.1f};
    /* The blast lights its own smoke and dust for half a second. */
    out->flash_count = 1;
    out->flashes[0] = (sbfx_flash){.delay = 0.0f, .duration = 0.5f, .color = {6.0f, 4.0f, 2.0f},
                                   .offset = {0.0f, 0.8f, 0.0f}};
}

/* Post effects are off until a scene asks; these are the values a partial block keeps. */
void sbfx_default_post(sbfx_post_params *post)
{
    *post = (sbfx_post_params){.blur = SBFX_BLUR_NONE, .persistence = 0.08f, .tile = 8, .samples = 15,
                               .shutter = 0.5f, .dof = false, .dof_near = {0.5f, 2.0f},
                               .dof_far = {20.0f, 60.0f}, .dof_max_radius = 8.0f, .dof_scale = 2};
}
