/* The host contract (docs/design.md §5, issue 10): every entry point leaves every GL state a host can
 * rely on as the host left it, and sbfx's pictures do not depend on that state. On a desktop
 * OpenGL context as well (SBFX_TEST_GL_API=core or compat, issue 18; tests/run.sh runs it so):
 * there the host also sets desktop OpenGL's own state (gl_desktop.h).
 *
 * A "hostile" host sets everything in gl_snapshot.h to a value other than GL's default —
 * texture, sampler and binding state on many units (not only the ones sbfx uses), a pixel
 * unpack buffer bound while sbfx uploads, pixel store with row lengths and skips, blending,
 * depth, stencil, cull, scissor, colour mask, polygon offset, dither off, alpha-to-coverage,
 * clip control... — and its scene depth texture samples LINEAR with COMPARE_REF_TO_TEXTURE,
 * its colour texture with a mipmapped filter it has no mipmaps for (incomplete unless read
 * through sbfx's own samplers). Each entry point runs between two snapshots that must agree;
 * the same module driven the same way under GL's default state must render the same bytes. */
#include <EGL/egl.h>
#include "gl_fixture.h"
#include "gl_snapshot.h"
#include "gl_desktop.h"
#include "host/test_scene.h"

#define W 96
#define H 64
#define GL_LOWER_LEFT_EXT 0x8CA1
#define GL_NEGATIVE_ONE_TO_ONE_EXT 0x935E
#define GL_ZERO_TO_ONE_EXT 0x935F

typedef void (*clip_control_fn)(GLenum origin, GLenum depth);

typedef struct host {
    gl_fixture gl;
    struct test_scene scene;
    GLuint program, vao, buffers[8], draw_fbo, read_fbo, renderbuffer, feedback;
    GLuint tex_2d[3], tex_3d[2], tex_array[2], tex_cube[2], samplers[2];
    GLuint out_texture[2], out_fbo[2]; /* 0: the module under GL's defaults, 1: under the hostile state */
    clip_control_fn clip_control;
    bool desktop, compat;  /* SBFX_TEST_GL_API=core or compat: desktop OpenGL (issue 18) */
    desktop_fns gl_fns;    /* its functions the ES headers lack */
    int units;
    snapshot before, after;
} host;

static GLuint host_program(void)
{
    static const char *vs = "#version 300 es\nlayout(location = 0) in vec4 p;\nvoid main() { gl_Position = p; }\n";
    static const char *fs = "#version 300 es\nprecision mediump float;\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
    return fixture_program(vs, fs);
}

static void make_textures(GLenum target, GLuint *out, int n)
{
    glGenTextures(n, out);
    for (int i = 0; i < n; i++) {
        glBindTexture(target, out[i]);
        if (target == GL_TEXTURE_2D) glTexImage2D(target, 0, GL_RGBA8, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        else if (target == GL_TEXTURE_CUBE_MAP)
            for (GLenum f = 0; f < 6; f++)
                glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f, 0, GL_RGBA8, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        else glTexImage3D(target, 0, GL_RGBA8, 4, 4, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    }
    glBindTexture(target, 0);
}

static void make_output(host *h, int i)
{
    fixture_rgba8_target(W, H, &h->out_texture[i], &h->out_fbo[i]);
}

/* The host's objects: a program, a vertex array with an element buffer and attributes, a
 * buffer for every binding point, framebuffers, textures of every kind, samplers. */
static void host_objects(host *h)
{
    h->program = host_program();
    glGenBuffers(8, h->buffers);
    for (int i = 0; i < 8; i++) {
        glBindBuffer(GL_ARRAY_BUFFER, h->buffers[i]);
        glBufferData(GL_ARRAY_BUFFER, 256, NULL, GL_STATIC_DRAW);
    }
    glGenVertexArrays(1, &h->vao);
    glBindVertexArray(h->vao);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, h->buffers[0]);
    for (GLuint a = 0; a < 3; a++) {
        glBindBuffer(GL_ARRAY_BUFFER, h->buffers[1 + a]);
        glEnableVertexAttribArray(a);
        glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, 20, (const void *)(size_t)(4 * a));
        glVertexAttribDivisor(a, a);
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glGenFramebuffers(1, &h->draw_fbo);
    glGenFramebuffers(1, &h->read_fbo);
    glGenRenderbuffers(1, &h->renderbuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, h->renderbuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glGenTransformFeedbacks(1, &h->feedback);
    make_textures(GL_TEXTURE_2D, h->tex_2d, 3);
    make_textures(GL_TEXTURE_3D, h->tex_3d, 2);
    make_textures(GL_TEXTURE_2D_ARRAY, h->tex_array, 2);
    make_textures(GL_TEXTURE_CUBE_MAP, h->tex_cube, 2);
    glGenSamplers(2, h->samplers);
    for (int i = 0; i < 2; i++) { /* what a shadow-mapping host binds: filtered, comparing, mipmapped */
        glSamplerParameteri(h->samplers[i], GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glSamplerParameteri(h->samplers[i], GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glSamplerParameteri(h->samplers[i], GL_TEXTURE_WRAP_S, GL_MIRRORED_REPEAT);
    }
    make_output(h, 0);
    make_output(h, 1);
}

static void host_open(host *h)
{
    memset(h, 0, sizeof(*h));
    fixture_open(&h->gl, W, H);
    char err[256];
    CHECK(test_scene_create(&h->scene, W, H, err, sizeof(err)) == 0, "%s", err);
    h->gl.frame.scene_color_texture = h->scene.color_texture;
    h->gl.frame.scene_depth_texture = h->scene.depth_texture;
    h->units = snap_units();
    h->clip_control = host_depth_clip_control();
    h->desktop = h->gl.egl.api != EGL_HEADLESS_GLES3;
    h->compat = h->gl.egl.api == EGL_HEADLESS_GL_COMPAT;
    snap_core_profile = h->gl.egl.api == EGL_HEADLESS_GL_CORE;
    snap_compat_profile = h->compat;
    if (h->desktop) desktop_fns_load(&h->gl_fns);
    host_objects(h);
    printf("# %s: %d texture units checked; clip control %s\n", (const char *)glGetString(GL_VERSION), h->units,
           h->clip_control ? "checked" : "not offered (GL_EXT_clip_control / GL_ARB_clip_control missing)");
}

/* ---- the two host states ------------------------------------------------------------------ */

static void units_bound(const host *h, bool hostile)
{
    for (int u = 0; u < h->units; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        glBindTexture(GL_TEXTURE_2D, hostile ? h->tex_2d[u % 3] : 0);
        glBindTexture(GL_TEXTURE_3D, hostile ? h->tex_3d[u % 2] : 0);
        glBindTexture(GL_TEXTURE_2D_ARRAY, hostile ? h->tex_array[u % 2] : 0);
        glBindTexture(GL_TEXTURE_CUBE_MAP, hostile ? h->tex_cube[u % 2] : 0);
        glBindSampler((GLuint)u, hostile ? h->samplers[u % 2] : 0);
    }
    glActiveTexture(hostile ? GL_TEXTURE7 : GL_TEXTURE0);
}

static void bindings(const host *h, bool hostile)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, hostile ? h->draw_fbo : 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, hostile ? h->read_fbo : 0);
    glBindRenderbuffer(GL_RENDERBUFFER, hostile ? h->renderbuffer : 0);
    glUseProgram(hostile ? h->program : 0);
    glBindVertexArray(hostile ? h->vao : 0);
    glBindBuffer(GL_ARRAY_BUFFER, hostile ? h->buffers[1] : 0);
    glBindBufferBase(GL_UNIFORM_BUFFER, 2, hostile ? h->buffers[2] : 0);
    glBindBuffer(GL_UNIFORM_BUFFER, hostile ? h->buffers[3] : 0);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, hostile ? h->buffers[4] : 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, hostile ? h->buffers[5] : 0);
    glBindBuffer(GL_COPY_READ_BUFFER, hostile ? h->buffers[6] : 0);
    glBindBuffer(GL_COPY_WRITE_BUFFER, hostile ? h->buffers[7] : 0);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, hostile ? h->feedback : 0);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, hostile ? h->buffers[0] : 0);
    units_bound(h, hostile);
}

static void set_on(GLenum cap, bool on)
{
    if (on) glEnable(cap);
    else glDisable(cap);
}

static void fragment_ops(bool hostile)
{
    set_on(GL_BLEND, hostile);
    glBlendFuncSeparate(hostile ? GL_SRC_COLOR : GL_ONE, hostile ? GL_DST_ALPHA : GL_ZERO,
                        hostile ? GL_ONE_MINUS_DST_COLOR : GL_ONE, hostile ? GL_SRC_ALPHA_SATURATE : GL_ZERO);
    glBlendEquationSeparate(hostile ? GL_FUNC_SUBTRACT : GL_FUNC_ADD, hostile ? GL_MAX : GL_FUNC_ADD);
    glBlendColor(hostile ? 0.1f : 0, hostile ? 0.2f : 0, hostile ? 0.3f : 0, hostile ? 0.4f : 0);
    set_on(GL_DEPTH_TEST, hostile);
    glDepthFunc(hostile ? GL_GREATER : GL_LESS);
    glDepthMask(hostile ? GL_FALSE : GL_TRUE);
    glDepthRangef(hostile ? 0.2f : 0.0f, hostile ? 0.7f : 1.0f);
    glClearDepthf(hostile ? 0.25f : 1.0f);
    set_on(GL_STENCIL_TEST, hostile);
    glStencilFuncSeparate(GL_FRONT, hostile ? GL_EQUAL : GL_ALWAYS, hostile ? 3 : 0, hostile ? 0x0f : ~0u);
    glStencilFuncSeparate(GL_BACK, hostile ? GL_NEVER : GL_ALWAYS, hostile ? 5 : 0, hostile ? 0xf0 : ~0u);
    glStencilOpSeparate(GL_FRONT, hostile ? GL_INCR : GL_KEEP, hostile ? GL_DECR : GL_KEEP, hostile ? GL_INVERT : GL_KEEP);
    glStencilOpSeparate(GL_BACK, hostile ? GL_ZERO : GL_KEEP, hostile ? GL_REPLACE : GL_KEEP, hostile ? GL_INCR_WRAP : GL_KEEP);
    glStencilMaskSeparate(GL_FRONT, hostile ? 0x3c : ~0u);
    glStencilMaskSeparate(GL_BACK, hostile ? 0xc3 : ~0u);
    glClearStencil(hostile ? 7 : 0);
    glColorMask(GL_TRUE, hostile ? GL_FALSE : GL_TRUE, GL_TRUE, hostile ? GL_FALSE : GL_TRUE);
    glClearColor(hostile ? 0.3f : 0, hostile ? 0.2f : 0, hostile ? 0.1f : 0, hostile ? 0.9f : 0);
    set_on(GL_DITHER, !hostile);
    set_on(GL_SAMPLE_ALPHA_TO_COVERAGE, hostile);
    set_on(GL_SAMPLE_COVERAGE, hostile);
    glSampleCoverage(hostile ? 0.5f : 1.0f, hostile ? GL_TRUE : GL_FALSE);
}

static void raster(bool hostile)
{
    glViewport(hostile ? 3 : 0, hostile ? 5 : 0, hostile ? 17 : W, hostile ? 11 : H);
    set_on(GL_SCISSOR_TEST, hostile);
    glScissor(hostile ? 1 : 0, hostile ? 2 : 0, hostile ? 3 : W, hostile ? 4 : H);
    set_on(GL_CULL_FACE, hostile);
    glCullFace(hostile ? GL_FRONT_AND_BACK : GL_BACK);
    glFrontFace(hostile ? GL_CW : GL_CCW);
    set_on(GL_POLYGON_OFFSET_FILL, hostile);
    glPolygonOffset(hostile ? 1.5f : 0.0f, hostile ? 2.0f : 0.0f);
    set_on(GL_RASTERIZER_DISCARD, false); /* the host draws nothing with it on: see rasterizer_discard_on */
    set_on(GL_PRIMITIVE_RESTART_FIXED_INDEX, hostile);
    if (!snap_core_profile) glHint(GL_GENERATE_MIPMAP_HINT, hostile ? GL_NICEST : GL_DONT_CARE);
    glHint(GL_FRAGMENT_SHADER_DERIVATIVE_HINT, hostile ? GL_FASTEST : GL_DONT_CARE);
    const GLint pack[] = {hostile ? 2 : 4, hostile ? 7 : 0, hostile ? 1 : 0, hostile ? 2 : 0};
    const GLint unpack[] = {hostile ? 8 : 4, hostile ? 5 : 0, hostile ? 3 : 0, hostile ? 1 : 0, hostile ? 1 : 0, hostile ? 1 : 0};
    const GLenum pack_names[] = {GL_PACK_ALIGNMENT, GL_PACK_ROW_LENGTH, GL_PACK_SKIP_PIXELS, GL_PACK_SKIP_ROWS};
    const GLenum unpack_names[] = {GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT,
                                   GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_IMAGES};
    for (int i = 0; i < 4; i++) glPixelStorei(pack_names[i], pack[i]);
    for (int i = 0; i < 6; i++) glPixelStorei(unpack_names[i], unpack[i]);
    for (GLuint a = 0; a < 4; a++)
        glVertexAttrib4f(a, hostile ? 0.5f + a : 0.0f, hostile ? -2.0f : 0.0f, hostile ? 7.0f : 0.0f, hostile ? 3.0f : 1.0f);
}

/* Host textures: a shadow map's sampling (depth) and an incomplete mipmapped filter (colour). */
static void host_texture_params(const host *h, bool hostile)
{
    glBindTexture(GL_TEXTURE_2D, h->scene.depth_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, hostile ? GL_LINEAR : GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, hostile ? GL_LINEAR : GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, hostile ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, hostile ? GL_GEQUAL : GL_LEQUAL);
    glBindTexture(GL_TEXTURE_2D, h->scene.color_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, hostile ? GL_NEAREST_MIPMAP_LINEAR : GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, hostile ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
}

static void host_state(host *h, bool hostile)
{
    if (h->desktop) desktop_state(&h->gl_fns, h->compat, hostile);
    host_texture_params(h, hostile);
    if (h->clip_control) h->clip_control(GL_LOWER_LEFT_EXT, hostile ? GL_ZERO_TO_ONE_EXT : GL_NEGATIVE_ONE_TO_ONE_EXT);
    fragment_ops(hostile);
    raster(hostile);
    bindings(h, hostile);
}

/* ---- entry points between snapshots --------------------------------------------------------- */

static void snap_before(host *h)
{
    host_state(h, true);
    snapshot_take(&h->before, h->clip_control != NULL);
    if (h->desktop) snap_desktop(&h->before, h->compat);
}

/* The entry point has run: the state must be the snapshot's, and GL must report no error. */
static void snap_after(host *h, const char *what)
{
    snapshot_take(&h->after, h->clip_control != NULL);
    if (h->desktop) snap_desktop(&h->after, h->compat);
    char first[64];
    int differ = snapshot_diff(&h->before, &h->after, what, first, sizeof(first));
    CHECK(differ == 0, "%s changed %d GL states (first: %s)", what, differ, first);
    GLenum e = glGetError();
    CHECK(e == GL_NO_ERROR, "%s left GL error 0x%04x", what, e);
}

static sbfx_scene *scene_from(const char *path, const char *extra)
{
    char err[512];
    sbfx_scene *scene = NULL;
    FILE *f = fopen(path, "rb");
    CHECK(f != NULL, "cannot open %s", path);
    if (!f) exit(1);
    static char text[32768];
    size_t n = fread(text, 1, sizeof(text) - 1024, f);
    fclose(f);
    text[n] = '\0';
    strcat(text, extra);
    CHECK(sbfx_scene_parse(text, path, &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (!scene) exit(1);
    return scene;
}

typedef struct state_case {
    const char *name, *path, *extra, *effect;
    const char *quality; /* switched to after sbfx_create (sbfx_set_quality), NULL: none */
    float budget_ms;     /* desc.frame_budget_ms */
    bool depth_range;    /* a frame saves the depth range on ES too (desktop OpenGL always does) */
    bool terminate;      /* early termination turned on (sbfx_set_early_termination) */
} state_case;

/* The built-in explosion, every post effect (heat shimmer, velocity blur, depth of field), the
 * seed's history blur, and lit smoke (a 2D-array texture on a fifth unit). */
static const state_case cases[] = {
    {"built-in explosion", NULL, NULL, "explosion", NULL, 0.0f, false, false},
    {"post.cfg: shimmer, velocity blur, depth of field", "scenes/post.cfg", "", "explosion", NULL, 0.0f, false, false},
    {"explosion with history blur", "scenes/explosion.cfg", "\npost = { motion_blur = { mode = \"history\"; persistence = 0.15; }; };\n",
     "explosion", NULL, 0.0f, false, false},
    {"lit-smoke.cfg", "scenes/lit-smoke.cfg", "", "column", NULL, 0.0f, false, false},
    /* a level's first use makes programs, the black-body constants, a wider instance buffer and
     * the level of detail's memory inside sbfx_set_quality; targets inside sbfx_render */
    {"built-in explosion switched to spherical/2/bl/lpp/abb/lod64", NULL, NULL, "explosion",
     "spherical/2/bl/lpp/abb/lod64", 0.0f, false, false},
    /* mixed resolution: the refine target (made inside sbfx_render), its depth test as the mask
     * (the particles' window depth: the host's depth range 0.2-0.7 and clip control ZERO_TO_ONE
     * would move it), the refined particles on a sixth unit */
    {"built-in explosion switched to exact/4/mx", NULL, NULL, "explosion", "exact/4/mx", 0.0f, true, false},
    /* the budget walks down at once: timer queries around the passes, levels switched in render */
    {"built-in explosion under a budget nothing meets (0.001 ms)", NULL, NULL, "explosion", NULL, 0.001f, false, false},
    /* early termination: the particle target's depth renderbuffer (made inside sbfx_render: the
     * host's renderbuffer binding), its test as the mask (the particles' window depth, as mixed
     * resolution's), the marks' framebuffer */
    {"built-in explosion with early termination", NULL, NULL, "explosion", NULL, 0.0f, true, true},
};

static sbfx *case_module(host *h, const state_case *c)
{
    sbfx_scene *scene = c->path ? scene_from(c->path, c->extra) : NULL;
    sbfx *fx = fixture_module(&h->gl, (sbfx_desc){.scene = scene, .ignore_timeline = true, .max_particles = 512,
                                                  .frame_budget_ms = c->budget_ms});
    sbfx_scene_free(scene);
    if (c->terminate) CHECK(sbfx_set_early_termination(fx, true) == SBFX_OK, "%s", sbfx_last_error(fx));
    return fx;
}

static void read_output(host *h, int i, uint8_t *rgba)
{
    host_state(h, false);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, h->out_fbo[i]);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

/* The host's picture: the scene, copied into both outputs before sbfx composites over it. */
static void draw_scene(host *h, double t)
{
    host_state(h, false);
    test_scene_orbit_camera(t, (float)W / H, h->gl.frame.view, h->gl.frame.projection);
    CHECK(test_scene_draw(&h->scene, h->gl.frame.view, h->gl.frame.projection) == 0);
    for (int i = 0; i < 2; i++) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, h->scene.framebuffer);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, h->out_fbo[i]);
        glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    host_state(h, false);
}

/* Renders one frame with both modules (0 under GL's defaults, 1 under the hostile state between
 * snapshots); the pictures must be the same bytes. Returns the hostile render's queries. */
static int render_both(host *h, sbfx *fx[2], double t, const char *what)
{
    draw_scene(h, t);
    static uint8_t out[2][W * H * 4];
    sbfx_frame frame = h->gl.frame;
    frame.out_framebuffer = h->out_fbo[0];
    CHECK(sbfx_render(fx[0], &frame) == SBFX_OK, "%s", sbfx_last_error(fx[0]));
    frame.out_framebuffer = h->out_fbo[1];
    snap_before(h);
    CHECK(sbfx_render(fx[1], &frame) == SBFX_OK, "%s", sbfx_last_error(fx[1]));
    snap_after(h, what);
    sbfx_counters c;
    sbfx_stats(fx[1], &c);
    read_output(h, 0, out[0]);
    read_output(h, 1, out[1]);
    int differ = 0;
    for (size_t i = 0; i < sizeof(out[0]); i++) differ += out[0][i] != out[1][i];
    CHECK(differ == 0, "%s: %d bytes of the picture depend on the host's GL state", what, differ);
    return c.gl_state_queries;
}

static void both(host *h, sbfx *fx[2], sbfx_result (*call)(sbfx *, void *), void *arg, const char *what)
{
    host_state(h, false);
    CHECK(call(fx[0], arg) == SBFX_OK, "%s: %s", what, sbfx_last_error(fx[0]));
    snap_before(h);
    CHECK(call(fx[1], arg) == SBFX_OK, "%s: %s", what, sbfx_last_error(fx[1]));
    snap_after(h, what);
}

static sbfx_result call_update(sbfx *fx, void *arg) { return sbfx_update(fx, *(double *)arg); }
static sbfx_result call_set_quality(sbfx *fx, void *arg)
{
    sbfx_quality q;
    sbfx_result r = sbfx_quality_parse(arg, &q, NULL, 0);
    return r == SBFX_OK ? sbfx_set_quality(fx, &q) : r;
}
static sbfx_result call_trigger(sbfx *fx, void *arg) { return sbfx_trigger(fx, arg, (const float[3]){0, 0, 0}); }

static sbfx_result call_push_slice(sbfx *fx, void *arg)
{
    (void)arg;
    enum { SIDE = 128 }; /* the default detail volume's width (docs/look.md) */
    static uint16_t slice[SIDE * SIDE];
    for (int i = 0; i < SIDE * SIDE; i++) {
        _Float16 v = (_Float16)((i * 37 % 101) / 100.0f);
        memcpy(&slice[i], &v, sizeof(v));
    }
    return sbfx_detail_push_slice(fx, slice, SIDE);
}

/* create, trigger, update, push_slice, render (first: targets made; then steady), idle render,
 * destroy: each under the hostile state between snapshots, the same against GL's defaults. */
static void run_case(const state_case *c, int expected_queries[3])
{
    host h;
    host_open(&h);
    printf("# %s\n", c->name);
    sbfx *fx[2];
    host_state(&h, false);
    fx[0] = case_module(&h, c);
    snap_before(&h);
    fx[1] = case_module(&h, c);
    snap_after(&h, "sbfx_create");
    if (c->quality) both(&h, fx, call_set_quality, (void *)c->quality, "sbfx_set_quality (first use)");
    both(&h, fx, call_trigger, (void *)c->effect, "sbfx_trigger");
    double dt = 0.25;
    both(&h, fx, call_update, &dt, "sbfx_update");
    both(&h, fx, call_push_slice, NULL, "sbfx_detail_push_slice");
    int q[3];
    q[0] = render_both(&h, fx, 0.25, "sbfx_render (first frame: targets made)");
    both(&h, fx, call_update, &dt, "sbfx_update");
    q[1] = render_both(&h, fx, 0.5, "sbfx_render (live particles)");
    for (int i = 0; c->budget_ms > 0 && i < 8; i++) { /* measurements arrive a few frames late */
        dt = 0.02;
        both(&h, fx, call_update, &dt, "sbfx_update");
        int q_level = render_both(&h, fx, 0.5 + dt * (i + 1), "sbfx_render (the budget's level)");
        CHECK(q_level == q[1], "%d queries at another level, %d at the top", q_level, q[1]);
    }
    dt = 10.0;
    for (int i = 0; i < 40; i++) both(&h, fx, call_update, &dt, "sbfx_update");
    sbfx_counters counters;
    sbfx_stats(fx[1], &counters);
    CHECK(counters.particles_alive == 0, "%d particles still alive", counters.particles_alive);
    printf("#   level %s, %d changes\n", counters.quality, counters.quality_changes);
    if (c->quality) CHECK(strcmp(counters.quality, c->quality) == 0, "level %s", counters.quality);
    if (c->budget_ms > 0) CHECK(counters.quality_changes > 0, "the budget did not move the level");
    q[2] = render_both(&h, fx, 10.5, "sbfx_render (idle)");
    printf("#   glGet/glIs calls to save and restore: first frame %d, live particles %d, idle %d\n", q[0], q[1], q[2]);
    CHECK(q[0] == q[1], "first frame %d queries, later frames %d", q[0], q[1]);
    /* desktop OpenGL: its own raster state on top, in every block that runs a pass (module.h,
     * SBFX_GL_SAVE_DESKTOP): depth range, polygon mode, logic op, depth clamp, polygon smooth,
     * 8 clip distances; and the compatibility profile's alpha test (the depth range already
     * counted in a case that saves it on ES too) */
    int desktop = h.desktop ? (h.compat ? 14 : 13) - (c->depth_range ? 1 : 0) : 0;
    int want[3] = {expected_queries[0], expected_queries[1] + desktop, expected_queries[2] ? expected_queries[2] + desktop : 0};
    CHECK(q[1] == want[1] && q[2] == want[2], "queries %d / %d, expected %d / %d", q[1], q[2], want[1], want[2]);
    host_state(&h, false);
    sbfx_destroy(fx[0]);
    snap_before(&h);
    sbfx_destroy(fx[1]);
    snap_after(&h, "sbfx_destroy");
    fixture_close(&h.gl);
}

/* Expected glGet/glIs counts of a render under the hostile host (which has a program bound,
 * so the restore asks glIsProgram once): 20 for the pass state (program, vertex array, array
 * buffer, draw framebuffer, viewport, 4 blend functions, 2 equations, depth function and
 * mask, colour mask, 6 enables), 1 glIsProgram, 1 active texture, then one per (unit,
 * target) sbfx binds and one sampler binding per unit; without post effects, 2 more: the
 * composite asks which texture the host's framebuffer draws into (its scene colour texture is
 * read for the tone map only when it is not that one). */
CHECK_TEST(builtin_explosion_leaves_state)
{
    /* units 0-3 2D (+ sampler each), unit 1 3D: 22 + 4 + 4 + 1, + 2 attachment queries; idle: no
     * pass, no query */
    int expected[3] = {33, 33, 0};
    run_case(&cases[0], expected);
}

CHECK_TEST(post_effects_leave_state)
{
    /* units 0-6 2D (the DoF composite's seven), unit 1 3D, 7 samplers; idle (post passes only):
     * units 0-6 2D + samplers */
    int expected[3] = {37, 37, 36};
    run_case(&cases[1], expected);
}

CHECK_TEST(history_blur_leaves_state)
{
    /* units 0-3 2D, unit 1 3D, 4 samplers; idle: the history pass and copy, units 0-1 */
    int expected[3] = {31, 31, 26};
    run_case(&cases[2], expected);
}

CHECK_TEST(lit_smoke_leaves_state)
{
    /* units 0-3 2D (3: no black body, the scene colour for the tone map), unit 1 3D, unit 4 2D
     * array, 4 samplers, + 2 attachment queries */
    int expected[3] = {35, 35, 0};
    run_case(&cases[3], expected);
}

CHECK_TEST(quality_first_use_leaves_state)
{
    /* as the built-in explosion: the new level binds the same units */
    int expected[3] = {33, 33, 0};
    run_case(&cases[4], expected);
}

CHECK_TEST(frame_budget_leaves_state)
{
    /* timer queries are not host state: the same save and restore as without a budget */
    int expected[3] = {33, 33, 0};
    run_case(&cases[6], expected);
}

CHECK_TEST(mixed_resolution_leaves_state)
{
    /* as the built-in explosion, and unit 5's 2D texture and sampler (the refined particles),
     * and the depth range (the refinement's mask compares the particles' window depth, which
     * the host's depth range and clip control place; on desktop OpenGL already counted) */
    int expected[3] = {36, 36, 0};
    run_case(&cases[5], expected);
}

CHECK_TEST(early_termination_leaves_state)
{
    /* as the built-in explosion, and the depth range (the marks' mask compares the particles'
     * window depth; on desktop OpenGL already counted) */
    int expected[3] = {34, 34, 0};
    run_case(&cases[7], expected);
}

/* ---- the host's shadow map (sbfx_render_shadow_map) ------------------------------------------ */

static sbfx_result call_shadow_map(sbfx *fx, void *arg)
{
    sbfx_shadow_map map;
    return sbfx_render_shadow_map(fx, arg, &map);
}

/* Made at load, drawn with live particles (one pass), cleared once when they are gone, refused
 * for a zero direction: the host's state is the snapshot's after each; both modules' maps hold
 * the same bytes whatever the host's state was. */
CHECK_TEST(shadow_map_leaves_state)
{
    host h;
    host_open(&h);
    sbfx_desc desc = {.ignore_timeline = true, .max_particles = 512, .shadow_map_size = 64};
    sbfx *fx[2];
    host_state(&h, false);
    fx[0] = fixture_module(&h.gl, desc);
    snap_before(&h);
    fx[1] = fixture_module(&h.gl, desc);
    snap_after(&h, "sbfx_create with a shadow map");
    float sun[3] = {0.5f, -0.8f, 0.3f};
    both(&h, fx, call_shadow_map, sun, "sbfx_render_shadow_map (idle: nothing drawn)");
    both(&h, fx, call_trigger, (void *)"explosion", "sbfx_trigger");
    double dt = 0.5;
    both(&h, fx, call_update, &dt, "sbfx_update");
    both(&h, fx, call_shadow_map, sun, "sbfx_render_shadow_map (live particles)");
    sbfx_counters c;
    sbfx_stats(fx[1], &c);
    CHECK(c.shadow_passes == 1, "%d shadow passes with live particles", c.shadow_passes);
    static float maps[2][64 * 64 * 4];
    host_state(&h, false);
    for (int i = 0; i < 2; i++) CHECK(sbfx_read_shadow_map(fx[i], maps[i], 64 * 64 * 4) == SBFX_OK);
    int map_differ = 0, first_differ = -1;
    for (int i = 0; i < 64 * 64 * 4; i++)
        if (maps[0][i] != maps[1][i] && map_differ++ == 0) first_differ = i;
    CHECK(map_differ == 0, "%d values of the map depend on the host's GL state (first: texel %d, %g vs %g)",
          map_differ, first_differ / 4, first_differ >= 0 ? maps[0][first_differ] : 0.0,
          first_differ >= 0 ? maps[1][first_differ] : 0.0);
    snap_before(&h);
    sbfx_shadow_map untouched;
    CHECK(sbfx_render_shadow_map(fx[1], (const float[3]){0, 0, 0}, &untouched) == SBFX_ERR_INVALID_ARGUMENT);
    snap_after(&h, "sbfx_render_shadow_map (zero direction)");
    dt = 10.0;
    for (int i = 0; i < 40; i++) both(&h, fx, call_update, &dt, "sbfx_update");
    both(&h, fx, call_shadow_map, sun, "sbfx_render_shadow_map (particles gone: cleared once)");
    host_state(&h, false);
    sbfx_destroy(fx[0]);
    snap_before(&h);
    sbfx_destroy(fx[1]);
    snap_after(&h, "sbfx_destroy with a shadow map");
    fixture_close(&h.gl);
}

/* ---- the snapshot can fail -------------------------------------------------------------------- */

typedef struct mutation {
    const char *entry;
    void (*apply)(const host *h);
} mutation;

static void m_sampler_far_unit(const host *h) { glBindSampler((GLuint)h->units - 1, 0); }
static void m_texture_3d(const host *h)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)h->units - 2);
    glBindTexture(GL_TEXTURE_3D, 0);
    glActiveTexture(GL_TEXTURE7);
}
static void m_blend_color(const host *h) { (void)h, glBlendColor(1, 1, 1, 1); }
static void m_skip_rows(const host *h) { (void)h, glPixelStorei(GL_UNPACK_SKIP_ROWS, 9); }
static void m_divisor(const host *h) { (void)h, glVertexAttribDivisor(2, 9); }
static void m_depth_range(const host *h) { (void)h, glDepthRangef(0.0f, 1.0f); }
static void m_dither(const host *h) { (void)h, glEnable(GL_DITHER); }
static void m_read_fbo(const host *h) { glBindFramebuffer(GL_READ_FRAMEBUFFER, h->draw_fbo); }
static void m_unpack_buffer(const host *h) { (void)h, glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0); }
static void m_stencil_back(const host *h) { (void)h, glStencilFuncSeparate(GL_BACK, GL_LESS, 5, 0xf0); }
static void m_clip(const host *h)
{
    if (h->clip_control) h->clip_control(GL_LOWER_LEFT_EXT, GL_NEGATIVE_ONE_TO_ONE_EXT);
    else glEnable(GL_DITHER);
}

CHECK_TEST(snapshot_detects_each_kind_of_change)
{
    host h;
    host_open(&h);
    const mutation mutations[] = {
        {"unit 47 sampler binding", m_sampler_far_unit}, {"unit 46 3D binding", m_texture_3d},
        {"GL_BLEND_COLOR", m_blend_color}, {"pixel store 0x0cf3", m_skip_rows},
        {"attribute 2 divisor", m_divisor}, {"GL_DEPTH_RANGE", m_depth_range}, {"GL_DITHER", m_dither},
        {"GL_READ_FRAMEBUFFER_BINDING", m_read_fbo}, {"GL_PIXEL_UNPACK_BUFFER_BINDING", m_unpack_buffer},
        {"stencil state 0x8800", m_stencil_back}, {"GL_CLIP_DEPTH_MODE_EXT", m_clip},
    };
    for (size_t i = 0; i < ARRAY_SIZE(mutations); i++) {
        snap_before(&h);
        mutations[i].apply(&h);
        snapshot_take(&h.after, h.clip_control != NULL);
        if (h.desktop) snap_desktop(&h.after, h.compat);
        char first[64];
        int differ = snapshot_diff(&h.before, &h.after, "deliberate change", first, sizeof(first));
        const char *want = mutations[i].entry;
        char unit_name[64];
        if (strncmp(want, "unit 4", 6) == 0) { /* named for the last units this context has */
            snprintf(unit_name, sizeof(unit_name), "unit %d %s", strcmp(want + 8, "sampler binding") == 0 ? h.units - 1 : h.units - 2,
                     want + 8);
            want = unit_name;
        }
        if (!h.clip_control && mutations[i].apply == m_clip) want = "GL_DITHER";
        CHECK(differ == 1 && strcmp(first, want) == 0, "change of %s: %d entries differ, first %s", want, differ, first);
    }
    fixture_close(&h.gl);
}

/* ---- host textures, the host's program, rasterizer discard ------------------------------------ */

static void texture_params(GLuint texture, GLint out[14])
{
    static const GLenum names[] = {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER, GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T,
                                   GL_TEXTURE_WRAP_R, GL_TEXTURE_COMPARE_MODE, GL_TEXTURE_COMPARE_FUNC,
                                   GL_TEXTURE_BASE_LEVEL, GL_TEXTURE_MAX_LEVEL, GL_TEXTURE_SWIZZLE_R,
                                   GL_TEXTURE_SWIZZLE_G, GL_TEXTURE_SWIZZLE_B, GL_TEXTURE_SWIZZLE_A,
                                   GL_TEXTURE_MIN_LOD};
    glBindTexture(GL_TEXTURE_2D, texture);
    for (int i = 0; i < 14; i++) glGetTexParameteriv(GL_TEXTURE_2D, names[i], &out[i]);
    glBindTexture(GL_TEXTURE_2D, 0);
}

CHECK_TEST(host_texture_parameters_unchanged)
{
    host h;
    host_open(&h);
    for (size_t c = 0; c < 2; c++) { /* the explosion, then every post effect (which reads colour too) */
        host_state(&h, false);
        sbfx *fx = case_module(&h, &cases[c]);
        sbfx_trigger(fx, "explosion", (const float[3]){0, 0, 0});
        sbfx_update(fx, 0.3);
        for (int hostile = 0; hostile < 2; hostile++) {
            draw_scene(&h, 0.3);
            host_texture_params(&h, hostile);
            GLint before[2][14], after[2][14];
            texture_params(h.scene.depth_texture, before[0]);
            texture_params(h.scene.color_texture, before[1]);
            sbfx_frame frame = h.gl.frame;
            frame.out_framebuffer = h.out_fbo[0];
            CHECK(sbfx_render(fx, &frame) == SBFX_OK, "%s", sbfx_last_error(fx));
            texture_params(h.scene.depth_texture, after[0]);
            texture_params(h.scene.color_texture, after[1]);
            CHECK(memcmp(before, after, sizeof(before)) == 0, "%s: a host texture parameter changed (%s set-up)",
                  cases[c].name, hostile ? "shadow-map" : "plain");
        }
        sbfx_destroy(fx);
    }
    fixture_close(&h.gl);
}

/* A host that deleted its current program: the program is gone once sbfx used its own, so it
 * cannot come back; sbfx must not raise GL_INVALID_VALUE trying (ImGui #6220). */
CHECK_TEST(host_program_deleted_while_current)
{
    host h;
    host_open(&h);
    sbfx *fx = case_module(&h, &cases[0]);
    sbfx_trigger(fx, "explosion", (const float[3]){0, 0, 0});
    sbfx_update(fx, 0.3);
    draw_scene(&h, 0.3);
    host_state(&h, true);
    glDeleteProgram(h.program);
    while (glGetError() != GL_NO_ERROR) {
    }
    CHECK(sbfx_render(fx, &h.gl.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    GLenum e = glGetError();
    CHECK(e == GL_NO_ERROR, "GL error 0x%04x after rendering with a deleted host program", e);
    GLint current = -1;
    glGetIntegerv(GL_CURRENT_PROGRAM, &current);
    CHECK(current == 0, "current program %d", current);
    sbfx_destroy(fx);
    fixture_close(&h.gl);
}

/* A host that left rasterizer discard on still gets its effects drawn, and discard back on. */
CHECK_TEST(rasterizer_discard_on)
{
    host h;
    host_open(&h);
    sbfx *fx[2] = {case_module(&h, &cases[0]), case_module(&h, &cases[0])};
    for (int i = 0; i < 2; i++) {
        sbfx_trigger(fx[i], "explosion", (const float[3]){0, 0, 0});
        sbfx_update(fx[i], 0.3);
    }
    draw_scene(&h, 0.3);
    sbfx_frame frame = h.gl.frame;
    frame.out_framebuffer = h.out_fbo[0];
    CHECK(sbfx_render(fx[0], &frame) == SBFX_OK);
    frame.out_framebuffer = h.out_fbo[1];
    glEnable(GL_RASTERIZER_DISCARD);
    CHECK(sbfx_render(fx[1], &frame) == SBFX_OK);
    CHECK(glIsEnabled(GL_RASTERIZER_DISCARD), "rasterizer discard was switched off");
    static uint8_t out[2][W * H * 4];
    read_output(&h, 0, out[0]);
    read_output(&h, 1, out[1]);
    CHECK(memcmp(out[0], out[1], sizeof(out[0])) == 0, "rasterizer discard changed sbfx's picture");
    sbfx_destroy(fx[0]);
    sbfx_destroy(fx[1]);
    fixture_close(&h.gl);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
