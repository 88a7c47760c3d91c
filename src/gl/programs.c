/* Shader variants, vertex arrays and the instance buffer, created once at load for the media
 * the loaded effects use: an effect that does not use a feature does not pay for it. */
#include <stdio.h>
#include "gl/gl.h"

static const char *const opacity_defines[SBFX_OPACITY_COUNT] = {
    [SBFX_OPACITY_PLANAR] = "#define OPACITY_PLANAR\n",
    [SBFX_OPACITY_SOFT] = "#define OPACITY_SOFT\n",
    [SBFX_OPACITY_SPHERICAL] = "#define OPACITY_SPHERICAL\n",
    [SBFX_OPACITY_EXACT] = "#define OPACITY_EXACT\n",
    [SBFX_OPACITY_FLOOR] = "#define OPACITY_FLOOR\n",
};

/* Lit media (the lit-smoke seed) replace the phase function by per-pixel lighting; the ray
 * march is compiled only where it has steps to take. */
void sbfx_particle_defines(const sbfx *fx, const sbfx_variant_key *key, sbfx_medium m, char *out, size_t size)
{
    const sbfx_medium_params *p = &fx->scene->media[m];
    bool heat = m == SBFX_HEAT;
    bool scatters = p->albedo > 0 && !heat, emits = m == SBFX_FIRE, lit = scatters && p->lit;
    bool float_targets = sbfx_half_float_renderable();
    if (scatters && (lit || !key->lpp)) { /* lit media light at most SBFX_LIT_MAX_LIGHTS */
        int slots = lit && fx->scene->light_slots > SBFX_LIT_MAX_LIGHTS ? SBFX_LIT_MAX_LIGHTS : fx->scene->light_slots;
        size_t n = (size_t)snprintf(out, size, "#define LIGHT_SLOTS %d\n", slots);
        out += n, size -= n;
    }
    size_t used = (size_t)snprintf(out, size, "%s%s%s%s%s%s", heat ? "#define MEDIUM_HEAT\n" : "",
                                   scatters && fx->scene->plan.fire_light ? "#define FIRE_LIGHT\n" : "",
                                   scatters && !lit && key->lpp ? "#define LIGHT_PER_PARTICLE\n" : "",
                                   fx->scene->plan.particle_velocity ? "#define HAS_PARTICLE_MOTION\n" : "",
                                   fx->scene->plan.distortion && float_targets ? "#define HAS_DISTORTION_TARGET\n" : "",
                                   fx->scene->plan.motion_target ? "#define HAS_MOTION_TARGET\n" : "");
    out += used, size -= used;
    /* SBFX_FILTER_BITS filters in the shader what the texture unit would: not an R32F volume,
     * which is sampled NEAREST (luts.c) */
    bool detail_nearest = fx->gl->context.filter_bits > 0 && fx->scene->desc.detail_format == SBFX_DETAIL_R32F;
    snprintf(out, size, "%s%s%s%s%s%s%s%s%s", opacity_defines[key->opacity],
             scatters ? "#define MEDIUM_SCATTERS\n" : "", emits ? "#define MEDIUM_EMITS\n" : "",
             p->detail_strength > 0 ? "#define HAS_DETAIL\n" : "", detail_nearest ? "#define DETAIL_NEAREST\n" : "",
             emits && key->abb ? "#define BLACKBODY_ANALYTIC\n" : "",
             scatters && !lit && (key->aph || fx->tables->phase_missed[m]) ? "#define PHASE_ANALYTIC\n" : "",
             lit ? "#define LIGHTING_LIT\n" : "", lit && p->steps_max > 0 ? "#define LIT_SHADOW\n" : "");
}

void sbfx_program_locate(sbfx_program *p)
{
    GLuint id = p->id;
    p->near = glGetUniformLocation(id, "u_near");
    p->projection = glGetUniformLocation(id, "u_projection");
    p->ray_map = glGetUniformLocation(id, "u_ray_map");
    p->pixel = glGetUniformLocation(id, "u_pixel");
    p->octagon = glGetUniformLocation(id, "u_octagon");
    p->tau = glGetUniformLocation(id, "u_tau");
    p->full_size = glGetUniformLocation(id, "u_full_size");
    p->heat_strength = glGetUniformLocation(id, "u_heat_strength");
    p->soft_scale = glGetUniformLocation(id, "u_soft_scale");
    p->depth = glGetUniformLocation(id, "u_depth");
    p->detail = glGetUniformLocation(id, "u_detail");
    p->detail_window = glGetUniformLocation(id, "u_detail_window");
    p->detail_strength = glGetUniformLocation(id, "u_detail_strength");
    p->time = glGetUniformLocation(id, "u_time");
    p->phase_lut = glGetUniformLocation(id, "u_phase_lut");
    p->phase_row = glGetUniformLocation(id, "u_phase_row");
    p->phase_warp = glGetUniformLocation(id, "u_phase_warp");
    p->phase_shift = glGetUniformLocation(id, "u_phase_shift");
    p->phase_analytic = glGetUniformLocation(id, "u_phase_analytic");
    p->albedo_color = glGetUniformLocation(id, "u_albedo_color");
    p->light_count = glGetUniformLocation(id, "u_light_count");
    p->light_vector = glGetUniformLocation(id, "u_light_vector");
    p->light_color = glGetUniformLocation(id, "u_light_color");
    p->ambient = glGetUniformLocation(id, "u_ambient");
    p->blackbody = glGetUniformLocation(id, "u_blackbody");
    p->blackbody_map = glGetUniformLocation(id, "u_blackbody_map");
    p->probe = glGetUniformLocation(id, "u_probe");
    p->temperature = glGetUniformLocation(id, "u_temperature");
    p->emission_scale = glGetUniformLocation(id, "u_emission_scale");
    p->cmf_rgb = glGetUniformLocation(id, "u_cmf_rgb");
    p->cmf_band = glGetUniformLocation(id, "u_cmf_band");
    p->smoke = glGetUniformLocation(id, "u_smoke");
    p->smoke_size = glGetUniformLocation(id, "u_smoke_size");
    p->smoke_variants = glGetUniformLocation(id, "u_smoke_variants");
    p->wrap = glGetUniformLocation(id, "u_wrap");
    p->translucency = glGetUniformLocation(id, "u_translucency");
    p->dampening = glGetUniformLocation(id, "u_direct");
    p->steps = glGetUniformLocation(id, "u_steps");
}

/* Constant for the program's life: set once here, not per frame. */
void sbfx_program_load_cmf(const sbfx *fx, const sbfx_program *p)
{
    glUseProgram(p->id);
    glUniform1i(glGetUniformLocation(p->id, "u_cmf_count"), fx->tables->cmf_bands);
    glUniform3fv(p->cmf_rgb, fx->tables->cmf_bands, fx->tables->cmf_rgb);
    glUniform1fv(p->cmf_band, fx->tables->cmf_bands, fx->tables->cmf_band);
    glUseProgram(0);
}

int sbfx_variant_index(const sbfx_variant_key *k)
{
    return (int)k->opacity * 8 + (k->lpp ? 4 : 0) + (k->abb ? 2 : 0) + (k->aph ? 1 : 0);
}

sbfx_result sbfx_variant_build(sbfx *fx, const sbfx_variant_key *key)
{
    sbfx_variant *v = &fx->gl->variants[sbfx_variant_index(key)];
    if (v->built) return SBFX_OK;
    char defines[384];
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) {
        if (!fx->scene->uses_medium[m]) continue;
        sbfx_particle_defines(fx, key, (sbfx_medium)m, defines, sizeof(defines));
        sbfx_program *p = &v->particle[m];
        p->id = sbfx_program_build(fx, "particle.vert", "particle.frag", defines);
        if (!p->id) return SBFX_ERR_SHADER;
        sbfx_program_locate(p);
        if (m == SBFX_FIRE && key->abb) sbfx_program_load_cmf(fx, p);
    }
    v->built = true;
    return SBFX_OK;
}

static void locate_pass_uniforms(GLuint id, sbfx_pass_uniforms *u)
{
    u->scene_depth = glGetUniformLocation(id, "u_scene_depth");
    u->divisor = glGetUniformLocation(id, "u_divisor");
    u->full_size = glGetUniformLocation(id, "u_full_size");
    u->depth_model = glGetUniformLocation(id, "u_depth_model");
    u->near = glGetUniformLocation(id, "u_near");
    u->closer = glGetUniformLocation(id, "u_closer");
    u->particles = glGetUniformLocation(id, "u_particles");
    u->low_depth = glGetUniformLocation(id, "u_low_depth");
    u->low_size = glGetUniformLocation(id, "u_low_size");
    u->depth_threshold = glGetUniformLocation(id, "u_depth_threshold");
    u->scene_color = glGetUniformLocation(id, "u_scene_color");
    u->scene_known = glGetUniformLocation(id, "u_scene_known");
    u->distortion = glGetUniformLocation(id, "u_distortion");
    u->tone_curve = glGetUniformLocation(id, "u_tone_curve");
    u->low_corners = glGetUniformLocation(id, "u_low_corners");
    u->particles_far = glGetUniformLocation(id, "u_particles_far");
    u->near_over_far = glGetUniformLocation(id, "u_near_over_far");
    u->tile_size = glGetUniformLocation(id, "u_tile_size");
    u->tile_grid = glGetUniformLocation(id, "u_tile_grid");
    u->tile_target = glGetUniformLocation(id, "u_tile_target");
    u->refined = glGetUniformLocation(id, "u_refined");
    u->contrast = glGetUniformLocation(id, "u_contrast");
    u->inv_divisor = glGetUniformLocation(id, "u_inv_divisor");
    u->low_texel = glGetUniformLocation(id, "u_low_texel");
    u->corners_texel = glGetUniformLocation(id, "u_corners_texel");
    u->near_model = glGetUniformLocation(id, "u_near_model");
    u->tone_filmic = glGetUniformLocation(id, "u_tone_filmic");
    u->tone_shoulder = glGetUniformLocation(id, "u_tone_shoulder");
    u->full_texel = glGetUniformLocation(id, "u_full_texel");
    u->epsilon = glGetUniformLocation(id, "u_epsilon");
}

/* Where RGBA32F renders, nearest-depth upsampling reads its four depths in one fetch from the
 * low-res corners (low_corners.frag, render/passes.c): made with the first nearest-depth composite. */
static sbfx_result build_corners_program(sbfx *fx)
{
    if (fx->gl->corners_program || !sbfx_float32_renderable()) return SBFX_OK;
    fx->gl->corners_program = sbfx_program_build(fx, "tiles.vert", "low_corners.frag", NULL);
    if (!fx->gl->corners_program) return SBFX_ERR_SHADER;
    locate_pass_uniforms(fx->gl->corners_program, &fx->gl->corners_u);
    return SBFX_OK;
}

/* Mixed resolution (render/refine.c): the pass that marks the pixels to refine, made with the
 * first mixed composite. */
static sbfx_result build_refine_mark_program(sbfx *fx)
{
    sbfx_gl *gl = fx->gl;
    if (gl->refine_mark_program) return SBFX_OK;
    gl->refine_depth_program = sbfx_program_build(fx, "tiles.vert", "depth_downsample.frag", "#define SINGLE_TEXEL\n");
    if (!gl->refine_depth_program) return SBFX_ERR_SHADER;
    locate_pass_uniforms(gl->refine_depth_program, &gl->refine_depth_u);
    gl->refine_mark_program = sbfx_program_build(fx, "tiles.vert", "refine_mark.frag",
                                                 gl->corners_program ? "#define LOW_CORNERS\n" : NULL);
    if (!gl->refine_mark_program) return SBFX_ERR_SHADER;
    locate_pass_uniforms(gl->refine_mark_program, &gl->refine_mark_u);
    return SBFX_OK;
}

static const char *const tone_map_defines[SBFX_TONE_MAP_COUNT] = {
    [SBFX_TONE_MAP_NONE] = "#define TONE_MAP_NONE\n",
    [SBFX_TONE_MAP_HUE_PRESERVING] = "#define TONE_MAP_HUE_PRESERVING\n",
    [SBFX_TONE_MAP_PER_CHANNEL] = "#define TONE_MAP_PER_CHANNEL\n",
    [SBFX_TONE_MAP_FILMIC] = "#define TONE_MAP_FILMIC\n",
};

/* Where sbfx owns the scene, the pixels outside the particles' tiles get the scene as the
 * composite would read it there (composite.frag SCENE_ONLY; render/tiles.h): one program for
 * every level. */
static sbfx_result build_scene_only_program(sbfx *fx)
{
    if (fx->gl->scene_only_program || !fx->scene->plan.owns_scene) return SBFX_OK;
    char defines[96];
    snprintf(defines, sizeof(defines), "#define OWN_SCENE\n#define SCENE_ONLY\n%s",
             fx->scene->plan.distortion && sbfx_half_float_renderable() ? "#define HAS_SHIMMER\n" : "");
    fx->gl->scene_only_program = sbfx_program_build(fx, "tiles.vert", "composite.frag", defines);
    if (!fx->gl->scene_only_program) return SBFX_ERR_SHADER;
    locate_pass_uniforms(fx->gl->scene_only_program, &fx->gl->scene_only_u);
    return SBFX_OK;
}

sbfx_result sbfx_composite_build(sbfx *fx, sbfx_upsample upsample)
{
    if (fx->gl->composites[upsample]) return SBFX_OK;
    char defines[256];
    bool mixed = upsample == SBFX_UPSAMPLE_MIXED && sbfx_half_float_renderable();
    bool nearest_depth = upsample == SBFX_UPSAMPLE_NEAREST_DEPTH || upsample == SBFX_UPSAMPLE_MIXED;
    sbfx_result r = nearest_depth ? build_corners_program(fx) : SBFX_OK;
    if (r == SBFX_OK) r = build_scene_only_program(fx);
    if (r == SBFX_OK && mixed) r = build_refine_mark_program(fx);
    if (r != SBFX_OK) return r;
    snprintf(defines, sizeof(defines), "%s%s%s%s%s%s%s",
             nearest_depth ? "#define UPSAMPLE_NEAREST_DEPTH\n" : "#define UPSAMPLE_BILINEAR\n",
             mixed ? "#define REFINED\n" : "",
             nearest_depth && fx->gl->corners_program ? "#define LOW_CORNERS\n" : "",
             fx->scene->plan.owns_scene ? "#define OWN_SCENE\n" : "",
             fx->scene->plan.owns_scene && fx->scene->post.dof ? "#define TRANSMITTANCE_ALPHA\n" : "",
             fx->scene->plan.distortion && sbfx_half_float_renderable() ? "#define HAS_SHIMMER\n" : "",
             tone_map_defines[fx->scene->desc.tone_map]);
    GLuint id = sbfx_program_build(fx, "tiles.vert", "composite.frag", defines);
    if (!id) return SBFX_ERR_SHADER;
    fx->gl->composites[upsample] = id;
    locate_pass_uniforms(id, &fx->gl->composite_us[upsample]);
    return SBFX_OK;
}

static sbfx_result build_depth_program(sbfx *fx)
{
    fx->gl->depth_program = sbfx_program_build(fx, "tiles.vert", "depth_downsample.frag", NULL);
    if (!fx->gl->depth_program) return SBFX_ERR_SHADER;
    locate_pass_uniforms(fx->gl->depth_program, &fx->gl->depth_u);
    return SBFX_OK;
}

/* Early termination's mark (render/terminate.c), made with the first frame that uses it. */
sbfx_result sbfx_stop_program_build(sbfx *fx)
{
    if (fx->gl->stop_program) return SBFX_OK;
    fx->gl->stop_program = sbfx_program_build(fx, "tiles.vert", "terminate_mark.frag", NULL);
    if (!fx->gl->stop_program) return SBFX_ERR_SHADER;
    locate_pass_uniforms(fx->gl->stop_program, &fx->gl->stop_u);
    return SBFX_OK;
}

static sbfx_result create_buffers(sbfx *fx)
{
    sbfx_gl *gl = fx->gl;
    if (!gl->fullscreen_vao) glGenVertexArrays(1, &gl->fullscreen_vao);
    glGenVertexArrays(1, &gl->particle_vao);
    glGenBuffers(1, &gl->instance_buffer);
    glBindVertexArray(gl->particle_vao);
    glBindBuffer(GL_ARRAY_BUFFER, gl->instance_buffer);
    size_t bytes = (size_t)fx->sim->pool.capacity * fx->scene->instance_floats * sizeof(float);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)bytes, NULL, GL_DYNAMIC_DRAW);
    /* 0 centre + radius, 1 detail + intensity, 2 previous centre, 3 per-particle light, 4 and 5
     * fire light (colour and d2, position) */
    bool used[6] = {true, true, fx->scene->instance_previous > 0, fx->scene->instance_light > 0, fx->scene->instance_fire > 0,
                    fx->scene->instance_fire > 0};
    for (GLuint a = 0; a < 6; a++) {
        if (!used[a]) continue;
        glEnableVertexAttribArray(a);
        glVertexAttribDivisor(a, 1);
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    fx->counters.gpu_bytes += bytes;
    return sbfx_gl_check(fx, "creating the particle instance buffer") ? SBFX_OK : SBFX_ERR_GL;
}

sbfx_result sbfx_programs_create(sbfx *fx)
{
    sbfx_result r;
    if ((r = build_depth_program(fx)) != SBFX_OK) return r;
    if (fx->scene->early_termination && (r = sbfx_stop_program_build(fx)) != SBFX_OK) return r;
    return create_buffers(fx);
}

/* First use of a level with light per particle in a module made without: a wider instance
 * layout (the CPU copy and the buffer's storage; the buffer object stays). */
sbfx_result sbfx_instances_reserve_light(sbfx *fx)
{
    size_t floats = (size_t)fx->sim->pool.capacity * (size_t)(fx->scene->instance_floats + 4);
    float *wider = sbfx_calloc(fx, floats, sizeof(float));
    if (!wider) return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "out of memory");
    sbfx_free(fx, fx->sim->instances);
    fx->sim->instances = wider;
    fx->counters.gpu_bytes -= (size_t)fx->sim->pool.capacity * fx->scene->instance_floats * sizeof(float);
    fx->scene->instance_light = fx->scene->instance_floats;
    fx->scene->instance_floats += 4;
    glBindVertexArray(0);
    glDeleteBuffers(1, &fx->gl->instance_buffer);
    glDeleteVertexArrays(1, &fx->gl->particle_vao);
    return create_buffers(fx);
}

void sbfx_programs_destroy(sbfx *fx)
{
    sbfx_gl *gl = fx->gl;
    for (int v = 0; v < SBFX_VARIANTS; v++)
        for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
            sbfx_program_delete(fx, gl->variants[v].particle[m].id);
    for (int u = 0; u < SBFX_UPSAMPLE_COUNT; u++) sbfx_program_delete(fx, gl->composites[u]);
    GLuint programs[] = {gl->depth_program, gl->corners_program, gl->scene_only_program, gl->refine_mark_program,
                         gl->refine_depth_program, gl->stop_program};
    for (size_t i = 0; i < ARRAY_SIZE(programs); i++) sbfx_program_delete(fx, programs[i]);
    if (gl->instance_buffer) glDeleteBuffers(1, &gl->instance_buffer);
    GLuint vaos[] = {gl->fullscreen_vao, gl->particle_vao};
    for (size_t i = 0; i < ARRAY_SIZE(vaos); i++)
        if (vaos[i]) glDeleteVertexArrays(1, &vaos[i]);
}
