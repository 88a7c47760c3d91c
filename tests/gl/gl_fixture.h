/* Shared set-up of the GL tests: a surfaceless GLES 3.0 context per (forked) test, a host
 * depth texture built from view distances, and an output framebuffer. Header-only. */
#ifndef SBFX_GL_FIXTURE_H
#define SBFX_GL_FIXTURE_H

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "check.h"
#include "egl/egl_headless.h"
#include "host/host_depth.h"
#include "internal.h"

typedef struct gl_fixture {
    struct egl_headless egl;
    GLuint depth_texture, out_texture, out_fbo;
    int width, height;
    sbfx_frame frame;
    int warnings;
    char last_warning[512];
} gl_fixture;

static gl_fixture *fixture_current;

static inline void fixture_log(sbfx_log_level level, const char *message, void *user)
{
    gl_fixture *f = user;
    if (level == SBFX_LOG_WARN && f) {
        f->warnings++;
        snprintf(f->last_warning, sizeof(f->last_warning), "%s", message);
    }
    if (getenv("SBFX_TEST_VERBOSE")) fprintf(stdout, "# sbfx: %s\n", message);
}

/* With SBFX_TEST_LOAD_DRIVER=1 (tests/run.sh sets it for Mesa, not for --gl-only's other
 * drivers), the harness's parent loads the EGL driver once before it forks the tests
 * (egl_headless_load_driver: Mesa then keeps its driver and LLVM loaded and leaves no thread):
 * every test's context starts without loading and relocating them again, an eighth of a GL
 * suite's time on llvmpipe. A driver that fails here is left to the tests, which say why. */
static void fixture_load_driver(void)
{
    const char *load = getenv("SBFX_TEST_LOAD_DRIVER");
    char err[512];
    if (load && strcmp(load, "1") == 0) (void)egl_headless_load_driver(err, sizeof(err));
}
/* The GL suites run their tests in batches (tests/check.h): a test's context and module then
 * reuse the memory the tests before it in the batch had, where a fork per test touched it fresh. */
__attribute__((constructor)) static void fixture_register_load_driver(void)
{
    check_before_forks = fixture_load_driver;
    check_batch = 1;
}

/* Opens the context; skips the test (with the reason) when no EGL/GLES3 is available. */
static inline void fixture_open(gl_fixture *f, int width, int height)
{
    char err[512];
    memset(f, 0, sizeof(*f));
    if (egl_headless_open_api(&f->egl, egl_headless_test_api(), err, sizeof(err)) != 0)
        CHECK_SKIP("no headless %s context: %s", f->egl.api == EGL_HEADLESS_GLES3 ? "GLES 3.0" : "desktop OpenGL", err);
    f->width = width;
    f->height = height;
    glGenTextures(1, &f->depth_texture);
    glBindTexture(GL_TEXTURE_2D, f->depth_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glGenTextures(1, &f->out_texture);
    glBindTexture(GL_TEXTURE_2D, f->out_texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glGenFramebuffers(1, &f->out_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, f->out_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, f->out_texture, 0);
    CHECK(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    f->frame = (sbfx_frame){.scene_depth_texture = f->depth_texture, .out_framebuffer = f->out_fbo,
                            .width = width, .height = height};
    f->frame.view[0] = f->frame.view[5] = f->frame.view[10] = f->frame.view[15] = 1.0f;
    fixture_current = f;
}

/* An RGBA8 texture of width x height and a framebuffer drawing into it, as a host makes its
 * output; leaves the 2D texture and framebuffer bindings at 0. */
static inline void fixture_rgba8_target(int width, int height, GLuint *texture, GLuint *fbo)
{
    glGenTextures(1, texture);
    glBindTexture(GL_TEXTURE_2D, *texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glGenFramebuffers(1, fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, *fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, *texture, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
}

static inline void fixture_close(gl_fixture *f)
{
    glDeleteFramebuffers(1, &f->out_fbo);
    GLuint t[] = {f->depth_texture, f->out_texture};
    glDeleteTextures(2, t);
    egl_headless_close(&f->egl);
}

static inline sbfx *fixture_module(gl_fixture *f, sbfx_desc desc)
{
    desc.log = fixture_log;
    desc.log_user = f;
    sbfx *fx = NULL;
    sbfx_result r = sbfx_create(&desc, &fx);
    CHECK(r == SBFX_OK, "sbfx_create: %s", fx ? sbfx_last_error(fx) : sbfx_result_string(r));
    if (!fx) exit(1);
    return fx;
}

/* scenes/NAME.cfg, loaded (the test stops if it cannot be). */
static inline sbfx_scene *fixture_load_scene(const char *name)
{
    char path[256], err[512];
    snprintf(path, sizeof(path), "scenes/%s.cfg", name);
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_load(path, &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (!scene) exit(1);
    return scene;
}

static inline void fixture_projection(gl_fixture *f, float fov_y, float near, float far)
{
    sbfx_perspective(f->frame.projection, fov_y, (float)f->width / f->height, near, far);
}

/* Fills the host depth texture (DEPTH_COMPONENT32F) so that every pixel linearises to the
 * view distance given by distance_at(x, y) under the frame's projection and clip depth mode;
 * +inf or beyond a finite far plane stays at the clear value (1, or 0 reversed). */
static inline void fixture_depth(gl_fixture *f, double (*distance_at)(int x, int y, void *), void *user)
{
    float *d = calloc((size_t)f->width * f->height, sizeof(float));
    for (int y = 0; y < f->height; y++)
        for (int x = 0; x < f->width; x++) d[y * f->width + x] = sbfx_window_depth(&f->frame, distance_at(x, y, user));
    glBindTexture(GL_TEXTURE_2D, f->depth_texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, f->width, f->height, 0,
                 GL_DEPTH_COMPONENT, GL_FLOAT, d);
    free(d);
}

static inline double depth_far_everywhere(int x, int y, void *user)
{
    (void)x, (void)y, (void)user;
    return INFINITY;
}

/* The pixel's ray (z = -1) in the CPU reference's terms, at the centre of target pixel (x, y). */
/* The common set-up: a context, a 1 rad / 0.1 m / 100 m projection, nothing opaque. */
static inline void fixture_open_far(gl_fixture *f, int width, int height)
{
    fixture_open(f, width, height);
    fixture_projection(f, 1.0f, 0.1f, 100.0f);
    fixture_depth(f, depth_far_everywhere, NULL);
}

static inline void fixture_ray(const gl_fixture *f, const sbfx_frame *frame, int tw, int th, int x, int y,
                        double ray[3])
{
    (void)f;
    const float *p = frame->projection;
    double ndc_x = (x + 0.5) / tw * 2.0 - 1.0, ndc_y = (y + 0.5) / th * 2.0 - 1.0;
    ray[0] = (ndc_x + p[8]) / p[0];
    ray[1] = (ndc_y + p[9]) / p[5];
    ray[2] = -1.0;
}

/* The near plane's distance under the frame's projection and clip depth mode. */
static inline double fixture_near(const sbfx_frame *frame)
{
    return sbfx_window_distance(frame, frame->projection[14] > 0.0f ? 1.0f : 0.0f);
}

/* The host's depth drawn as a plane at `distance` under the frame's projection and clip depth
 * mode (platform/host/host_depth.h), into a texture of `format`; the frame's depth texture. */
static inline bool fixture_draw_depth_plane(gl_fixture *f, double distance, GLenum format)
{
    bool zero_to_one = f->frame.clip_depth_mode == SBFX_CLIP_DEPTH_ZERO_TO_ONE;
    int rc = host_depth_plane(&f->depth_texture, f->width, f->height, format, f->frame.projection, zero_to_one, distance);
    f->frame.scene_depth_texture = f->depth_texture;
    return rc == 0;
}

/* The distance the GPU reads back for a requested one: the host's float window depth,
 * linearised (the host depth buffer's precision, not the shader's); INFINITY where nothing is. */
static inline double fixture_stored_distance(const sbfx_frame *frame, double z)
{
    return sbfx_window_distance(frame, sbfx_window_depth(frame, z));
}

/* Reads the particle target; returns a malloc'ed RGBA float array of its size (not a fixed 4 MB:
 * under ASan each such block is mapped, its shadow poisoned and unmapped again, some 600 000
 * page faults in one suite's reads). */
static inline float *fixture_read_target(sbfx *fx, int *w, int *h)
{
    size_t cap = (size_t)fx->gl->low_width * (size_t)fx->gl->low_height * 4u;
    if (cap < 4) cap = 4;
    float *rgba = malloc(cap * sizeof(float));
    CHECK(sbfx_read_particle_target(fx, rgba, cap, w, h) == SBFX_OK, "%s", sbfx_last_error(fx));
    return rgba;
}

/* Whether the current context offers the GL extension `name` (glGetStringi, as src/ asks). */
/* A program from two sources, as a host builds one (link status left to the caller's draw). */
static inline GLuint fixture_program(const char *vs, const char *fs)
{
    GLuint prog = glCreateProgram(), shaders[2] = {glCreateShader(GL_VERTEX_SHADER), glCreateShader(GL_FRAGMENT_SHADER)};
    const char *src[2] = {vs, fs};
    for (int i = 0; i < 2; i++) {
        glShaderSource(shaders[i], 1, &src[i], NULL);
        glCompileShader(shaders[i]);
        glAttachShader(prog, shaders[i]);
    }
    glLinkProgram(prog);
    glDeleteShader(shaders[0]);
    glDeleteShader(shaders[1]);
    return prog;
}

static inline bool fixture_has_extension(const char *name)
{
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++) {
        const char *ext = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (ext && strcmp(ext, name) == 0) return true;
    }
    return false;
}

/* Hides the GL extensions `names` (space-separated) from the contexts opened after this call, to
 * test a fallback: Mesa's MESA_EXTENSION_OVERRIDE ("-NAME ..."). Other drivers ignore that
 * variable: after opening, fixture_require_hidden() finds out. */
static inline void fixture_hide_extensions(const char *names)
{
    check_own_process(); /* Mesa reads the variable once, at a process's first context */
    char value[512] = "";
    size_t used = 0;
    char copy[512];
    snprintf(copy, sizeof(copy), "%s", names);
    for (char *save = NULL, *name = strtok_r(copy, " ", &save); name; name = strtok_r(NULL, " ", &save))
        used += (size_t)snprintf(value + used, used < sizeof(value) ? sizeof(value) - used : 0, "%s-%s",
                                 used ? " " : "", name);
    setenv("MESA_EXTENSION_OVERRIDE", value, 1);
}

/* On the current context: skips the running test, saying why, where one of the extensions that
 * fixture_hide_extensions() hid is still offered (the driver does not honour Mesa's variable),
 * as the fallback under test cannot be forced there. */
static inline void fixture_require_hidden(const char *names)
{
    char copy[512];
    snprintf(copy, sizeof(copy), "%s", names);
    for (char *save = NULL, *name = strtok_r(copy, " ", &save); name; name = strtok_r(NULL, " ", &save))
        if (fixture_has_extension(name))
            CHECK_SKIP("%s still offers %s with MESA_EXTENSION_OVERRIDE hiding it (only Mesa honours that "
                       "variable): the fallback cannot be forced on this driver",
                       (const char *)glGetString(GL_RENDERER), name);
}

/* Whether an 8-bit channel read back is the unsigned-normalised value v converted by the GL:
 * within one level of v * 255 (a clear to 0.5 reads 128 on Mesa, 127 on NVIDIA; both are
 * allowed, GLES 3.0 2.1.6.1 leaves the rounding to the implementation). */
static inline bool fixture_unorm8_is(int level, float v)
{
    return fabs(level - (double)v * 255.0) < 1.0;
}

static inline bool all_finite(const float *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i])) return false;
    return true;
}

#endif
