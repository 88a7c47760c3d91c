/* One frame's GPU work, as the seed's figure 9 draws it, between one save and one restore of the
 * host's GL state (gl/gl_state.c): the particle passes when particles live — opaque depth to the
 * particle target's resolution (passes.c), the particles front to back into it (particles.c), the
 * composite over the host's framebuffer (passes.c) — then the post chain when the scene has one
 * (post.c). The frame's particles come from the sim room, sorted (and merged by a lodN level)
 * here; sbfx.c (sbfx_render) brackets it with the frame budget. */
#include <math.h>
#include <string.h>
#include "render/render.h"

/* The farthest view distance any of the first `count` particles reaches: its centre's distance
 * along -z plus its radius, at least `near` (the composite clamps depths to it and divides by
 * it). Nearest-depth upsampling needs no care beyond it (composite.frag). */
static float particles_far(const sbfx *fx, int count, float near)
{
    float far = near;
    for (int i = 0; i < count; i++) {
        const sbfx_view_particle *v = &fx->sim->view[i];
        float reach = -v->center[2] + v->radius;
        if (reach > far) far = reach;
    }
    return far;
}

static frame_params frame_params_from(const sbfx_depth_model *m)
{
    frame_params fp = {.projection = {m->projection[0], m->projection[1], m->projection[2], m->projection[3]},
                       .near = (float)m->near};
    sbfx_depth_model_uniform(m, fp.depth_model);
    sbfx_near_model_uniform(m, fp.near_model);
    return fp;
}

/* Which units the particle passes bind which targets on (depth, particle, composite). */
static sbfx_gl_units pass_units(const sbfx *fx, bool scene_color)
{
    const sbfx_gl *gl = fx->gl;
    sbfx_gl_units u = {.tex_2d = 1u << 0 | 1u << 1 | 1u << 2};
    /* unit 3: the black body for the particles, the scene colour for the composite */
    if (gl->blackbody_texture || fx->scene->plan.owns_scene || scene_color) u.tex_2d |= 1u << SBFX_UNIT_BLACKBODY;
    if (fx->scene->plan.distortion) u.tex_2d |= 1u << 4; /* the shimmer offsets, when the target holds them */
    /* mixed resolution's refined particles (the targets may be made inside this frame) */
    if (gl->refine_mark_program && fx->scene->desc.upsample == SBFX_UPSAMPLE_MIXED) u.tex_2d |= 1u << SBFX_UNIT_REFINED;
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
        if (fx->scene->desc.lod_particles > 0) count = lod_reduce(&fx->sim->lod, fx->sim->view, count, fx->scene->desc.lod_particles);
        sbfx_sort_back_to_front(fx, count);
        fp.particles_far = particles_far(fx, count, fp.near);
        sbfx_tiles_plan(fx, frame, &fp, count); /* where the particles can change the picture */
        bool tiles = sbfx_tiles_any(fx);
        if (tiles) sbfx_pass_depth(fx, frame, &fp);
        if (tiles && sbfx_corners_used(fx)) sbfx_pass_corners(fx);
        sbfx_pass_particles(fx, frame, &fp, count);
        if (tiles) sbfx_pass_refine(fx, frame, &fp, count);
        if (tiles || fx->scene->plan.owns_scene) sbfx_pass_composite(fx, frame, &fp);
    }
    if (fx->scene->plan.owns_scene) {
        fx->render->post.particles_drawn = count > 0;
        if (count == 0) sbfx_tiles_plan_idle(fx, frame); /* the post chain draws over the rest */
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
    if (fx->scene->plan.owns_scene) units.tex_2d |= sbfx_post_units(fx).tex_2d;
    return units;
}

/* What the frame's block saves: the pass state, desktop OpenGL's own, and where mixed
 * resolution's refinement or early termination may run, the depth range (their masks compare
 * window depths). */
static unsigned frame_parts(const sbfx *fx, int count)
{
    bool mixed = count > 0 && fx->gl->refine_mark_program && fx->scene->desc.upsample == SBFX_UPSAMPLE_MIXED;
    bool stops = count > 0 && fx->scene->early_termination && fx->gl->stop_program;
    return SBFX_GL_SAVE_PASS | fx->gl->context.parts | (mixed || stops ? SBFX_GL_SAVE_DEPTH_RANGE : 0u);
}

sbfx_result sbfx_render_frame(sbfx *fx, const sbfx_frame *frame, const sbfx_depth_model *depth, int count)
{
    sbfx_gl_units units = frame_units(fx, count, frame->scene_color_texture != 0);
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, frame_parts(fx, count), &units);
    if (saved.polygon_mode_unfixed && !fx->render->warned_polygon_mode) {
        fx->render->warned_polygon_mode = true;
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
    if (!particles && !fx->scene->plan.owns_scene) return 0; /* such a frame runs no pass */
    sbfx_gl_units units = frame_units(fx, particles ? 1 : 0, true);
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, frame_parts(fx, particles ? 1 : 0), &units);
    return sbfx_gl_state_restore(&saved);
}

/* A frame's own counters start at 0 (sbfx_render, sbfx_render_view_particles). */
void sbfx_frame_counters_reset(sbfx *fx)
{
    fx->counters.passes = 0;
    fx->counters.draw_calls = 0;
    fx->counters.gl_state_queries = 0;
    fx->counters.fire_lit_particles = 0;
    fx->counters.composite_tiles = 0;
    fx->counters.composite_pixels = 0;
}

bool sbfx_frame_check(sbfx *fx, const sbfx_frame *f, sbfx_depth_model *depth)
{
    if (f->width <= 0 || f->height <= 0 || f->width > 16384 || f->height > 16384) {
        sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "frame size %dx%d is out of range", f->width, f->height);
        return false;
    }
    if (!f->scene_depth_texture) {
        sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "frame has no scene_depth_texture: sbfx needs "
                  "the opaque scene's depth as a texture");
        return false;
    }
    if (fx->scene->plan.owns_scene && !f->scene_color_texture) {
        sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "this scene's post effects (heat shimmer, motion blur or "
                  "depth of field) need frame.scene_color_texture");
        return false;
    }
    return sbfx_depth_model_from(fx, f, depth);
}

sbfx_result sbfx_render_view_particles(sbfx *fx, const sbfx_frame *frame,
                                       const sbfx_view_particle *particles, int count)
{
    if (!fx || !frame || (count > 0 && !particles) || count < 0) return SBFX_ERR_INVALID_ARGUMENT;
    sbfx_frame_counters_reset(fx);
    fx->counters.particles_skipped = 0;
    sbfx_depth_model depth;
    if (!sbfx_frame_check(fx, frame, &depth)) return SBFX_ERR_INVALID_ARGUMENT;
    if (count > fx->sim->pool.capacity)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "%d particles exceed the pool of %d",
                         count, fx->sim->pool.capacity);
    int n = 0;
    for (int i = 0; i < count; i++) {
        if (sbfx_view_particle_valid(&particles[i]) && fx->scene->uses_medium[particles[i].medium]) {
            fx->sim->view[n] = particles[i];
            memcpy(fx->sim->view[n++].previous_center, particles[i].center, sizeof(particles[i].center));
        }
        else
            fx->counters.particles_skipped++;
    }
    if (n == 0 && !fx->scene->plan.owns_scene) return SBFX_OK;
    sbfx_gl_enter(fx);
    sbfx_result r = sbfx_render_frame(fx, frame, &depth, n);
    sbfx_gl_leave(fx, "sbfx_render_view_particles");
    return r;
}
