/* Post effects after the particle composite (seed fig. 9, RTR 12.4-12.5): depth of field,
 * then motion blur (the seed's history blend, or McGuire's velocity reconstruction). Each
 * exists in the plan — programs, targets, passes — only when the scene asks for it. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "module.h"

bool sbfx_post_owns_scene(const sbfx *fx) { return fx->plan.owns_scene; }

static bool has_steps(const sbfx *fx) { return fx->post.dof || fx->post.blur != SBFX_BLUR_NONE; }

/* ---- programs (load) ---- */
static GLuint build(sbfx *fx, const char *frag, const char *defines, bool wanted)
{
    return wanted ? sbfx_program_build(fx, "fullscreen.vert", frag, defines) : 0;
}

sbfx_result sbfx_post_programs_create(sbfx *fx)
{
    sbfx_post_gl *p = &fx->gl.post;
    if (!fx->plan.owns_scene) return SBFX_OK;
    bool float_ok = sbfx_half_float_renderable();
    p->color_format = float_ok ? &sbfx_rt_rgba16f : &sbfx_rt_rgba8;
    p->velocity_format = p->color_format;
    p->encode_velocity = !float_ok;
    if (fx->plan.distortion && !float_ok)
        sbfx_log(fx, SBFX_LOG_WARN, "heat shimmer needs a float particle target (GL_EXT_color_buffer_half_float "
                 "or GL_EXT_color_buffer_float): shimmer is off");
    char defines[128];
    snprintf(defines, sizeof(defines), "%s%s", p->encode_velocity ? "#define ENCODE_UNORM\n" : "",
             fx->plan.particle_velocity && float_ok ? "#define HAS_PARTICLE_VELOCITY\n" : "");
    bool velocity = fx->post.blur == SBFX_BLUR_VELOCITY, history = fx->post.blur == SBFX_BLUR_HISTORY;
    bool dof = fx->post.dof;
    p->copy_program = build(fx, "copy.frag", NULL, true);
    p->history_program = build(fx, "history_blur.frag", NULL, history);
    p->velocity_program = build(fx, "velocity.frag", defines, velocity);
    p->tile_program = build(fx, "tile_max.frag", defines, velocity);
    p->neighbor_program = build(fx, "neighbor_max.frag", defines, velocity);
    p->blur_program = build(fx, "motion_blur.frag", defines, velocity);
    p->dof_setup_program = build(fx, "dof_setup.frag", NULL, dof);
    p->dof_blur_program = build(fx, "dof_blur.frag", NULL, dof);
    p->dof_composite_program = build(fx, "dof_composite.frag", NULL, dof);
    GLuint need[] = {p->copy_program, history ? p->history_program : 1, velocity ? p->blur_program : 1,
                     velocity ? p->velocity_program : 1, velocity ? p->tile_program : 1,
                     velocity ? p->neighbor_program : 1, dof ? p->dof_composite_program : 1,
                     dof ? p->dof_setup_program : 1, dof ? p->dof_blur_program : 1};
    for (size_t i = 0; i < ARRAY_SIZE(need); i++)
        if (!need[i]) return SBFX_ERR_SHADER;
    return SBFX_OK;
}

static void destroy_targets(sbfx *fx)
{
    sbfx_post_gl *p = &fx->gl.post;
    sbfx_rt *all[] = {&p->frame[0], &p->frame[1], &p->history[0], &p->history[1], &p->velocity,
                      &p->tiles, &p->neighbors, &p->dof[0], &p->dof[1]};
    for (size_t i = 0; i < ARRAY_SIZE(all); i++) sbfx_rt_destroy(fx, all[i]);
    p->width = p->height = 0;
    p->history_valid = false;
}

void sbfx_post_destroy(sbfx *fx)
{
    sbfx_post_gl *p = &fx->gl.post;
    destroy_targets(fx);
    GLuint programs[] = {p->velocity_program, p->tile_program, p->neighbor_program, p->blur_program,
                         p->history_program, p->copy_program, p->dof_setup_program, p->dof_blur_program,
                         p->dof_composite_program};
    for (size_t i = 0; i < ARRAY_SIZE(programs); i++)
        if (programs[i]) glDeleteProgram(programs[i]);
}

/* ---- targets (first render, size changes) ---- */
static bool make(sbfx *fx, sbfx_rt *rt, int w, int h, const sbfx_rt_format *a, const sbfx_rt_format *b, GLenum filter)
{
    const sbfx_rt_format *colors[SBFX_RT_MAX] = {a, b, NULL};
    return sbfx_rt_create(fx, rt, w, h, colors, NULL, filter);
}

sbfx_result sbfx_post_targets_ensure(sbfx *fx, int w, int h)
{
    sbfx_post_gl *p = &fx->gl.post;
    if (!fx->plan.owns_scene || (p->width == w && p->height == h)) return SBFX_OK;
    destroy_targets(fx);
    const sbfx_rt_format *c = p->color_format, *v = p->velocity_format;
    bool ok = true;
    int frames = (fx->post.dof ? 1 : 0) + (fx->post.blur != SBFX_BLUR_NONE ? 1 : 0);
    for (int i = 0; i < frames; i++) ok = ok && make(fx, &p->frame[i], w, h, c, NULL, GL_NEAREST);
    if (fx->post.blur == SBFX_BLUR_HISTORY)
        for (int i = 0; i < 2; i++) ok = ok && make(fx, &p->history[i], w, h, c, NULL, GL_NEAREST);
    if (fx->post.blur == SBFX_BLUR_VELOCITY) {
        int t = fx->post.tile, tw = (w + t - 1) / t, th = (h + t - 1) / t;
        ok = ok && make(fx, &p->velocity, w, h, v, NULL, GL_NEAREST) && make(fx, &p->tiles, tw, th, v, NULL, GL_NEAREST) &&
             make(fx, &p->neighbors, tw, th, v, NULL, GL_NEAREST);
    }
    if (fx->post.dof) {
        int s = fx->post.dof_scale, dw = (w + s - 1) / s, dh = (h + s - 1) / s;
        for (int i = 0; i < 2; i++) ok = ok && make(fx, &p->dof[i], dw, dh, c, c, GL_NEAREST);
    }
    if (!ok) {
        destroy_targets(fx);
        return sbfx_fail(fx, SBFX_ERR_GL, "cannot create the %dx%d post-effect targets", w, h);
    }
    p->width = w, p->height = h;
    return sbfx_gl_check(fx, "creating the post-effect targets") ? SBFX_OK : SBFX_ERR_GL;
}

/* ---- passes ---- */
typedef struct post_frame {
    const sbfx_frame *f;
    float depth_params[2], far;
} post_frame;

static void bind_unit(GLuint program, const char *name, int unit, GLuint texture)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, texture);
    glUniform1i(glGetUniformLocation(program, name), unit);
}

/* Starts a full-screen pass of `program` into `fbo` of w x h; finish() draws it. */
static void begin(GLuint program, GLuint fbo, int w, int h)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glUseProgram(program);
}

static void finish(sbfx *fx)
{
    glBindVertexArray(fx->gl.fullscreen_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    fx->counters.passes++;
    fx->counters.draw_calls++;
}

static void pass_copy(sbfx *fx, GLuint source, GLuint fbo, int w, int h)
{
    GLuint prog = fx->gl.post.copy_program;
    begin(prog, fbo, w, h);
    bind_unit(prog, "u_source", 0, source);
    finish(fx);
}

static void set_depth_uniforms(GLuint prog, const post_frame *pf, const char *far_name)
{
    glUniform2fv(glGetUniformLocation(prog, "u_depth_params"), 1, pf->depth_params);
    glUniform1f(glGetUniformLocation(prog, far_name), pf->far);
}

/* Depth of field: split by CoC at the blur resolution, blur both fields separably (two
 * passes), composite over the sharp image. */
static void pass_dof(sbfx *fx, const post_frame *pf, GLuint source, GLuint fbo)
{
    sbfx_post_gl *p = &fx->gl.post;
    const sbfx_post_params *post = &fx->post;
    const sbfx_frame *f = pf->f;
    GLuint prog = p->dof_setup_program;
    begin(prog, p->dof[0].framebuffer, p->dof[0].width, p->dof[0].height);
    bind_unit(prog, "u_color", 0, source);
    bind_unit(prog, "u_scene_depth", 1, f->scene_depth_texture);
    glUniform1i(glGetUniformLocation(prog, "u_scale"), post->dof_scale);
    glUniform2i(glGetUniformLocation(prog, "u_size"), f->width, f->height);
    set_depth_uniforms(prog, pf, "u_far_plane");
    glUniform2fv(glGetUniformLocation(prog, "u_near"), 1, post->dof_near);
    glUniform2fv(glGetUniformLocation(prog, "u_far"), 1, post->dof_far);
    bind_unit(prog, "u_particle_motion", 2, fx->gl.particles.texture[2]);
    glUniform1i(glGetUniformLocation(prog, "u_particles_drawn"), p->particles_drawn && fx->gl.particles.texture[2]);
    glUniform1f(glGetUniformLocation(prog, "u_divisor"), (float)fx->desc.target_divisor);
    glUniform2i(glGetUniformLocation(prog, "u_particle_size"), fx->gl.low_width, fx->gl.low_height);
    finish(fx);
    prog = p->dof_blur_program;
    for (int dir = 0; dir < 2; dir++) {
        const sbfx_rt *in = &p->dof[dir], *out = &p->dof[1 - dir];
        begin(prog, out->framebuffer, out->width, out->height);
        bind_unit(prog, "u_far_field", 0, in->texture[0]);
        bind_unit(prog, "u_near_field", 1, in->texture[1]);
        glUniform2i(glGetUniformLocation(prog, "u_direction"), dir == 0, dir == 1);
        glUniform2i(glGetUniformLocation(prog, "u_low_size"), in->width, in->height);
        glUniform1f(glGetUniformLocation(prog, "u_max_radius"), post->dof_max_radius / post->dof_scale);
        finish(fx);
    }
    prog = p->dof_composite_program;
    begin(prog, fbo, f->width, f->height);
    bind_unit(prog, "u_color", 0, source);
    bind_unit(prog, "u_far_field", 1, p->dof[0].texture[0]);
    bind_unit(prog, "u_near_field", 2, p->dof[0].texture[1]);
    bind_unit(prog, "u_scene_depth", 3, f->scene_depth_texture);
    set_depth_uniforms(prog, pf, "u_far_plane");
    glUniform2fv(glGetUniformLocation(prog, "u_far"), 1, post->dof_far);
    glUniform1f(glGetUniformLocation(prog, "u_scale"), (float)post->dof_scale);
    glUniform2i(glGetUniformLocation(prog, "u_low_size"), p->dof[0].width, p->dof[0].height);
    finish(fx);
}

/* The seed's motion blur: history = mix(new, history, e^(-dt/persistence)), then shown. */
static void pass_history(sbfx *fx, GLuint source, GLuint fbo, int w, int h, double dt)
{
    sbfx_post_gl *p = &fx->gl.post;
    GLuint prog = p->history_program;
    const sbfx_rt *previous = &p->history[1 - p->history_next], *next = &p->history[p->history_next];
    float keep = p->history_valid ? (float)exp(-dt / fx->post.persistence) : 0.0f;
    begin(prog, next->framebuffer, w, h);
    bind_unit(prog, "u_current", 0, source);
    bind_unit(prog, "u_history", 1, previous->texture[0]);
    glUniform1f(glGetUniformLocation(prog, "u_keep"), keep);
    finish(fx);
    pass_copy(fx, next->texture[0], fbo, w, h);
    p->history_valid = true;
    p->history_next = 1 - p->history_next;
}

static void multiply4(const double a[16], const double b[16], double out[16])
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
            out[c * 4 + r] = s;
        }
}

/* General 4x4 inverse by cofactors (column-major); false when singular. */
static bool invert4(const double m[16], double out[16])
{
    double inv[16];
    inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] + m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] - m[8] * m[7] * m[14] - m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] + m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] - m[8] * m[6] * m[13] - m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] - m[9] * m[3] * m[14] - m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] + m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] - m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] + m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] + m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] - m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] + m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] - m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] - m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] + m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] - m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] + m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    double det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
    if (!(fabs(det) > 1e-300)) return false;
    for (int i = 0; i < 16; i++) out[i] = inv[i] / det;
    return true;
}

static void view_projection(const sbfx_frame *f, double out[16])
{
    double v[16], p[16];
    for (int i = 0; i < 16; i++) v[i] = f->view[i], p[i] = f->projection[i];
    multiply4(p, v, out);
}

/* McGuire's reconstruction: velocity, tile max, neighbour max, gather. */
static void pass_velocity_blur(sbfx *fx, const post_frame *pf, GLuint source, GLuint fbo)
{
    sbfx_post_gl *p = &fx->gl.post;
    const sbfx_frame *f = pf->f;
    const sbfx_post_params *post = &fx->post;
    double now[16], inverse[16], reproject[16];
    view_projection(f, now);
    if (!p->have_previous || !invert4(now, inverse)) memcpy(reproject, (double[16]){1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, sizeof(reproject));
    else multiply4(p->previous_view_projection, inverse, reproject);
    float reproject_f[16];
    for (int i = 0; i < 16; i++) reproject_f[i] = (float)reproject[i];
    GLuint prog = p->velocity_program;
    begin(prog, p->velocity.framebuffer, f->width, f->height);
    bind_unit(prog, "u_scene_depth", 0, f->scene_depth_texture);
    bind_unit(prog, "u_particle_velocity", 1, fx->gl.particles.texture[2]);
    glUniform1i(glGetUniformLocation(prog, "u_particles_drawn"), p->particles_drawn && fx->gl.particles.texture[2]);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_reproject"), 1, GL_FALSE, reproject_f);
    glUniform2f(glGetUniformLocation(prog, "u_size"), (float)f->width, (float)f->height);
    glUniform1f(glGetUniformLocation(prog, "u_shutter"), post->shutter);
    glUniform1f(glGetUniformLocation(prog, "u_max_radius"), (float)post->tile);
    glUniform1f(glGetUniformLocation(prog, "u_divisor"), (float)fx->desc.target_divisor);
    glUniform2i(glGetUniformLocation(prog, "u_low_size"), fx->gl.low_width, fx->gl.low_height);
    finish(fx);
    prog = p->tile_program;
    begin(prog, p->tiles.framebuffer, p->tiles.width, p->tiles.height);
    bind_unit(prog, "u_velocity", 0, p->velocity.texture[0]);
    glUniform1i(glGetUniformLocation(prog, "u_tile"), post->tile);
    glUniform2i(glGetUniformLocation(prog, "u_size"), f->width, f->height);
    glUniform1f(glGetUniformLocation(prog, "u_max_radius"), (float)post->tile);
    finish(fx);
    prog = p->neighbor_program;
    begin(prog, p->neighbors.framebuffer, p->neighbors.width, p->neighbors.height);
    bind_unit(prog, "u_tiles", 0, p->tiles.texture[0]);
    glUniform2i(glGetUniformLocation(prog, "u_tiles_size"), p->tiles.width, p->tiles.height);
    glUniform1f(glGetUniformLocation(prog, "u_max_radius"), (float)post->tile);
    finish(fx);
    prog = p->blur_program;
    begin(prog, fbo, f->width, f->height);
    bind_unit(prog, "u_color", 0, source);
    bind_unit(prog, "u_velocity", 1, p->velocity.texture[0]);
    bind_unit(prog, "u_neighbor_max", 2, p->neighbors.texture[0]);
    bind_unit(prog, "u_scene_depth", 3, f->scene_depth_texture);
    glUniform2i(glGetUniformLocation(prog, "u_size"), f->width, f->height);
    glUniform1i(glGetUniformLocation(prog, "u_tile"), post->tile);
    glUniform1i(glGetUniformLocation(prog, "u_samples"), post->samples);
    glUniform1f(glGetUniformLocation(prog, "u_max_radius"), (float)post->tile);
    set_depth_uniforms(prog, pf, "u_far");
    finish(fx);
}

/* Runs the post chain on `source` (the composite's image, or the bare scene on an idle frame)
 * and leaves the final image in the host's framebuffer. */
sbfx_result sbfx_post_run(sbfx *fx, const sbfx_frame *f, GLuint source)
{
    sbfx_post_gl *p = &fx->gl.post;
    const float *proj = f->projection;
    post_frame pf = {f, {proj[10], proj[14]}, proj[14] / (proj[10] + 1.0f)};
    double dt = p->have_previous ? fx->time - p->last_time : 0.0;
    glDisable(GL_BLEND);
    if (!has_steps(fx)) {
        if (source != 0) pass_copy(fx, source, f->out_framebuffer, f->width, f->height);
    } else {
        GLuint input = source;
        if (fx->post.dof) {
            bool last = fx->post.blur == SBFX_BLUR_NONE;
            GLuint dest = last ? f->out_framebuffer : p->frame[1].framebuffer;
            pass_dof(fx, &pf, input, dest);
            input = p->frame[1].texture[0];
        }
        if (fx->post.blur == SBFX_BLUR_HISTORY) pass_history(fx, input, f->out_framebuffer, f->width, f->height, dt);
        if (fx->post.blur == SBFX_BLUR_VELOCITY) pass_velocity_blur(fx, &pf, input, f->out_framebuffer);
    }
    view_projection(f, p->previous_view_projection);
    p->last_time = fx->time;
    p->have_previous = true;
    return SBFX_OK;
}

/* Where the particle composite writes when sbfx owns the scene: the first post frame, or the
 * host's framebuffer when no step follows. */
GLuint sbfx_post_composite_target(const sbfx *fx, const sbfx_frame *f)
{
    return has_steps(fx) ? fx->gl.post.frame[0].framebuffer : f->out_framebuffer;
}

GLuint sbfx_post_composite_texture(const sbfx *fx) { return fx->gl.post.frame[0].texture[0]; }
