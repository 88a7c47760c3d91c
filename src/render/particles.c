/* Pass 2 of a frame (frame.c): the sorted particles into the low-resolution target, back to
 * front ("over"), or front to back ("under") where early termination stops what is hidden
 * (terminate.c; docs/gpus.md "Front to back, and early termination"), premultiplied light and
 * transmittance; consecutive particles of one medium share a draw call. Per particle its
 * instance data (centre, radius, detail window, intensity; the previous centre, the light per
 * particle, the fire's light where the plan has them), per medium its uniforms and tables. */
#include <math.h>
#include <string.h>
#include "render/render.h"

#define SBFX_FOUR_PI_F 12.566370614f

/* Lit media (LIGHTING_LIT): their own texture array, wrap as scale and bias (seed eq. 5.2.3). */
static void set_lit_uniforms(sbfx *fx, const sbfx_program *p, sbfx_medium m)
{
    const sbfx_medium_params *mp = &fx->scene->media[m];
    sbfx_bind_texture(UNIT_SMOKE, GL_TEXTURE_2D_ARRAY, fx->gl->smoke_texture[m], 0);
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
    const sbfx_medium_params *mp = &fx->scene->media[m];
    glUniform1f(p->tau, mp->tau);
    glUniform1f(p->heat_strength, mp->heat_strength);
    glUniform1f(p->soft_scale, 0.0f);
    glUniform1i(p->detail, UNIT_DETAIL);
    glUniform1f(p->detail_window, mp->detail_window);
    glUniform1f(p->detail_strength, mp->detail_strength);
    glUniform1f(p->time, (float)sbfx_detail_time(fx));
    /* pre-exposed (docs/look-fire.md): the exposure scales the light where it is made, so the
     * particle target holds what the display gets and fire stays inside the radiance ceiling */
    float exposure = fx->scene->desc.exposure, scatter = mp->albedo * exposure;
    glUniform3f(p->albedo_color, scatter * mp->color[0], scatter * mp->color[1], scatter * mp->color[2]);
    glUniform1i(p->light_count, lights->count);
    /* count 0 is a no-op in ES 3.0 but INVALID_VALUE in WebGL 2 (an empty array): not called */
    if (lights->count > 0) glUniform4fv(p->light_vector, lights->count, &lights->vector[0][0]);
    /* the phase model's 4 pi (a light of colour E scattered isotropically gives back E) folded in
     * here, not per fragment; lit media take the colours as they are */
    float color[SBFX_SHADER_LIGHTS][3];
    for (int i = 0; i < lights->count; i++)
        for (int k = 0; k < 3; k++) color[i][k] = lights->color[i][k] * (mp->lit ? 1.0f : SBFX_FOUR_PI_F);
    if (lights->count > 0) glUniform3fv(p->light_color, lights->count, &color[0][0]);
    glUniform3fv(p->ambient, 1, fx->scene->ambient);
    glUniform4f(p->temperature, mp->t0, mp->t1, mp->cooling, mp->soot);
    glUniform1f(p->emission_scale, mp->emission_scale * (1.0f - mp->albedo) * exposure);
    sbfx_tables_bind(fx, p, m);
    if (fx->gl->smoke_texture[m]) set_lit_uniforms(fx, p, m);
}

static void set_frame_uniforms(sbfx *fx, const sbfx_program *p, const frame_params *fp, int width, int height)
{
    const sbfx_gl *gl = fx->gl;
    glUniform1f(p->near, fp->near);
    glUniform4fv(p->projection, 1, fp->projection);
    /* particle.frag's ray: ((2 x / size - 1) + P[8]) / P[0], folded in double (and y alike) */
    const float *pr = fp->projection;
    glUniform4f(p->ray_map, (float)(2.0 / ((double)width * pr[0])), (float)(2.0 / ((double)height * pr[1])),
                (float)((pr[2] - 1.0) / pr[0]), (float)((pr[3] - 1.0) / pr[1]));
    glUniform2f(p->pixel, 2.0f / width, 2.0f / height);
    /* rectangles for the frame as before tiles, and for the bench's floor, whose every fragment
     * writes: its picture is its rectangle */
    glUniform1i(p->octagon, !fx->render->tiles.full_screen && fx->scene->desc.opacity != SBFX_OPACITY_FLOOR);
    glUniform1i(p->depth, UNIT_DEPTH);
    glUniform2f(p->full_size, (float)gl->out_width, (float)gl->out_height);
}

/* Writes the sorted particles into the instance buffer; returns nothing, cannot fail. */
/* In-scattered light of the phase model at the particle's centre, in double: what the
 * fragment shader's in_scattered() computes per pixel, once per particle instead. */
static void particle_light(const sbfx *fx, const frame_lights *lights, const sbfx_view_particle *v, float out[3])
{
    const sbfx_medium_params *m = &fx->scene->media[v->medium];
    double c[3] = {v->center[0], v->center[1], v->center[2]};
    double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    double to_eye[3] = {-c[0] / len, -c[1] / len, -c[2] / len};
    double sum[3] = {fx->scene->ambient[0], fx->scene->ambient[1], fx->scene->ambient[2]};
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
    const sbfx_medium_params *m = &fx->scene->media[v->medium];
    if (v->medium == SBFX_FIRE || !(m->albedo > 0.0f) || fx->sim->frame_fire_count == 0) return;
    const double c[3] = {v->center[0], v->center[1], v->center[2]};
    sbfx_fire_scatter s;
    sbfx_fire_scatter_at(fx->sim->frame_fire, fx->sim->frame_fire_count, fx->scene->desc.exposure, c, m->lit ? 0.0 : m->phase_g, &s);
    double values[8];
    sbfx_fire_scatter_instance(&s, c, v->radius, values);
    for (int k = 0; k < 8; k++) out[k] = (float)values[k];
    if (s.rgb[0] > 0.0 || s.rgb[1] > 0.0 || s.rgb[2] > 0.0) fx->counters.fire_lit_particles++;
}

static void upload_instances(sbfx *fx, const frame_lights *lights, int count)
{
    const int stride = fx->scene->instance_floats;
    for (int i = 0; i < count; i++) {
        const sbfx_view_particle *v = sbfx_drawn_particle(fx, count, i);
        float *dst = &fx->sim->instances[stride * i];
        memcpy(dst, v->center, 3 * sizeof(float));
        dst[3] = v->radius;
        memcpy(dst + 4, v->detail, 3 * sizeof(float));
        dst[7] = v->intensity;
        if (fx->scene->instance_previous) {
            memcpy(dst + fx->scene->instance_previous, v->previous_center, 3 * sizeof(float));
            dst[fx->scene->instance_previous + 3] = 0.0f;
        }
        if (fx->scene->instance_light) {
            particle_light(fx, lights, v, dst + fx->scene->instance_light);
            dst[fx->scene->instance_light + 3] = 0.0f;
        }
        if (fx->scene->instance_fire) particle_fire(fx, v, dst + fx->scene->instance_fire);
    }
    glBindBuffer(GL_ARRAY_BUFFER, fx->gl->instance_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)((size_t)count * stride * sizeof(float)), fx->sim->instances);
}

static void draw_run(sbfx *fx, int first, int count)
{
    const GLsizei stride = (GLsizei)(fx->scene->instance_floats * sizeof(float));
    const char *base = (const char *)(size_t)((size_t)first * (size_t)stride);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, stride, base);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, stride, base + 4 * sizeof(float));
    if (fx->scene->instance_previous)
        glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, stride, base + fx->scene->instance_previous * sizeof(float));
    if (fx->scene->instance_light)
        glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, stride, base + fx->scene->instance_light * sizeof(float));
    if (fx->scene->instance_fire) {
        glVertexAttribPointer(4, 4, GL_FLOAT, GL_FALSE, stride, base + fx->scene->instance_fire * sizeof(float));
        glVertexAttribPointer(5, 4, GL_FLOAT, GL_FALSE, stride, base + (fx->scene->instance_fire + 4) * sizeof(float));
    }
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 8, count); /* an octagon a particle (particle.vert) */
    fx->counters.draw_calls++;
}

/* The particles' draws into the bound target (width x height, its opaque depth on UNIT_DEPTH,
 * depth_texture), in the frame's order (sbfx_drawn_particle); consecutive particles of one
 * medium share a draw call, and a run ends at each of early termination's checkpoints (stops:
 * none, or terminate.c's), where the mark follows it. ES 3.0 has no base instance, so each run re-points the instance
 * attributes at its first particle. */
void sbfx_draw_particles(sbfx *fx, const sbfx_frame *f, const frame_params *fp, int count, int width, int height,
                         const sbfx_stops *stops, GLuint depth_texture)
{
    sbfx_gl *gl = fx->gl;
    frame_lights lights;
    sbfx_gather_lights(fx, f->view, &lights);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    /* back to front, "over": rgb = src + dst (1 - a); transmittance a = dst (1 - a). Nearest first,
     * "under": rgb = dst + dst.a src, the same transmittance: each attachment's alpha holds the
     * transmittance in front of it (heat writes alpha 0), so its light, offset or velocity is
     * weighed by what the nearer particles let through, the same sum in the other order (ES 3.0
     * core blend factors). In RGBA16F "under" multiplies every stored transmittance's rounding
     * into the light behind it (docs/gpus.md): the order only early termination needs. */
    if (fx->render->front_to_back) glBlendFuncSeparate(GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
    else glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
    if (gl->detail_texture) sbfx_bind_texture(UNIT_DETAIL, GL_TEXTURE_3D, gl->detail_texture, 0);
    glBindVertexArray(gl->particle_vao);
    glBindBuffer(GL_ARRAY_BUFFER, gl->instance_buffer); /* draw_run points the attributes into it */
    int stop = 0, stop_count = stops ? stops->count : 0;
    for (int first = 0; first < count;) {
        sbfx_medium m = sbfx_drawn_particle(fx, count, first)->medium;
        int last = stop < stop_count ? stops->at[stop] : count, end = first + 1;
        while (end < last && sbfx_drawn_particle(fx, count, end)->medium == m) end++;
        const sbfx_program *p = &gl->particle[m];
        glUseProgram(p->id);
        set_frame_uniforms(fx, p, fp, width, height);
        set_medium_uniforms(fx, p, m, &lights);
        draw_run(fx, first, end - first);
        first = end;
        if (stop < stop_count && end == stops->at[stop]) sbfx_terminate_mark(fx, stops->epsilon[stop++], depth_texture);
    }
    fx->counters.passes++;
}

/* Pass 2: the particles into the low-resolution target, their instances written first. */
void sbfx_pass_particles(sbfx *fx, const sbfx_frame *f, const frame_params *fp, int count)
{
    sbfx_gl *gl = fx->gl;
    frame_lights lights;
    sbfx_gather_lights(fx, f->view, &lights);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gl->particles.framebuffer);
    glViewport(0, 0, gl->low_width, gl->low_height);
    /* No light added, everything transmitted, no offset, no motion: every attachment. */
    const GLfloat clear[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    for (GLint i = 0; i < SBFX_RT_MAX; i++)
        if (gl->particles.texture[i]) glClearBufferfv(GL_COLOR, i, clear);
    sbfx_bind_texture(UNIT_DEPTH, GL_TEXTURE_2D, gl->low_depth.depth, 0);
    fx->counters.fire_lit_particles = 0;
    fx->sim->frame_fire_count = 0;
    fx->render->stops_marked = 0;
    fx->render->front_to_back = sbfx_terminate_used(fx); /* the order of the instances and both draws */
    if (fx->scene->plan.fire_light) sbfx_fire_lights_of_frame(fx, count);
    upload_instances(fx, &lights, count);
    sbfx_stops stops;
    sbfx_terminate_plan(fx, &lights, fp, count, &stops);
    if (stops.count > 0) sbfx_terminate_begin(fx);
    sbfx_draw_particles(fx, f, fp, count, gl->low_width, gl->low_height, &stops, gl->low_depth.depth);
    if (stops.count > 0) sbfx_terminate_end();
}
