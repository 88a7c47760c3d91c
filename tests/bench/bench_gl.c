/* GL side of the accuracy benchmark: see bench_gl.h. */
#include "bench_fragments.h"
#include "bench_gl.h"

#include <EGL/egl.h>
#include <GLES2/gl2ext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---- timer query (EXT_disjoint_timer_query) -------------------------------------------- */

static PFNGLGENQUERIESEXTPROC gen_queries;
static PFNGLDELETEQUERIESEXTPROC delete_queries;
static PFNGLBEGINQUERYEXTPROC begin_query;
static PFNGLENDQUERYEXTPROC end_query;
static PFNGLGETQUERYOBJECTUI64VEXTPROC query_result_u64;

static bool has_gl_extension(const char *name)
{
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; i++) {
        const char *e = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (e && strcmp(e, name) == 0) return true;
    }
    return false;
}

void bench_timer_init(bench_timer *t)
{
    memset(t, 0, sizeof(*t));
    if (!has_gl_extension("GL_EXT_disjoint_timer_query")) return;
    gen_queries = (PFNGLGENQUERIESEXTPROC)eglGetProcAddress("glGenQueriesEXT");
    delete_queries = (PFNGLDELETEQUERIESEXTPROC)eglGetProcAddress("glDeleteQueriesEXT");
    begin_query = (PFNGLBEGINQUERYEXTPROC)eglGetProcAddress("glBeginQueryEXT");
    end_query = (PFNGLENDQUERYEXTPROC)eglGetProcAddress("glEndQueryEXT");
    query_result_u64 = (PFNGLGETQUERYOBJECTUI64VEXTPROC)eglGetProcAddress("glGetQueryObjectui64vEXT");
    if (!gen_queries || !delete_queries || !begin_query || !end_query || !query_result_u64) return;
    gen_queries(1, &t->query);
    t->has_query = t->query != 0;
}

static void delete_segment_queries(void);

void bench_timer_destroy(bench_timer *t)
{
    if (t->has_query) delete_queries(1, &t->query);
    if (t->has_query) delete_segment_queries();
    memset(t, 0, sizeof(*t));
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* The query's result in ms, or NAN when the GPU reports a disjoint event (the time is void). */
static double query_ms(const bench_timer *t)
{
    GLuint64 ns = 0;
    query_result_u64(t->query, GL_QUERY_RESULT_EXT, &ns);
    GLint disjoint = 0;
    glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
    return disjoint ? NAN : (double)ns / 1e6;
}

/* Starts a measurement: nothing of earlier work may be inside it. */
static double begin_sample(const bench_timer *t)
{
    glFinish();
    GLint disjoint = 0;
    glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint); /* reading it clears the flag */
    double start = now_ms();
    if (t->has_query) begin_query(GL_TIME_ELAPSED_EXT, t->query);
    return start;
}

static bench_sample end_sample(const bench_timer *t, double start)
{
    if (t->has_query) end_query(GL_TIME_ELAPSED_EXT);
    glFinish();
    bench_sample s = {NAN, now_ms() - start};
    if (t->has_query) s.gpu_ms = query_ms(t);
    return s;
}

bench_sample bench_time_call(bench_timer *t, void (*fn)(void *), void *user)
{
    double start = begin_sample(t);
    fn(user);
    return end_sample(t, start);
}

/* ---- the particle pass, through the linker's --wrap ----------------------------------- */

void __real_glBindFramebuffer(GLenum target, GLuint framebuffer);
void __real_glDrawArraysInstanced(GLenum mode, GLint first, GLsizei count, GLsizei instances);
void __real_glDrawArrays(GLenum mode, GLint first, GLsizei count);
void __wrap_glBindFramebuffer(GLenum target, GLuint framebuffer);
void __wrap_glDrawArraysInstanced(GLenum mode, GLint first, GLsizei count, GLsizei instances);
void __wrap_glDrawArrays(GLenum mode, GLint first, GLsizei count);

#define MAX_SEGMENTS 16

/* While armed, every draw-framebuffer bind closes the running segment and opens the next; each
 * segment gets its own timer query. The particle pass is the segment with instanced draws of
 * particles (the passes over the screen's tiles draw instanced rectangles). */
static struct {
    bench_timer *timer;
    GLuint queries[MAX_SEGMENTS];
    bool armed, active;
    int segments;
    double start;
    bench_sample wall[MAX_SEGMENTS];
    int instanced[MAX_SEGMENTS];
} pass;

static void segment_end(void)
{
    if (!pass.active) return;
    int k = pass.segments - 1;
    if (pass.timer->has_query) end_query(GL_TIME_ELAPSED_EXT);
    glFinish();
    pass.wall[k].wall_ms = now_ms() - pass.start;
    pass.active = false;
}

static void segment_begin(void)
{
    if (pass.segments == MAX_SEGMENTS) return;
    int k = pass.segments++;
    pass.instanced[k] = 0;
    glFinish();
    pass.start = now_ms();
    if (pass.timer->has_query) begin_query(GL_TIME_ELAPSED_EXT, pass.queries[k]);
    pass.active = true;
}

void __wrap_glBindFramebuffer(GLenum target, GLuint framebuffer)
{
    bool draw = target == GL_FRAMEBUFFER || target == GL_DRAW_FRAMEBUFFER;
    if (pass.armed && draw) segment_end();
    __real_glBindFramebuffer(target, framebuffer);
    if (pass.armed && draw) segment_begin();
}

/* The current program draws particles (particle.vert's instance attribute). */
static bool drawing_particles(void)
{
    GLint program = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    return program && glGetAttribLocation((GLuint)program, "a_center_radius") >= 0;
}

void __wrap_glDrawArraysInstanced(GLenum mode, GLint first, GLsizei count, GLsizei instances)
{
    if (pass.active && drawing_particles()) pass.instanced[pass.segments - 1]++;
    __real_glDrawArraysInstanced(mode, first, count, instances);
    bench_fragments_draw(mode, first, count, instances);
}

void __wrap_glDrawArrays(GLenum mode, GLint first, GLsizei count)
{
    __real_glDrawArrays(mode, first, count);
    bench_fragments_draw(mode, first, count, 0);
}

static void delete_segment_queries(void)
{
    if (pass.queries[0]) delete_queries(MAX_SEGMENTS, pass.queries);
    memset(pass.queries, 0, sizeof(pass.queries));
}

/* The one segment with instanced draws, or -1 if there is not exactly one. */
static int particle_segment(void)
{
    int found = -1;
    for (int k = 0; k < pass.segments; k++) {
        if (!pass.instanced[k]) continue;
        if (found >= 0) return -1;
        found = k;
    }
    return found;
}

bool bench_time_particle_pass(bench_timer *t, void (*fn)(void *), void *user, bench_sample *out)
{
    if (!pass.queries[0] && t->has_query) gen_queries(MAX_SEGMENTS, pass.queries);
    pass.timer = t;
    pass.armed = true;
    pass.active = false;
    pass.segments = 0;
    fn(user);
    segment_end();
    pass.armed = false;
    int k = particle_segment();
    *out = (bench_sample){NAN, NAN};
    if (k < 0) return false;
    out->wall_ms = pass.wall[k].wall_ms;
    if (t->has_query) {
        GLuint64 ns = 0;
        query_result_u64(pass.queries[k], GL_QUERY_RESULT_EXT, &ns);
        GLint disjoint = 0;
        glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
        out->gpu_ms = disjoint ? NAN : (double)ns / 1e6;
    }
    return true;
}

/* ---- targets and read-backs ----------------------------------------------------------- */

int bench_target_create(bench_target *t, int width, int height)
{
    memset(t, 0, sizeof(*t));
    t->width = width;
    t->height = height;
    glGenRenderbuffers(1, &t->renderbuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, t->renderbuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glGenFramebuffers(1, &t->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->renderbuffer);
    bool ok = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return ok ? 0 : -1;
}

void bench_target_destroy(bench_target *t)
{
    glDeleteFramebuffers(1, &t->fbo);
    glDeleteRenderbuffers(1, &t->renderbuffer);
    memset(t, 0, sizeof(*t));
}

void bench_target_fill_from(const bench_target *t, GLuint from)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, from);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t->fbo);
    glBlitFramebuffer(0, 0, t->width, t->height, 0, 0, t->width, t->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void bench_read_rgba8(GLuint fbo, int width, int height, uint8_t *out)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, out);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

static const char depth_vs[] =
    "#version 300 es\n"
    "void main() {\n"
    "    vec2 c = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
    "    gl_Position = vec4(c * 2.0 - 1.0, 0.0, 1.0);\n"
    "}\n";
static const char depth_fs[] =
    "#version 300 es\n"
    "precision highp float;\n"
    "precision highp sampler2D;\n"
    "uniform sampler2D u_depth;\n"
    "out vec4 o;\n"
    "void main() { o = vec4(texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r, 0.0, 0.0, 1.0); }\n";

static GLuint compile(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        glDeleteShader(s);
        return 0;
    }
    return s;
}

static GLuint depth_program(void)
{
    GLuint vs = compile(GL_VERTEX_SHADER, depth_vs), fs = compile(GL_FRAGMENT_SHADER, depth_fs);
    GLuint p = 0;
    if (vs && fs) {
        p = glCreateProgram();
        glAttachShader(p, vs);
        glAttachShader(p, fs);
        glLinkProgram(p);
        GLint ok = 0;
        glGetProgramiv(p, GL_LINK_STATUS, &ok);
        if (!ok) glDeleteProgram(p), p = 0;
    }
    glDeleteShader(vs);
    glDeleteShader(fs);
    return p;
}

/* Draws the depth texture's red channel into an RGBA32F texture of the same size. */
static int draw_depth(GLuint program, GLuint depth_texture, GLuint fbo, int width, int height)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) return -1;
    glViewport(0, 0, width, height);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(program);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, depth_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glUniform1i(glGetUniformLocation(program, "u_depth"), 0);
    GLuint vao = 0;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    return 0;
}

int bench_read_depth(GLuint depth_texture, int width, int height, float *out, char *err, size_t n)
{
    if (!has_gl_extension("GL_EXT_color_buffer_float")) {
        snprintf(err, n, "reading depth back needs GL_EXT_color_buffer_float");
        return -1;
    }
    GLuint program = depth_program();
    if (!program) {
        snprintf(err, n, "the depth read-back shader failed to build");
        return -1;
    }
    GLuint tex = 0, fbo = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, width, height);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    int rc = draw_depth(program, depth_texture, fbo, width, height);
    float *rgba = rc == 0 ? malloc((size_t)width * height * 4 * sizeof(float)) : NULL;
    if (rgba) {
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rgba);
        for (size_t i = 0; i < (size_t)width * height; i++) out[i] = rgba[4 * i];
        free(rgba);
    } else {
        snprintf(err, n, "the RGBA32F depth read-back target is incomplete or out of memory");
        rc = -1;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    glDeleteProgram(program);
    return glGetError() == GL_NO_ERROR ? rc : -1;
}

const char *bench_gl_renderer(void)
{
    const char *s = (const char *)glGetString(GL_RENDERER);
    return s ? s : "(unknown renderer)";
}

const char *bench_gl_version(void)
{
    const char *s = (const char *)glGetString(GL_VERSION);
    return s ? s : "(unknown version)";
}
