/* Post effects after the particle composite (seed fig. 9, RTR 12.4-12.5): depth of field,
 * then motion blur (the seed's history blend, or McGuire's velocity reconstruction). Each
 * exists in the plan — programs, targets, passes — only when the scene asks for it. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "render/render.h"

enum post_uniform {
    PU_BLOCK_COLUMNS,
    PU_BLOCK_SIZE,
    PU_CLASS,
    PU_CLASSES,
    PU_COLOR,
    PU_CURRENT,
    PU_DEPTH_MODEL,
    PU_DIRECTION,
    PU_DISTORTION,
    PU_DIVISOR,
    PU_FAR,
    PU_FAR_FIELD,
    PU_FULL_SIZE,
    PU_HISTORY,
    PU_KEEP,
    PU_LOW_SIZE,
    PU_LOW_TEXEL,
    PU_MAX_RADIUS,
    PU_NEAR,
    PU_NDC_DEPTH,
    PU_NEAR_FIELD,
    PU_NEIGHBOR_MAX,
    PU_PARTICLE_MOTION,
    PU_PARTICLE_SIZE,
    PU_PARTICLE_TEXEL,
    PU_PARTICLE_VELOCITY,
    PU_PARTICLES_DRAWN,
    PU_REPROJECT,
    PU_SAMPLES,
    PU_SCALE,
    PU_SCENE_COLOR,
    PU_SCENE_DEPTH,
    PU_SHUTTER,
    PU_SIZE,
    PU_SOURCE,
    PU_TARGET,
    PU_TILE,
    PU_TILE_GRID,
    PU_TILE_SIZE,
    PU_TILE_TARGET,
    PU_TILES,
    PU_TILES_SIZE,
    PU_VELOCITY,
    PU_COUNT
};
_Static_assert(PU_COUNT <= SBFX_POST_UNIFORMS, "SBFX_POST_UNIFORMS is too small for post.c");
static const char *const post_uniform_names[PU_COUNT] = {
    [PU_BLOCK_COLUMNS] = "u_block_columns",
    [PU_BLOCK_SIZE] = "u_block_size",
    [PU_CLASS] = "u_class",
    [PU_CLASSES] = "u_classes",
    [PU_COLOR] = "u_color",
    [PU_CURRENT] = "u_current",
    [PU_DEPTH_MODEL] = "u_depth_model",
    [PU_DIRECTION] = "u_direction",
    [PU_DISTORTION] = "u_distortion",
    [PU_DIVISOR] = "u_divisor",
    [PU_FAR] = "u_far",
    [PU_FAR_FIELD] = "u_far_field",
    [PU_FULL_SIZE] = "u_full_size",
    [PU_HISTORY] = "u_history",
    [PU_KEEP] = "u_keep",
    [PU_LOW_SIZE] = "u_low_size",
    [PU_LOW_TEXEL] = "u_low_texel",
    [PU_MAX_RADIUS] = "u_max_radius",
    [PU_NEAR] = "u_near",
    [PU_NDC_DEPTH] = "u_ndc_depth",
    [PU_NEAR_FIELD] = "u_near_field",
    [PU_NEIGHBOR_MAX] = "u_neighbor_max",
    [PU_PARTICLE_MOTION] = "u_particle_motion",
    [PU_PARTICLE_SIZE] = "u_particle_size",
    [PU_PARTICLE_TEXEL] = "u_particle_texel",
    [PU_PARTICLE_VELOCITY] = "u_particle_velocity",
    [PU_PARTICLES_DRAWN] = "u_particles_drawn",
    [PU_REPROJECT] = "u_reproject",
    [PU_SAMPLES] = "u_samples",
    [PU_SCALE] = "u_scale",
    [PU_SCENE_COLOR] = "u_scene_color",
    [PU_SCENE_DEPTH] = "u_scene_depth",
    [PU_SHUTTER] = "u_shutter",
    [PU_SIZE] = "u_size",
    [PU_SOURCE] = "u_source",
    [PU_TARGET] = "u_target",
    [PU_TILE] = "u_tile",
    [PU_TILE_GRID] = "u_tile_grid",
    [PU_TILE_SIZE] = "u_tile_size",
    [PU_TILE_TARGET] = "u_tile_target",
    [PU_TILES] = "u_tiles",
    [PU_TILES_SIZE] = "u_tiles_size",
    [PU_VELOCITY] = "u_velocity",
};

/* Uniform locations of the post programs, looked up once at load (-1 where a program has no
 * such uniform). Per frame a pass finds its program's row by id: no string lookups. */
static GLuint *post_programs(sbfx_post_gl *p, int i)
{
    GLuint *all[SBFX_POST_PROGRAMS] = {&p->copy_program, &p->history_program, &p->velocity_program, &p->tile_program,
                                      &p->neighbor_program, &p->class_program, &p->blur_program, &p->fast_program,
                                      &p->still_program, &p->dof_setup_program, &p->dof_blur_program,
                                      &p->dof_composite_program, &p->dof_plain_program,
                                      &p->dof_setup_plain_program};
    return all[i];
}

static void locate_post_uniforms(sbfx_post_gl *p)
{
    for (int i = 0; i < SBFX_POST_PROGRAMS; i++)
        for (int u = 0; u < PU_COUNT; u++)
            p->locations[i][u] = *post_programs(p, i) ? glGetUniformLocation(*post_programs(p, i), post_uniform_names[u]) : -1;
}

static GLint post_loc(const sbfx_post_gl *p, GLuint program, int uniform)
{
    for (int i = 0; i < SBFX_POST_PROGRAMS; i++)
        if (*post_programs((sbfx_post_gl *)p, i) == program) return p->locations[i][uniform];
    return -1;
}

static bool has_steps(const sbfx *fx) { return fx->scene->post.dof || fx->scene->post.blur != SBFX_BLUR_NONE; }

/* The depth of field's composite writes the velocity blur's velocities (no pass of their own). */
static bool fused_velocity(const sbfx *fx) { return fx->scene->post.dof && fx->scene->post.blur == SBFX_BLUR_VELOCITY; }

static GLuint velocity_texture(const sbfx *fx)
{
    const sbfx_post_gl *p = &fx->render->post;
    return fused_velocity(fx) ? p->frame[1].texture[1] : p->velocity.texture[0];
}

/* ---- programs (load) ---- */
static GLuint build(sbfx *fx, const char *frag, const char *defines, bool wanted)
{
    return wanted ? sbfx_program_build(fx, "fullscreen.vert", frag, defines) : 0;
}

/* A program of the velocity blur's classified blocks (blur_tiles.vert). */
static GLuint build_tiled(sbfx *fx, const char *frag, const char *defines, bool wanted)
{
    return wanted ? sbfx_program_build(fx, "blur_tiles.vert", frag, defines) : 0;
}

/* Tiles per side of the velocity blur's blocks: blocks of about 32 pixels, few enough
 * instances (2040 at 1920x1080) that the vertex work of drawing them stays small. */
static int block_tiles(const sbfx *fx) { return fx->scene->post.tile >= 32 ? 1 : 32 / fx->scene->post.tile; }

/* The depth of field's blur radius in blur-resolution texels, as dof_blur.frag takes it. */
static int dof_blur_radius(const sbfx *fx)
{
    int r = (int)ceilf(fx->scene->post.dof_max_radius / (float)fx->scene->post.dof_scale);
    return r < 0 ? 0 : r > 16 ? 16 : r;
}

/* The velocity blur's programs (defines: the velocity target's encoding, the particles' motion);
 * no velocity pass with depth of field, whose composite writes the velocities. */
static bool velocity_programs(sbfx *fx, const char *defines)
{
    sbfx_post_gl *p = &fx->render->post;
    const sbfx_post_params *post = &fx->scene->post;
    char tile[160], block[160], samples[160], fast[176];
    /* loops sized to the scene, so the compilers unroll what runs, not the largest size */
    snprintf(tile, sizeof(tile), "%s#define TILE %d\n", defines, post->tile);
    snprintf(block, sizeof(block), "%s#define BLOCK %d\n", defines, block_tiles(fx));
    snprintf(samples, sizeof(samples), "%s#define SAMPLES %d\n", defines, post->samples);
    snprintf(fast, sizeof(fast), "%s#define FAST\n", samples);
    p->velocity_program = build(fx, "velocity.frag", defines, !post->dof);
    p->tile_program = build(fx, "tile_max.frag", tile, true);
    p->neighbor_program = build(fx, "neighbor_max.frag", defines, true);
    p->class_program = build(fx, "tile_class.frag", block, true);
    p->blur_program = build_tiled(fx, "motion_blur.frag", samples, true);
    p->fast_program = build_tiled(fx, "motion_blur.frag", fast, true);
    p->still_program = build_tiled(fx, "copy.frag", NULL, true);
    return (post->dof || p->velocity_program) && p->tile_program && p->neighbor_program && p->class_program &&
           p->blur_program && p->fast_program && p->still_program;
}

/* `frag` for tiles.vert over the particles' tiles (*inside) and, with NO_PARTICLES, the rest. */
static bool build_split(sbfx *fx, const char *frag, const char *defines, GLuint *inside, GLuint *rest)
{
    char plain[256];
    snprintf(plain, sizeof(plain), "#define NO_PARTICLES\n%s", defines);
    *inside = sbfx_program_build(fx, "tiles.vert", frag, defines);
    *rest = sbfx_program_build(fx, "tiles.vert", frag, plain);
    return *inside && *rest;
}

/* The depth of field's programs; with the velocity blur its composite writes the velocities
 * (velocity_defines: the velocity programs' defines, else NULL). */
static bool dof_programs(sbfx *fx, const char *velocity_defines, bool shimmer, bool float_ok)
{
    sbfx_post_gl *p = &fx->render->post;
    char setup[32], blur[48], composite[192];
    snprintf(setup, sizeof(setup), "#define DOF_SCALE %d\n", fx->scene->post.dof_scale);
    snprintf(blur, sizeof(blur), "#define RADIUS %d\n%s", dof_blur_radius(fx), float_ok ? "#define PAIRS\n" : "");
    snprintf(composite, sizeof(composite), "%s%s%s", shimmer ? "#define HAS_SHIMMER\n" : "",
             velocity_defines ? "#define WRITE_VELOCITY\n" : "", velocity_defines ? velocity_defines : "");
    p->dof_blur_program = build(fx, "dof_blur.frag", blur, true);
    return build_split(fx, "dof_setup.frag", setup, &p->dof_setup_program, &p->dof_setup_plain_program) &&
           build_split(fx, "dof_composite.frag", composite, &p->dof_composite_program, &p->dof_plain_program) &&
           p->dof_blur_program;
}

sbfx_result sbfx_post_programs_create(sbfx *fx)
{
    sbfx_post_gl *p = &fx->render->post;
    if (!fx->scene->plan.owns_scene) return SBFX_OK;
    bool float_ok = sbfx_half_float_renderable();
    p->color_format = float_ok ? &sbfx_rt_rgba16f : &sbfx_rt_rgba8;
    p->velocity_format = p->color_format;
    p->encode_velocity = !float_ok;
    if (fx->scene->plan.distortion && !float_ok)
        sbfx_log(fx, SBFX_LOG_WARN, "heat shimmer needs a float particle target (GL_EXT_color_buffer_half_float "
                 "or GL_EXT_color_buffer_float): shimmer is off");
    char defines[128];
    snprintf(defines, sizeof(defines), "%s%s", p->encode_velocity ? "#define ENCODE_UNORM\n" : "",
             fx->scene->plan.particle_velocity && float_ok ? "#define HAS_PARTICLE_VELOCITY\n" : "");
    bool velocity = fx->scene->post.blur == SBFX_BLUR_VELOCITY, history = fx->scene->post.blur == SBFX_BLUR_HISTORY;
    p->copy_program = build(fx, "copy.frag", NULL, true);
    p->history_program = build(fx, "history_blur.frag", NULL, history);
    bool ok = p->copy_program && (!history || p->history_program);
    ok = ok && (!velocity || velocity_programs(fx, defines));
    ok = ok && (!fx->scene->post.dof ||
                dof_programs(fx, velocity ? defines : NULL, fx->scene->plan.distortion && float_ok, float_ok));
    if (!ok) return SBFX_ERR_SHADER;
    locate_post_uniforms(p);
    return SBFX_OK;
}

static void destroy_targets(sbfx *fx)
{
    sbfx_post_gl *p = &fx->render->post;
    sbfx_rt *all[] = {&p->frame[0], &p->frame[1], &p->history[0], &p->history[1], &p->velocity,
                      &p->tile_rows, &p->tiles, &p->neighbors, &p->classes, &p->dof[0], &p->dof[1]};
    for (size_t i = 0; i < ARRAY_SIZE(all); i++) sbfx_rt_destroy(fx, all[i]);
    p->width = p->height = 0;
    p->history_valid = false;
}

void sbfx_post_destroy(sbfx *fx)
{
    sbfx_post_gl *p = &fx->render->post;
    destroy_targets(fx);
    GLuint programs[] = {p->velocity_program, p->tile_program, p->neighbor_program, p->class_program,
                         p->blur_program, p->fast_program, p->still_program, p->history_program, p->copy_program, p->dof_setup_program, p->dof_blur_program,
                         p->dof_composite_program, p->dof_plain_program, p->dof_setup_plain_program};
    for (size_t i = 0; i < ARRAY_SIZE(programs); i++) sbfx_program_delete(fx, programs[i]);
}

/* ---- targets (first render, size changes) ---- */
static bool make(sbfx *fx, sbfx_rt *rt, int w, int h, const sbfx_rt_format *a, const sbfx_rt_format *b, GLenum filter)
{
    const sbfx_rt_format *colors[SBFX_RT_MAX] = {a, b, NULL};
    return sbfx_rt_create(fx, rt, w, h, colors, NULL, filter);
}

sbfx_result sbfx_post_targets_ensure(sbfx *fx, int w, int h)
{
    sbfx_post_gl *p = &fx->render->post;
    if (!fx->scene->plan.owns_scene || (p->width == w && p->height == h)) return SBFX_OK;
    destroy_targets(fx);
    const sbfx_rt_format *c = p->color_format, *v = p->velocity_format;
    bool ok = true;
    int frames = (fx->scene->post.dof ? 1 : 0) + (fx->scene->post.blur != SBFX_BLUR_NONE ? 1 : 0);
    /* frame[1] is the depth of field's image when the velocity blur follows: its composite writes
     * the velocities beside it (dof_composite.frag, WRITE_VELOCITY) */
    for (int i = 0; i < frames; i++) ok = ok && make(fx, &p->frame[i], w, h, c, i == 1 && fused_velocity(fx) ? v : NULL, GL_NEAREST);
    if (fx->scene->post.blur == SBFX_BLUR_HISTORY)
        for (int i = 0; i < 2; i++) ok = ok && make(fx, &p->history[i], w, h, c, NULL, GL_NEAREST);
    if (fx->scene->post.blur == SBFX_BLUR_VELOCITY) {
        int t = fx->scene->post.tile, tw = (w + t - 1) / t, th = (h + t - 1) / t;
        int k = block_tiles(fx), bw = (tw + k - 1) / k, bh = (th + k - 1) / k;
        ok = ok && (fused_velocity(fx) || make(fx, &p->velocity, w, h, v, NULL, GL_NEAREST)) &&
             make(fx, &p->tile_rows, tw, h, v, NULL, GL_NEAREST) &&
             make(fx, &p->tiles, tw, th, v, NULL, GL_NEAREST) && make(fx, &p->neighbors, tw, th, v, NULL, GL_NEAREST) &&
             make(fx, &p->classes, bw, bh, v, NULL, GL_NEAREST);
    }
    if (fx->scene->post.dof) {
        int s = fx->scene->post.dof_scale, dw = (w + s - 1) / s, dh = (h + s - 1) / s;
        /* LINEAR: the composite reads the blurred fields bilinearly in one fetch each (RGBA16F and
         * RGBA8 are filterable); the setup and the blur read texels by index */
        for (int i = 0; i < 2; i++) ok = ok && make(fx, &p->dof[i], dw, dh, c, c, GL_LINEAR);
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
    float depth_model[4];  /* window depth -> distance (projection.c) */
    float ndc_depth[2];    /* window depth -> ndc z */
    float reproject[16];   /* current NDC -> previous clip (the velocity blur) */
} post_frame;

/* The host's textures are read through sbfx's samplers, sbfx's own through their parameters. */
static void bind_unit(const sbfx *fx, GLuint program, int uniform, int unit, GLuint texture)
{
    const sbfx_post_gl *p = &fx->render->post;
    GLuint sampler = texture == p->host_depth ? fx->gl->depth_sampler
                     : texture == p->host_color ? fx->gl->color_sampler : 0;
    sbfx_bind_texture((GLuint)unit, GL_TEXTURE_2D, texture, sampler);
    glUniform1i(post_loc(p, program, uniform), unit);
}

sbfx_gl_units sbfx_post_units(const sbfx *fx)
{
    /* copy: unit 0; history: 0-1; velocity blur: 0-4; depth of field: 0-6 */
    uint32_t units = 1u;
    if (fx->scene->post.blur == SBFX_BLUR_HISTORY) units = 3u;
    if (fx->scene->post.blur == SBFX_BLUR_VELOCITY) units = 31u;
    if (fx->scene->post.dof) units = 127u;
    return (sbfx_gl_units){.tex_2d = units};
}

/* Starts a full-screen pass of `program` into `fbo` of w x h; finish() draws it. */
static void begin(GLuint program, GLuint fbo, int w, int h)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glUseProgram(program);
}

static void finish(sbfx *fx)
{
    glBindVertexArray(fx->gl->fullscreen_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    fx->counters.passes++;
    fx->counters.draw_calls++;
}

static void pass_copy(sbfx *fx, GLuint source, GLuint fbo, int w, int h)
{
    const sbfx_post_gl *p = &fx->render->post;
    GLuint prog = p->copy_program;
    begin(prog, fbo, w, h);
    bind_unit(fx, prog, PU_SOURCE, 0, source);
    finish(fx);
}

static void set_depth_uniforms(const sbfx_post_gl *p, GLuint prog, const post_frame *pf)
{
    glUniform4fv(post_loc(p, prog, PU_DEPTH_MODEL), 1, pf->depth_model);
}

/* What the velocities are made of (velocity.frag, or dof_composite.frag's WRITE_VELOCITY). */
static void set_velocity_uniforms(sbfx *fx, GLuint prog, const post_frame *pf)
{
    const sbfx_post_gl *p = &fx->render->post;
    glUniformMatrix4fv(post_loc(p, prog, PU_REPROJECT), 1, GL_FALSE, pf->reproject);
    glUniform2fv(post_loc(p, prog, PU_NDC_DEPTH), 1, pf->ndc_depth);
    glUniform1f(post_loc(p, prog, PU_SHUTTER), fx->scene->post.shutter);
    glUniform1f(post_loc(p, prog, PU_MAX_RADIUS), (float)fx->scene->post.tile);
}

/* The particles' coverage and distance (the motion target) for the DoF's CoC, when this frame
 * drew particles into it; the pixel -> particle texel scale for the composite. */
static void bind_particle_motion(sbfx *fx, GLuint prog, int unit)
{
    const sbfx_post_gl *p = &fx->render->post;
    GLuint motion = fx->gl->particles.texture[2];
    bind_unit(fx, prog, PU_PARTICLE_MOTION, unit, motion);
    glUniform1i(post_loc(p, prog, PU_PARTICLES_DRAWN), p->particles_drawn && motion);
    float divisor = (float)fx->scene->desc.target_divisor;
    if (fx->gl->low_width > 0 && fx->gl->low_height > 0)
        glUniform2f(post_loc(p, prog, PU_PARTICLE_TEXEL), 1.0f / (divisor * (float)fx->gl->low_width),
                    1.0f / (divisor * (float)fx->gl->low_height));
}

/* A post pass of `prog` over the particles' tiles (inside) or the rest (tiles.vert), in a target
 * of w x h at 1/divisor of the output. */
static void draw_tiles(sbfx *fx, GLuint prog, bool inside, int w, int h, int divisor)
{
    const sbfx_post_gl *p = &fx->render->post;
    sbfx_pass_uniforms u = {.tile_size = post_loc(p, prog, PU_TILE_SIZE), .tile_grid = post_loc(p, prog, PU_TILE_GRID),
                            .tile_target = post_loc(p, prog, PU_TILE_TARGET)};
    sbfx_tiles_draw(fx, &u, inside, w, h, divisor);
    fx->counters.passes++;
}

/* Depth of field, step 1, over the particles' tiles (inside) or the rest. */
static void dof_setup(sbfx *fx, const post_frame *pf, GLuint prog, GLuint source, bool inside)
{
    sbfx_post_gl *p = &fx->render->post;
    const sbfx_post_params *post = &fx->scene->post;
    const sbfx_frame *f = pf->f;
    const sbfx_tiles *t = &fx->render->tiles;
    if ((inside ? t->inside : t->outside) == 0) return;
    begin(prog, p->dof[0].framebuffer, p->dof[0].width, p->dof[0].height);
    sbfx_bind_texture(0, GL_TEXTURE_2D, source, fx->gl->color_sampler); /* LINEAR: 2 x 2 means in one fetch */
    glUniform1i(post_loc(p, prog, PU_COLOR), 0);
    bind_unit(fx, prog, PU_SCENE_DEPTH, 1, f->scene_depth_texture);
    glUniform1i(post_loc(p, prog, PU_SCALE), post->dof_scale);
    glUniform2i(post_loc(p, prog, PU_SIZE), f->width, f->height);
    set_depth_uniforms(p, prog, pf);
    glUniform2fv(post_loc(p, prog, PU_NEAR), 1, post->dof_near);
    glUniform2fv(post_loc(p, prog, PU_FAR), 1, post->dof_far);
    bind_particle_motion(fx, prog, 2);
    bind_unit(fx, prog, PU_SCENE_COLOR, 3, f->scene_color_texture);
    glUniform1f(post_loc(p, prog, PU_DIVISOR), (float)fx->scene->desc.target_divisor);
    glUniform2i(post_loc(p, prog, PU_PARTICLE_SIZE), fx->gl->low_width, fx->gl->low_height);
    draw_tiles(fx, prog, inside, p->dof[0].width, p->dof[0].height, post->dof_scale);
}

static void dof_composite(sbfx *fx, const post_frame *pf, GLuint prog, GLuint source, GLuint fbo, bool inside);

/* Depth of field: split by CoC at the blur resolution, blur both fields separably (two
 * passes), composite over the sharp image. The setup and the composite draw over the particles'
 * tiles and, without the particles' fetches (NO_PARTICLES), over the rest; the setup's blocks lie
 * in one tile each only where its scale divides the tile: else its full variant covers both. */
static void pass_dof(sbfx *fx, const post_frame *pf, GLuint source, GLuint fbo)
{
    sbfx_post_gl *p = &fx->render->post;
    const sbfx_post_params *post = &fx->scene->post;
    bool split = fx->render->tiles.size % post->dof_scale == 0;
    dof_setup(fx, pf, p->dof_setup_program, source, true);
    dof_setup(fx, pf, split ? p->dof_setup_plain_program : p->dof_setup_program, source, false);
    GLuint prog = p->dof_blur_program;
    for (int dir = 0; dir < 2; dir++) {
        const sbfx_rt *in = &p->dof[dir], *out = &p->dof[1 - dir];
        begin(prog, out->framebuffer, out->width, out->height);
        bind_unit(fx, prog, PU_FAR_FIELD, 0, in->texture[0]);
        bind_unit(fx, prog, PU_NEAR_FIELD, 1, in->texture[1]);
        glUniform2i(post_loc(p, prog, PU_DIRECTION), dir == 0, dir == 1);
        glUniform2i(post_loc(p, prog, PU_LOW_SIZE), in->width, in->height);
        glUniform1f(post_loc(p, prog, PU_MAX_RADIUS), post->dof_max_radius / post->dof_scale);
        finish(fx);
    }
    dof_composite(fx, pf, p->dof_composite_program, source, fbo, true);
    dof_composite(fx, pf, p->dof_plain_program, source, fbo, false);
}

/* Depth of field, step 3, over the particles' tiles (inside) or the rest (tiles.vert). */
static void dof_composite(sbfx *fx, const post_frame *pf, GLuint prog, GLuint source, GLuint fbo, bool inside)
{
    sbfx_post_gl *p = &fx->render->post;
    const sbfx_post_params *post = &fx->scene->post;
    const sbfx_frame *f = pf->f;
    const sbfx_tiles *t = &fx->render->tiles;
    if ((inside ? t->inside : t->outside) == 0) return;
    begin(prog, fbo, f->width, f->height);
    bind_unit(fx, prog, PU_COLOR, 0, source);
    bind_unit(fx, prog, PU_FAR_FIELD, 1, p->dof[0].texture[0]);
    bind_unit(fx, prog, PU_NEAR_FIELD, 2, p->dof[0].texture[1]);
    bind_unit(fx, prog, PU_SCENE_DEPTH, 3, f->scene_depth_texture);
    set_depth_uniforms(p, prog, pf);
    glUniform2fv(post_loc(p, prog, PU_FAR), 1, post->dof_far);
    glUniform2f(post_loc(p, prog, PU_LOW_TEXEL), 1.0f / (float)(post->dof_scale * p->dof[0].width),
                1.0f / (float)(post->dof_scale * p->dof[0].height));
    bind_particle_motion(fx, prog, 4);
    bind_unit(fx, prog, PU_SCENE_COLOR, 5, f->scene_color_texture);
    glUniform2f(post_loc(p, prog, PU_FULL_SIZE), (float)f->width, (float)f->height);
    /* the shimmer offsets, LINEAR like the composite's (none: an empty unit reads 0, no offset) */
    sbfx_bind_texture(6, GL_TEXTURE_2D, fx->gl->particles.texture[1], fx->gl->color_sampler);
    glUniform1i(post_loc(p, prog, PU_DISTORTION), 6);
    if (fused_velocity(fx)) set_velocity_uniforms(fx, prog, pf);
    draw_tiles(fx, prog, inside, f->width, f->height, 1);
}

/* The seed's motion blur: history = mix(new, history, e^(-dt/persistence)), then shown. */
static void pass_history(sbfx *fx, GLuint source, GLuint fbo, int w, int h, double dt)
{
    sbfx_post_gl *p = &fx->render->post;
    GLuint prog = p->history_program;
    const sbfx_rt *previous = &p->history[1 - p->history_next], *next = &p->history[p->history_next];
    float keep = p->history_valid ? (float)exp(-dt / fx->scene->post.persistence) : 0.0f;
    begin(prog, next->framebuffer, w, h);
    bind_unit(fx, prog, PU_CURRENT, 0, source);
    bind_unit(fx, prog, PU_HISTORY, 1, previous->texture[0]);
    glUniform1f(post_loc(p, prog, PU_KEEP), keep);
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

/* Current NDC -> the previous frame's clip space, in double (identity on the first frame). */
static void reprojection(const sbfx *fx, const sbfx_frame *f, float out[16])
{
    const sbfx_post_gl *p = &fx->render->post;
    double now[16], inverse[16], reproject[16];
    view_projection(f, now);
    if (!p->have_previous || !invert4(now, inverse)) memcpy(reproject, (double[16]){1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, sizeof(reproject));
    else multiply4(p->previous_view_projection, inverse, reproject);
    for (int i = 0; i < 16; i++) out[i] = (float)reproject[i];
}

/* The longest velocity of `tile` texels of `in` (w x h) along (dx, dy), into `out`: rows, then
 * columns. */
static void pass_tile_max(sbfx *fx, GLuint in, int w, int h, const sbfx_rt *out, int dx, int dy)
{
    const sbfx_post_gl *p = &fx->render->post;
    GLuint prog = p->tile_program;
    begin(prog, out->framebuffer, out->width, out->height);
    bind_unit(fx, prog, PU_VELOCITY, 0, in);
    glUniform1i(post_loc(p, prog, PU_TILE), fx->scene->post.tile);
    glUniform2i(post_loc(p, prog, PU_SIZE), w, h);
    glUniform2i(post_loc(p, prog, PU_DIRECTION), dx, dy);
    glUniform1f(post_loc(p, prog, PU_MAX_RADIUS), (float)fx->scene->post.tile);
    finish(fx);
}

/* The velocity blur's blocks of `class` (tile_class.frag) with `program`, as instances of
 * blur_tiles.vert, which reads the classes on unit 4. */
static void draw_blocks(sbfx *fx, GLuint program, float class, const sbfx_frame *f)
{
    const sbfx_post_gl *p = &fx->render->post;
    bind_unit(fx, program, PU_CLASSES, 4, p->classes.texture[0]);
    glUniform1f(post_loc(p, program, PU_CLASS), class);
    glUniform1i(post_loc(p, program, PU_BLOCK_COLUMNS), p->classes.width);
    glUniform1f(post_loc(p, program, PU_BLOCK_SIZE), (float)(block_tiles(fx) * fx->scene->post.tile));
    glUniform2f(post_loc(p, program, PU_TARGET), (float)f->width, (float)f->height);
    glBindVertexArray(fx->gl->fullscreen_vao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, p->classes.width * p->classes.height);
    fx->counters.passes++;
    fx->counters.draw_calls++;
}

/* Which blocks the gather can change and how (tile_class.frag); as before the classes (the
 * tiles' full_screen: the bench's "before", the tests' control) every block is the full
 * gather's. */
static void classify_blocks(sbfx *fx)
{
    sbfx_post_gl *p = &fx->render->post;
    if (fx->render->tiles.full_screen) {
        static const GLfloat moving[4] = {1.0f, 0.0f, 0.0f, 1.0f};
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, p->classes.framebuffer);
        glClearBufferfv(GL_COLOR, 0, moving);
        return;
    }
    GLuint prog = p->class_program;
    begin(prog, p->classes.framebuffer, p->classes.width, p->classes.height);
    bind_unit(fx, prog, PU_NEIGHBOR_MAX, 0, p->neighbors.texture[0]);
    glUniform2i(post_loc(p, prog, PU_TILES_SIZE), p->neighbors.width, p->neighbors.height);
    glUniform1f(post_loc(p, prog, PU_MAX_RADIUS), (float)fx->scene->post.tile);
    finish(fx);
}

/* The gather with `prog` over the blocks of `class`: 1 the full path, 0.5 the fast one. */
static void gather(sbfx *fx, const post_frame *pf, GLuint prog, float class, GLuint source, GLuint fbo)
{
    const sbfx_post_gl *p = &fx->render->post;
    const sbfx_frame *f = pf->f;
    begin(prog, fbo, f->width, f->height);
    bind_unit(fx, prog, PU_COLOR, 0, source);
    bind_unit(fx, prog, PU_VELOCITY, 1, velocity_texture(fx));
    bind_unit(fx, prog, PU_NEIGHBOR_MAX, 2, p->neighbors.texture[0]);
    bind_unit(fx, prog, PU_SCENE_DEPTH, 3, f->scene_depth_texture);
    glUniform2i(post_loc(p, prog, PU_SIZE), f->width, f->height);
    glUniform1i(post_loc(p, prog, PU_TILE), fx->scene->post.tile);
    glUniform1i(post_loc(p, prog, PU_SAMPLES), fx->scene->post.samples);
    glUniform1f(post_loc(p, prog, PU_MAX_RADIUS), (float)fx->scene->post.tile);
    set_depth_uniforms(p, prog, pf);
    draw_blocks(fx, prog, class, f);
}

/* McGuire's reconstruction: velocity, tile max (rows, then columns), neighbour max, the blocks
 * it moves (tile_class.frag), the gather over them and a copy over the rest. */
static void pass_velocity_blur(sbfx *fx, const post_frame *pf, GLuint source, GLuint fbo)
{
    sbfx_post_gl *p = &fx->render->post;
    const sbfx_frame *f = pf->f;
    const sbfx_post_params *post = &fx->scene->post;
    GLuint prog = p->velocity_program;
    if (!fused_velocity(fx)) {
        begin(prog, p->velocity.framebuffer, f->width, f->height);
        bind_unit(fx, prog, PU_SCENE_DEPTH, 0, f->scene_depth_texture);
        bind_unit(fx, prog, PU_PARTICLE_VELOCITY, 1, fx->gl->particles.texture[2]);
        glUniform1i(post_loc(p, prog, PU_PARTICLES_DRAWN), p->particles_drawn && fx->gl->particles.texture[2]);
        set_velocity_uniforms(fx, prog, pf);
        set_depth_uniforms(p, prog, pf);
        glUniform2f(post_loc(p, prog, PU_SIZE), (float)f->width, (float)f->height);
        glUniform1f(post_loc(p, prog, PU_DIVISOR), (float)fx->scene->desc.target_divisor);
        glUniform2i(post_loc(p, prog, PU_LOW_SIZE), fx->gl->low_width, fx->gl->low_height);
        finish(fx);
    }
    pass_tile_max(fx, velocity_texture(fx), f->width, f->height, &p->tile_rows, 1, 0);
    pass_tile_max(fx, p->tile_rows.texture[0], p->tile_rows.width, p->tile_rows.height, &p->tiles, 0, 1);
    prog = p->neighbor_program;
    begin(prog, p->neighbors.framebuffer, p->neighbors.width, p->neighbors.height);
    bind_unit(fx, prog, PU_TILES, 0, p->tiles.texture[0]);
    glUniform2i(post_loc(p, prog, PU_TILES_SIZE), p->tiles.width, p->tiles.height);
    glUniform1f(post_loc(p, prog, PU_MAX_RADIUS), (float)post->tile);
    finish(fx);
    classify_blocks(fx);
    gather(fx, pf, p->blur_program, 1.0f, source, fbo);
    gather(fx, pf, p->fast_program, 0.5f, source, fbo);
    prog = p->still_program;
    begin(prog, fbo, f->width, f->height);
    bind_unit(fx, prog, PU_SOURCE, 0, source);
    draw_blocks(fx, prog, 0.0f, f);
}

/* Runs the post chain on `source` (the composite's image, or the bare scene on an idle frame)
 * and leaves the final image in the host's framebuffer. */
sbfx_result sbfx_post_run(sbfx *fx, const sbfx_frame *f, const sbfx_depth_model *depth, GLuint source)
{
    sbfx_post_gl *p = &fx->render->post;
    post_frame pf = {f, {0}, {depth->ndc[0], depth->ndc[1]}, {0}};
    sbfx_depth_model_uniform(depth, pf.depth_model);
    if (fx->scene->post.blur == SBFX_BLUR_VELOCITY) reprojection(fx, f, pf.reproject);
    p->host_depth = f->scene_depth_texture;
    p->host_color = f->scene_color_texture;
    double dt = p->have_previous ? fx->sim->time - p->last_time : 0.0;
    glDisable(GL_BLEND);
    if (!has_steps(fx)) {
        if (source != 0) pass_copy(fx, source, f->out_framebuffer, f->width, f->height);
    } else {
        GLuint input = source;
        if (fx->scene->post.dof) {
            bool last = fx->scene->post.blur == SBFX_BLUR_NONE;
            GLuint dest = last ? f->out_framebuffer : p->frame[1].framebuffer;
            pass_dof(fx, &pf, input, dest);
            input = p->frame[1].texture[0];
        }
        if (fx->scene->post.blur == SBFX_BLUR_HISTORY) pass_history(fx, input, f->out_framebuffer, f->width, f->height, dt);
        if (fx->scene->post.blur == SBFX_BLUR_VELOCITY) pass_velocity_blur(fx, &pf, input, f->out_framebuffer);
    }
    view_projection(f, p->previous_view_projection);
    p->last_time = fx->sim->time;
    p->have_previous = true;
    return SBFX_OK;
}

/* Where the particle composite writes when sbfx owns the scene: the first post frame, or the
 * host's framebuffer when no step follows. */
GLuint sbfx_post_composite_target(const sbfx *fx, const sbfx_frame *f)
{
    return has_steps(fx) ? fx->render->post.frame[0].framebuffer : f->out_framebuffer;
}

GLuint sbfx_post_composite_texture(const sbfx *fx) { return fx->render->post.frame[0].texture[0]; }
