/* The three GPU passes of a frame with live particles, between one save and one restore of
 * the host's GL state (gl_state.c). */
#include <math.h>
#include <string.h>
#include "module.h"

#define UNIT_DEPTH 0
#define UNIT_DETAIL 1
#define UNIT_SMOKE 4 /* a lit medium's smoke texture array */
#define SBFX_FOUR_PI_F 12.566370614f

/* Heat shimmer in the composite: heat particles and a float target to hold their offsets. */
static bool shimmer(const sbfx *fx) { return fx->plan.distortion && fx->gl.particles.texture[1]; }

/* The frame's projection as the passes' uniforms. */
typedef struct frame_params {
    float projection[4];   /* P[0], P[5], P[8], P[9] */
    float depth_model[4];  /* window depth -> distance (projection.c) */
    float near;
    float particles_far;   /* view distance (along -z) beyond which no drawn particle reaches */
} frame_params;

/* The farthest view distance any of the first `count` particles reaches: its centre's distance
 * along -z plus its radius, at least `near` (the composite clamps depths to it and divides by
 * it). Nearest-depth upsampling needs no care beyond it (composite.frag). */
static float particles_far(const sbfx *fx, int count, float near)
{
    float far = near;
    for (int i = 0; i < count; i++) {
        const sbfx_view_particle *v = &fx->view[i];
        float reach = -v->center[2] + v->radius;
        if (reach > far) far = reach;
    }
    return far;
}

static frame_params frame_params_from(const sbfx_depth_model *m)
{
    frame_params fp = {{m->projection[0], m->projection[1], m->projection[2], m->projection[3]}, {0}, (float)m->near,
                       0.0f};
    sbfx_depth_model_uniform(m, fp.depth_model);
    return fp;
}

/* Pass 1: the closest opaque distance of each low-res texel, as near / distance (0: none). */
static void pass_depth(sbfx *fx, const sbfx_frame *f, const frame_params *fp)
{
    sbfx_gl *gl = &fx->gl;
    GLuint prog = gl->depth_program;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gl->low_depth.framebuffer);
    glViewport(0, 0, gl->low_width, gl->low_height);
    glEnable(GL_DEPTH_TEST); /* depth writes need the test on; ALWAYS keeps every fragment */
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glUseProgram(prog);
    sbfx_bind_texture(0, GL_TEXTURE_2D, f->scene_depth_texture, gl->depth_sampler);
    const sbfx_pass_uniforms *u = &gl->depth_u;
    glUniform1i(u->scene_depth, 0);
    glUniform1i(u->divisor, fx->desc.target_divisor);
    glUniform2i(u->full_size, f->width, f->height);
    glUniform4fv(u->depth_model, 1, fp->depth_model);
    glUniform1f(u->near, fp->near);
    glBindVertexArray(gl->fullscreen_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    fx->counters.passes++;
    fx->counters.draw_calls++;
}

/* Pass 1b (nearest-depth upsampling, RGBA32F devices): the four low-res depths around each
 * texel gathered into one RGBA32F texel (low_corners.frag), so the composite reads them in one
 * fetch instead of four. */
static bool corners_used(const sbfx *fx)
{
    return fx->gl.low_corners.framebuffer && fx->desc.upsample == SBFX_UPSAMPLE_NEAREST_DEPTH;
}

static void pass_corners(sbfx *fx)
{
    sbfx_gl *gl = &fx->gl;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gl->low_corners.framebuffer);
    glViewport(0, 0, gl->low_corners.width, gl->low_corners.height);
    glDisable(GL_BLEND); /* a copy: whatever blending the host left on */
    glUseProgram(gl->corners_program);
    sbfx_bind_texture(0, GL_TEXTURE_2D, gl->low_depth.depth, 0);
    glUniform1i(gl->corners_u.low_depth, 0);
    glUniform2i(gl->corners_u.low_size, gl->low_width, gl->low_height);
    glBindVertexArray(gl->fullscreen_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    fx->counters.passes++;
    fx->counters.draw_calls++;
}

/* The lights of this frame in view space: the scene's, then the live flashes (fading out
 * linearly over their duration). */
typedef struct frame_lights {
    int count;
    float vector[SBFX_SHADER_LIGHTS][4];
    float color[SBFX_SHADER_LIGHTS][3];
} frame_lights;

static void to_view(const float m[16], const float v[3], float w, float out[4])
{
    for (int r = 0; r < 3; r++) out[r] = m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * w;
    out[3] = w;
}

static void gather_lights(const sbfx *fx, const float view[16], frame_lights *out)
{
    out->count = 0;
    for (int i = 0; i < fx->light_count && out->count < SBFX_SHADER_LIGHTS; i++, out->count++) {
        const sbfx_scene_light *l = &fx->lights[i];
        to_view(view, l->vector, l->point ? 1.0f : 0.0f, out->vector[out->count]);
        memcpy(out->color[out->count], l->color, sizeof(l->color));
    }
    /* live flashes, brightest first, as many as the shaders' light slots hold (lights.c) */
    int order[SBFX_MAX_LIVE_FLASHES], lit = 0;
    float weight[SBFX_MAX_LIVE_FLASHES];
    for (int i = 0; i < fx->flash_count; i++) {
        const sbfx_live_flash *f = &fx->flashes[i];
        double t = (fx->time - f->start) / f->duration;
        if (t < 0.0 || t >= 1.0) continue;
        float w = (f->color[0] + f->color[1] + f->color[2]) * (float)(1.0 - t);
        int at = lit++;
        for (; at > 0 && weight[at - 1] < w; at--) order[at] = order[at - 1], weight[at] = weight[at - 1];
        order[at] = i, weight[at] = w;
    }
    for (int j = 0; j < lit && out->count < fx->light_slots; j++, out->count++) {
        const sbfx_live_flash *f = &fx->flashes[order[j]];
        double t = (fx->time - f->start) / f->duration;
        to_view(view, f->position, 1.0f, out->vector[out->count]);
        for (int k = 0; k < 3; k++) out->color[out->count][k] = f->color[k] * (float)(1.0 - t);
    }
}

/* Lit media (LIGHTING_LIT): their own texture array, wrap as scale and bias (seed eq. 5.2.3). */
static void set_lit_uniforms(sbfx *fx, const sbfx_program *p, sbfx_medium m)
{
    const sbfx_medium_params *mp = &fx->media[m];
    sbfx_bind_texture(UNIT_SMOKE, GL_TEXTURE_2D_ARRAY, fx->gl.smoke_texture[m], 0);
    glUniform1i(p->smoke, UNIT_SMOKE);
    glUniform1f(p->smoke_size, (float)mp->texture_size);
    glUniform1f(p->smoke_variants, (float)mp->texture_variants);
    glUniform3f(p->wrap, 1.0f / (1.0f + mp->wrap), mp->wrap / (1.0f + mp->wrap), 1.0f + mp->wrap);
    glUniform1f(p->translucency, mp->translucency);
    glUniform1f(p->dampening, 1.0f - mp->dampening); /* u_direct */
    glUniform2f(p->steps, (float)mp->steps_min + 0.5f, (float)(mp->steps_max - mp->steps_min));
}

static void set_medium_uniforms(sbfx *fx, const sbfx_program *p, sbfx_medium m, const frame_lights *lights)
{
    const sbfx_medium_params *mp = &fx->media[m];
    glUniform1f(p->tau, mp->tau);
    glUniform1f(p->heat_strength, mp->heat_strength);
    glUniform1f(p->soft_scale, 0.0f);
    glUniform1i(p->detail, UNIT_DETAIL);
    glUniform1f(p->detail_window, mp->detail_window);
    glUniform1f(p->detail_strength, mp->detail_strength);
    glUniform1f(p->time, (float)sbfx_detail_time(fx));
    /* pre-exposed (docs/look-fire.md): the exposure scales the light where it is made, so the
     * particle target holds what the display gets and fire stays inside the radiance ceiling */
    float exposure = fx->desc.exposure, scatter = mp->albedo * exposure;
    glUniform3f(p->albedo_color, scatter * mp->color[0], scatter * mp->color[1], scatter * mp->color[2]);
    glUniform1i(p->light_count, lights->count);
    glUniform4fv(p->light_vector, lights->count, &lights->vector[0][0]);
    /* the phase model's 4 pi (a light of colour E scattered isotropically gives back E) folded in
     * here, not per fragment; lit media take the colours as they are */
    float color[SBFX_SHADER_LIGHTS][3];
    for (int i = 0; i < lights->count; i++)
        for (int k = 0; k < 3; k++) color[i][k] = lights->color[i][k] * (mp->lit ? 1.0f : SBFX_FOUR_PI_F);
    glUniform3fv(p->light_color, lights->count, &color[0][0]);
    glUniform3fv(p->ambient, 1, fx->ambient);
    glUniform4f(p->temperature, mp->t0, mp->t1, mp->cooling, mp->soot);
    glUniform1f(p->emission_scale, mp->emission_scale * (1.0f - mp->albedo) * exposure);
    sbfx_tables_bind(fx, p, m);
    if (fx->gl.smoke_texture[m]) set_lit_uniforms(fx, p, m);
}

static void set_frame_uniforms(sbfx *fx, const sbfx_program *p, const frame_params *fp)
{
    const sbfx_gl *gl = &fx->gl;
    glUniform1f(p->near, fp->near);
    glUniform4fv(p->projection, 1, fp->projection);
    glUniform2f(p->target_size, (float)gl->low_width, (float)gl->low_height);
    glUniform2f(p->pixel, 2.0f / gl->low_width, 2.0f / gl->low_height);
    glUniform1i(p->depth, UNIT_DEPTH);
    glUniform2f(p->full_size, (float)gl->out_width, (float)gl->out_height);
}

/* Writes the sorted particles into the instance buffer; returns nothing, cannot fail. */
/* In-scattered light of the phase model at the particle's centre, in double: what the
 * fragment shader's in_scattered() computes per pixel, once per particle instead. */
static void particle_light(const sbfx *fx, const frame_lights *lights, const sbfx_view_particle *v, float out[3])
{
    const sbfx_medium_params *m = &fx->media[v->medium];
    double c[3] = {v->center[0], v->center[1], v->center[2]};
    double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    double to_eye[3] = {-c[0] / len, -c[1] / len, -c[2] / len};
    double sum[3] = {fx->ambient[0], fx->ambient[1], fx->ambient[2]};
    for (int i = 0; i < lights->count && len > 0; i++) {
        const float *l = lights->vector[i];
        double travel[3] = {l[0], l[1], l[2]}, falloff = 1.0;
        if (l[3] > 0.5f) {
            double d[3] = {c[0] - l[0], c[1] - l[1], c[2] - l[2]};
            double d2 = fmax(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 0.25);
            for (int k = 0; k < 3; k++) travel[k] = d[k] / sqrt(d2);
            falloff = 1.0 / d2;
        }
        double cos_theta = travel[0] * to_eye[0] + travel[1] * to_eye[1] + travel[2] * to_eye[2];
        double scattered = falloff * sbfx_phase(cos_theta, m->phase_g) * 4.0 * M_PI;
        for (int k = 0; k < 3; k++) sum[k] += lights->color[i][k] * scattered;
    }
    for (int k = 0; k < 3; k++) out[k] = (float)sum[k];
}

/* The frame's fire light in-scattered at a dust or smoke particle (fire_light.h): colour at the
 * centre and d2, then where it falls off from (sbfx_fire_scatter_instance). Lit media have no
 * phase function: theirs is isotropic (g = 0), shaded by their maps in the shader. */
static void particle_fire(sbfx *fx, const sbfx_view_particle *v, float out[8])
{
    memset(out, 0, 8 * sizeof(float));
    const sbfx_medium_params *m = &fx->media[v->medium];
    if (v->medium == SBFX_FIRE || !(m->albedo > 0.0f) || fx->frame_fire_count == 0) return;
    const double c[3] = {v->center[0], v->center[1], v->center[2]};
    sbfx_fire_scatter s;
    sbfx_fire_scatter_at(fx->frame_fire, fx->frame_fire_count, fx->desc.exposure, c, m->lit ? 0.0 : m->phase_g, &s);
    double values[8];
    sbfx_fire_scatter_instance(&s, c, v->radius, values);
    for (int k = 0; k < 8; k++) out[k] = (float)values[k];
    if (s.rgb[0] > 0.0 || s.rgb[1] > 0.0 || s.rgb[2] > 0.0) fx->counters.fire_lit_particles++;
}

static void upload_instances(sbfx *fx, const frame_lights *lights, int count)
{
    const int stride = fx->instance_floats;
    for (int i = 0; i < count; i++) {
        const sbfx_view_particle *v = &fx->view[fx->order[i]];
        float *dst = &fx->instances[stride * i];
        memcpy(dst, v->center, 3 * sizeof(float));
        dst[3] = v->radius;
        memcpy(dst + 4, v->detail, 3 * sizeof(float));
        dst[7] = v->intensity;
        if (fx->instance_previous) {
            memcpy(dst + fx->instance_previous, v->previous_center, 3 * sizeof(float));
            dst[fx->instance_previous + 3] = 0.0f;
        }
        if (fx->instance_light) {
            particle_light(fx, lights, v, dst + fx->instance_light);
            dst[fx->instance_light + 3] = 0.0f;
        }
        if (fx->instance_fire) particle_fire(fx, v, dst + fx->instance_fire);
    }
    glBindBuffer(GL_ARRAY_BUFFER, fx->gl.instance_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)((size_t)count * stride * sizeof(float)), fx->instances);
}

static void draw_run(sbfx *fx, int first, int count)
{
    const GLsizei stride = (GLsizei)(fx->instance_floats * sizeof(float));
    const char *base = (const char *)(size_t)((size_t)first * (size_t)stride);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, stride, base);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, stride, base + 4 * sizeof(float));
    if (fx->instance_previous)
        glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, stride, base + fx->instance_previous * sizeof(float));
    if (fx->instance_light)
        glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, stride, base + fx->instance_light * sizeof(float));
    if (fx->instance_fire) {
        glVertexAttribPointer(4, 4, GL_FLOAT, GL_FALSE, stride, base + fx->instance_fire * sizeof(float));
        glVertexAttribPointer(5, 4, GL_FLOAT, GL_FALSE, stride, base + (fx->instance_fire + 4) * sizeof(float));
    }
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, count);
    fx->counters.draw_calls++;
}

/* Pass 2: back to front; consecutive particles of one medium share a draw call. ES 3.0 has no
 * base instance, so each run re-points the instance attributes at its first particle. */
static void pass_particles(sbfx *fx, const sbfx_frame *f, const frame_params *fp, int count)
{
    sbfx_gl *gl = &fx->gl;
    frame_lights lights;
    gather_lights(fx, f->view, &lights);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gl->particles.framebuffer);
    glViewport(0, 0, gl->low_width, gl->low_height);
    /* No light added, everything transmitted, no offset, no motion: every attachment. */
    const GLfloat clear[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    for (GLint i = 0; i < SBFX_RT_MAX; i++)
        if (gl->particles.texture[i]) glClearBufferfv(GL_COLOR, i, clear);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    /* rgb = src + dst (1 - a); transmittance a = dst (1 - a) */
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
    sbfx_bind_texture(UNIT_DEPTH, GL_TEXTURE_2D, gl->low_depth.depth, 0);
    if (gl->detail_texture) sbfx_bind_texture(UNIT_DETAIL, GL_TEXTURE_3D, gl->detail_texture, 0);
    fx->counters.fire_lit_particles = 0;
    fx->frame_fire_count = 0;
    if (fx->plan.fire_light) sbfx_fire_lights_of_frame(fx, count);
    upload_instances(fx, &lights, count);
    glBindVertexArray(gl->particle_vao);
    for (int first = 0; first < count;) {
        sbfx_medium m = fx->view[fx->order[first]].medium;
        int end = first + 1;
        while (end < count && fx->view[fx->order[end]].medium == m) end++;
        const sbfx_program *p = &gl->particle[m];
        glUseProgram(p->id);
        set_frame_uniforms(fx, p, fp);
        set_medium_uniforms(fx, p, m, &lights);
        draw_run(fx, first, end - first);
        first = end;
    }
    fx->counters.passes++;
}

/* The tone map leaves room for the host's picture (composite.frag) when it may read the scene
 * colour: given, and not attached to the framebuffer being drawn (a feedback loop is undefined
 * in GLES). Two counted queries of the bound draw framebuffer when it is the host's own. */
static bool scene_color_readable(sbfx *fx, const sbfx_frame *f)
{
    if (!f->scene_color_texture) return false;
    if (f->out_framebuffer == 0) return true;
    GLint type = GL_NONE, name = 0;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                          GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    fx->counters.gl_state_queries++;
    if (type != GL_TEXTURE) return true;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                          GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
    fx->counters.gl_state_queries++;
    return (GLuint)name != f->scene_color_texture;
}

/* Pass 3: dst = dst * T + C over the host's framebuffer (its alpha is kept). */
static void pass_composite(sbfx *fx, const sbfx_frame *f, const frame_params *fp)
{
    sbfx_gl *gl = &fx->gl;
    GLuint prog = gl->composite_program;
    bool owns = fx->plan.owns_scene;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, owns ? sbfx_post_composite_target(fx, f) : f->out_framebuffer);
    glViewport(0, 0, f->width, f->height);
    if (owns) {
        glDisable(GL_BLEND); /* writes the whole image: scene * T + C */
    } else {
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
    }
    glUseProgram(prog);
    bool scene_known = owns || scene_color_readable(fx, f);
    if (scene_known) sbfx_bind_texture(3, GL_TEXTURE_2D, f->scene_color_texture, gl->color_sampler);
    glUniform1i(gl->composite_u.scene_color, 3);
    glUniform1i(gl->composite_u.scene_known, scene_known);
    if (owns) glUniform2f(gl->composite_u.full_size, (float)f->width, (float)f->height);
    if (shimmer(fx)) {
        sbfx_bind_texture(4, GL_TEXTURE_2D, gl->particles.texture[1], gl->color_sampler); /* LINEAR: bilinear in one fetch */
        glUniform1i(gl->composite_u.distortion, 4);
    }
    sbfx_bind_texture(0, GL_TEXTURE_2D, gl->particles.texture[0], 0);
    sbfx_bind_texture(1, GL_TEXTURE_2D, corners_used(fx) ? gl->low_corners.texture[0] : gl->low_depth.depth, 0);
    sbfx_bind_texture(2, GL_TEXTURE_2D, f->scene_depth_texture, gl->depth_sampler);
    const sbfx_pass_uniforms *u = &gl->composite_u;
    glUniform1i(u->particles, 0);
    glUniform1i(u->low_depth, 1);
    glUniform1i(u->low_corners, 1);
    glUniform1i(u->scene_depth, 2);
    glUniform2i(u->low_size, gl->low_width, gl->low_height);
    glUniform1f(u->divisor, (float)fx->desc.target_divisor);
    glUniform4fv(u->depth_model, 1, fp->depth_model);
    glUniform1f(u->near, fp->near);
    glUniform1f(u->depth_threshold, 0.05f);
    glUniform1f(u->particles_far, fp->particles_far);
    glUniform1f(u->near_over_far, fp->near / fp->particles_far);
    glUniform3f(u->tone_curve, (float)fx->tone_curve.knee, (float)fx->tone_curve.steepness,
                (float)fx->tone_curve.inverse_log_white);
    glBindVertexArray(gl->fullscreen_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    fx->counters.passes++;
    fx->counters.draw_calls++;
}

/* Which units the particle passes bind which targets on (depth, particle, composite). */
static sbfx_gl_units pass_units(const sbfx *fx, bool scene_color)
{
    const sbfx_gl *gl = &fx->gl;
    sbfx_gl_units u = {.tex_2d = 1u << 0 | 1u << 1 | 1u << 2};
    /* unit 3: the black body for the particles, the scene colour for the composite */
    if (gl->blackbody_texture || fx->plan.owns_scene || scene_color) u.tex_2d |= 1u << SBFX_UNIT_BLACKBODY;
    if (fx->plan.distortion) u.tex_2d |= 1u << 4; /* the shimmer offsets, when the target holds them */
    if (gl->detail_texture) u.tex_3d |= 1u << UNIT_DETAIL;
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (gl->smoke_texture[m]) u.tex_array |= 1u << UNIT_SMOKE;
    return u;
}

static sbfx_result draw_frame(sbfx *fx, const sbfx_frame *frame, const sbfx_depth_model *depth, int count)
{
    sbfx_result r = count > 0 ? sbfx_targets_ensure(fx, frame->width, frame->height) : SBFX_OK;
    if (r == SBFX_OK) r = sbfx_post_targets_ensure(fx, frame->width, frame->height);
    if (r != SBFX_OK) return r;
    frame_params fp = frame_params_from(depth);
    if (count > 0) {
        /* a lodN level: at most N particles, the least visible merged (src/sim/lod.h) */
        if (fx->desc.lod_particles > 0) count = lod_reduce(&fx->lod, fx->view, count, fx->desc.lod_particles);
        sbfx_sort_back_to_front(fx, count);
        fp.particles_far = particles_far(fx, count, fp.near);
        pass_depth(fx, frame, &fp);
        if (corners_used(fx)) pass_corners(fx);
        pass_particles(fx, frame, &fp, count);
        pass_composite(fx, frame, &fp);
    }
    if (fx->plan.owns_scene) {
        fx->gl.post.particles_drawn = count > 0;
        bool composited_to_out = sbfx_post_composite_target(fx, frame) == frame->out_framebuffer;
        GLuint source = count == 0 ? frame->scene_color_texture
                        : composited_to_out ? 0 : sbfx_post_composite_texture(fx);
        sbfx_post_run(fx, frame, depth, source);
    }
    return SBFX_OK;
}

/* The frame: particle passes when particles live, then the post chain when the scene has one,
 * all inside one save and restore of the host's state (only the units this frame binds).
 * Where the post chain reads from: the composite's image, nothing (the composite already
 * wrote the host's framebuffer), or on a frame without particles the bare scene. */
static sbfx_gl_units frame_units(const sbfx *fx, int count, bool scene_color)
{
    sbfx_gl_units units = count > 0 ? pass_units(fx, scene_color) : (sbfx_gl_units){0};
    if (fx->plan.owns_scene) units.tex_2d |= sbfx_post_units(fx).tex_2d;
    return units;
}

sbfx_result sbfx_render_frame(sbfx *fx, const sbfx_frame *frame, const sbfx_depth_model *depth, int count)
{
    sbfx_gl_units units = frame_units(fx, count, frame->scene_color_texture != 0);
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_PASS | fx->context_parts, &units);
    if (saved.polygon_mode_unfixed && !fx->warned_polygon_mode) {
        fx->warned_polygon_mode = true;
        sbfx_log(fx, SBFX_LOG_WARN, "the host's polygon mode is not GL_FILL and glPolygonMode is not in the "
                 "process (link libOpenGL or libGL): the effects are drawn in the host's mode");
    }
    sbfx_result r = draw_frame(fx, frame, depth, count);
    fx->counters.gl_state_queries += sbfx_gl_state_restore(&saved);
    if (r != SBFX_OK) return r;
    return sbfx_gl_check(fx, "rendering the frame's passes") ? SBFX_OK : SBFX_ERR_GL;
}

int sbfx_host_state_roundtrip(sbfx *fx, bool particles)
{
    if (!particles && !fx->plan.owns_scene) return 0; /* such a frame runs no pass */
    sbfx_gl_units units = frame_units(fx, particles ? 1 : 0, true);
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_PASS | fx->context_parts, &units);
    return sbfx_gl_state_restore(&saved);
}

int sbfx_frame_lights(const sbfx *fx, const float view[16], sbfx_view_light *out, int capacity)
{
    frame_lights lights;
    gather_lights(fx, view, &lights);
    int n = lights.count < capacity ? lights.count : capacity;
    for (int i = 0; i < n; i++) {
        memcpy(out[i].vector, lights.vector[i], sizeof(out[i].vector));
        memcpy(out[i].color, lights.color[i], sizeof(out[i].color));
    }
    return n;
}

void sbfx_frame_ambient(const sbfx *fx, float ambient[3]) { memcpy(ambient, fx->ambient, 3 * sizeof(float)); }

/* The detail animation loops every 4 s: its phase on the clock, in [0, 1) loops (the volume's
 * time axis wraps with REPEAT, so the jump from 1 back to 0 is seamless). */
double sbfx_detail_time(const sbfx *fx) { return sbfx_clock_phase(fx, SBFX_DETAIL_LOOP_SECONDS); }
