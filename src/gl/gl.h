/* The gl room (src/rooms.txt; docs/hacking.md): what the module makes on the GPU and how it
 * behaves as a guest in the host's context. Above the plan, its tables and the simulation
 * (what to make, and the particles' instance data the buffers hold).
 *
 * Exports to the rooms above:
 *   - the context (context.c: ES 3.0+ or desktop OpenGL that runs GLSL ES 3.00) and the
 *     precision diagnostics read at create (precision.c); GL error checks and the host's
 *     pending errors (gl_util.c: sbfx_gl_check, sbfx_gl_enter/leave);
 *   - the host contract: the GL state saved and put back, texture units, samplers (gl_state.h);
 *   - programs built from the embedded shaders with defines (gl_util.c: sbfx_program_build),
 *     the particle and composite variants of each quality level (program.h, programs.c);
 *   - render targets and each level's particle target set (target.h: rt.c, targets.c);
 *   - what a quality level needs on the GPU, made at load or at first use, and switching to it
 *     (levels.c: sbfx_quality_load, sbfx_quality_apply);
 *   - the textures the particle shader samples: the scene's tables, the detail volume, smoke
 *     textures (luts.c, with the detail volume's public entry points);
 *   - the objects a reload takes over (objects.h), sbfx's own GPU timer (gpu_timer.h).
 * Its state: sbfx_gl (fx->gl). */
#ifndef SBFX_GL_H
#define SBFX_GL_H

#include <GLES3/gl3.h>
#include "base/base.h"
#include "scene/scene_tables.h"
#include "sim/sim.h"
#include "gl/gl_state.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "gl/target.h"

#define SBFX_UNIT_PHASE 2     /* texture units of the particle passes' tables */
#define SBFX_UNIT_BLACKBODY 3

/* GL errors pending when an entry point was called: the host's, read off at entry so that
 * sbfx's checks see only its own, and posted again at return where GL allows (gl_util.c). */
#define SBFX_HOST_ERRORS_MAX 8
typedef struct sbfx_host_errors {
    GLenum code[SBFX_HOST_ERRORS_MAX];
    int count;
    unsigned logged;             /* bit per kind already logged (once per module) */
} sbfx_host_errors;

/* What was learnt about the host's context at create; kept across sbfx_reload. */
typedef struct sbfx_gl_context {
    unsigned parts;               /* SBFX_GL_SAVE_DESKTOP / _COMPAT on desktop OpenGL (context.c) */
    bool mediump_as_highp;        /* a software rasteriser: shaders' mediump compiled as highp (context.c) */
    bool mediump_native;          /* SBFX_MEDIUMP=native: mediump as written, also there (precision.c) */
    int filter_bits;              /* SBFX_FILTER_BITS=N: filtered fetches by hand, N-bit weights; 0: off */
    sbfx_host_errors host_errors; /* GL errors the host left pending (gl_util.c) */
    bool warned_format;           /* a particle target format's fallback was logged (targets.c) */
    bool warned_refine;           /* mixed resolution's fallback to nearest depth was logged (targets.c) */
} sbfx_gl_context;

/* The gl room's state (fx->gl). */
typedef struct sbfx_gl {
    sbfx_gl_context context;
    sbfx_pass_uniforms depth_u, corners_u, composite_u;
    GLuint fullscreen_vao, particle_vao, instance_buffer;
    GLuint depth_program, corners_program, composite_program;
    GLuint refine_mark_program;  /* mixed resolution: marks the pixels the coarse target fails (refine_mark.frag) */
    sbfx_pass_uniforms refine_mark_u;
    GLuint refine_depth_program; /* mixed resolution: the depth at full resolution (depth_downsample.frag SINGLE_TEXEL) */
    sbfx_pass_uniforms refine_depth_u;
    GLuint stop_program;         /* early termination's mark (terminate_mark.frag, render/terminate.c) */
    sbfx_pass_uniforms stop_u;
    GLuint scene_only_program;   /* the scene outside the particles' tiles (owned scenes: composite.frag SCENE_ONLY) */
    sbfx_pass_uniforms scene_only_u;
    sbfx_program particle[SBFX_MEDIUM_COUNT];
    GLuint blackbody_texture, phase_texture, detail_texture;
    GLuint smoke_texture[SBFX_MEDIUM_COUNT]; /* 2D arrays, lit media only (tables/tables.h layout) */
    GLuint depth_sampler, color_sampler;     /* how the host's depth and colour are read */
    int detail_ring_next;        /* next slice sbfx_detail_push_slice writes */
    float *detail_scratch;       /* one R32F slice, only with SBFX_DETAIL_R32F */
    /* targets, (re)made when the output size changes */
    sbfx_rt particles, low_depth, low_corners;
    sbfx_rt refine, refine_depth;  /* mixed resolution's (render/refine.c); none at other levels */
    GLuint stop_framebuffer;       /* early termination's marks (render/terminate.c); 0: none */
    int out_width, out_height, low_width, low_height;
    GLenum target_type;
    /* quality caches (the fields above hold the current level's copies) */
    sbfx_variant variants[SBFX_VARIANTS];
    GLuint composites[SBFX_UPSAMPLE_COUNT];
    sbfx_pass_uniforms composite_us[SBFX_UPSAMPLE_COUNT];
    sbfx_target_set targets[SBFX_TARGET_SETS];
    /* objects.c: what the module made (lendable), and the module it borrows from while a
     * sbfx_set_scene builds it */
    sbfx_object objects[SBFX_OBJECTS];
    int object_count;
    struct sbfx *donor;
} sbfx_gl;

/* context.c: OpenGL ES 3.0+, or desktop OpenGL that runs GLSL ES 3.00 (issue 18) */
sbfx_result sbfx_context_check(sbfx *fx);
int sbfx_context_version(bool *desktop); /* major * 10 + minor of the current context */
bool sbfx_context_desktop(void);
/* precision.c: the diagnostics SBFX_MEDIUMP and SBFX_FILTER_BITS, read once by sbfx_create */
sbfx_result sbfx_precision_from_env(sbfx *fx);
const char *sbfx_filter_library(void);

/* gl_util.c */
bool sbfx_gl_check(sbfx *fx, const char *what);
/* Around the GL work of a public entry point: enter reads off the errors the host left
 * pending; leave, after sbfx's own errors were checked, posts them again (include/sbfx.h, "GL errors
 * the host left pending"). */
void sbfx_gl_enter(sbfx *fx);
void sbfx_gl_leave(sbfx *fx, const char *entry);
GLuint sbfx_program_build(sbfx *fx, const char *vert_name, const char *frag_name,
                          const char *defines);
void sbfx_texture_params(GLenum target, GLenum filter, GLenum wrap);
GLuint sbfx_texture_create(sbfx *fx, GLenum target, GLenum filter, GLenum wrap);
bool sbfx_has_extension(const char *name);
/* The embedded shaders (generated from shaders_es/ at build time). */
const char *sbfx_shader_source(const char *name);

/* luts.c: the scene's tables, the detail volume, lit media's smoke textures */
sbfx_result sbfx_luts_create(sbfx *fx);
void sbfx_luts_destroy(sbfx *fx);
/* A table's texture where a level chosen later samples it first (from the CPU copy). */
sbfx_result sbfx_tables_upload_blackbody(sbfx *fx);
sbfx_result sbfx_tables_upload_phase(sbfx *fx);
/* Binds the tables to their units and sets a particle program's table uniforms for medium m. */
void sbfx_tables_bind(const sbfx *fx, const sbfx_program *p, sbfx_medium m);

/* levels.c: a quality level on the GPU */
sbfx_variant_key sbfx_variant_key_of(const sbfx *fx, const sbfx_quality *q);
/* Load: builds what the declared levels need (inside load_gl's saved state), the top current. */
sbfx_result sbfx_quality_load(sbfx *fx);
/* Makes q the current level: builds what its first use needs (own saved state), then points
 * the module's current programs, composite and tables at it. No allocation once used. */
sbfx_result sbfx_quality_apply(sbfx *fx, const sbfx_quality *q);
/* More light slots than the scene has (tests and tools that set lights): the particle
 * programs are made again with the larger loop. */
void sbfx_light_slots_reserve(sbfx *fx, int count);

#endif
