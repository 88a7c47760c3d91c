/* Fragment counts of the particle pass: see bench_fragments.h. */
#include "bench_fragments.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h" /* sbfx_shader_source: the module's own particle.vert */

static struct {
    bench_fragment_tally *tally;
    GLuint program, fbo, renderbuffer;
    GLint projection, near, pixel;
    int width, height;
    float *pixels;
} fc;

static const char count_fs[] = "#version 300 es\nprecision mediump float;\nout vec4 o_count;\n"
                               "void main() { o_count = vec4(1.0); }\n";

static GLuint compile(GLenum stage, const char *text)
{
    GLuint s = glCreateShader(stage);
    glShaderSource(s, 1, &text, NULL);
    glCompileShader(s);
    GLint ok = GL_FALSE;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetShaderInfoLog(s, sizeof(log), NULL, log);
        fprintf(stderr, "bench: fragment count shader: %s\n", log);
        glDeleteShader(s);
        return 0;
    }
    return s;
}

static bool ensure_program(void)
{
    if (fc.program) return true;
    const char *vs_text = sbfx_shader_source("particle.vert");
    GLuint vs = vs_text ? compile(GL_VERTEX_SHADER, vs_text) : 0, fs = compile(GL_FRAGMENT_SHADER, count_fs);
    GLuint p = vs && fs ? glCreateProgram() : 0;
    if (p) {
        glAttachShader(p, vs);
        glAttachShader(p, fs);
        glLinkProgram(p);
        GLint ok = GL_FALSE;
        glGetProgramiv(p, GL_LINK_STATUS, &ok);
        if (!ok) {
            char log[512] = "";
            glGetProgramInfoLog(p, sizeof(log), NULL, log);
            fprintf(stderr, "bench: fragment count program: %s\n", log);
            glDeleteProgram(p), p = 0;
        }
    }
    if (vs) glDeleteShader(vs);
    if (fs) glDeleteShader(fs);
    if (!p) return false;
    fc.program = p;
    fc.projection = glGetUniformLocation(p, "u_projection");
    fc.near = glGetUniformLocation(p, "u_near");
    fc.pixel = glGetUniformLocation(p, "u_pixel");
    return true;
}

static bool ensure_target(int w, int h)
{
    if (fc.fbo && fc.width == w && fc.height == h) return true;
    if (!fc.fbo) glGenFramebuffers(1, &fc.fbo), glGenRenderbuffers(1, &fc.renderbuffer);
    free(fc.pixels);
    fc.pixels = malloc((size_t)w * h * 4 * sizeof(float));
    if (!fc.pixels) return false;
    fc.width = w, fc.height = h;
    glBindRenderbuffer(GL_RENDERBUFFER, fc.renderbuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA16F, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, fc.fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, fc.renderbuffer);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        fprintf(stderr, "bench: fragment count target %dx%d RGBA16F: status 0x%04x\n", w, h, status);
    return status == GL_FRAMEBUFFER_COMPLETE;
}

void bench_fragments_begin(bench_fragment_tally *tally)
{
    memset(tally, 0, sizeof(*tally));
    fc.tally = tally;
}

void bench_fragments_end(void) { fc.tally = NULL; }

/* What the counting draw changes, put back afterwards. */
typedef struct saved_state {
    GLint program, fbo, viewport[4], src_rgb, dst_rgb, src_a, dst_a, eq_rgb, eq_a, renderbuffer;
    GLboolean blend, mask[4];
    GLfloat clear[4];
} saved_state;

static void save(saved_state *s)
{
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->fbo);
    glGetIntegerv(GL_RENDERBUFFER_BINDING, &s->renderbuffer);
    glGetIntegerv(GL_VIEWPORT, s->viewport);
    glGetIntegerv(GL_BLEND_SRC_RGB, &s->src_rgb), glGetIntegerv(GL_BLEND_DST_RGB, &s->dst_rgb);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &s->src_a), glGetIntegerv(GL_BLEND_DST_ALPHA, &s->dst_a);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &s->eq_rgb), glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &s->eq_a);
    s->blend = glIsEnabled(GL_BLEND);
    glGetBooleanv(GL_COLOR_WRITEMASK, s->mask);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, s->clear);
}

static void restore(const saved_state *s)
{
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)s->fbo);
    glBindRenderbuffer(GL_RENDERBUFFER, (GLuint)s->renderbuffer);
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    glUseProgram((GLuint)s->program);
    glBlendFuncSeparate((GLenum)s->src_rgb, (GLenum)s->dst_rgb, (GLenum)s->src_a, (GLenum)s->dst_a);
    glBlendEquationSeparate((GLenum)s->eq_rgb, (GLenum)s->eq_a);
    if (!s->blend) glDisable(GL_BLEND);
    glColorMask(s->mask[0], s->mask[1], s->mask[2], s->mask[3]);
    glClearColor(s->clear[0], s->clear[1], s->clear[2], s->clear[3]);
}

/* The particle program's vertex uniforms, copied to the counting program. */
static void copy_uniforms(GLuint from)
{
    float v[4] = {0};
    glGetUniformfv(from, glGetUniformLocation(from, "u_projection"), v);
    glUniform4fv(fc.projection, 1, v);
    glGetUniformfv(from, glGetUniformLocation(from, "u_near"), v);
    glUniform1f(fc.near, v[0]);
    glGetUniformfv(from, glGetUniformLocation(from, "u_pixel"), v);
    glUniform2fv(fc.pixel, 1, v);
}

static double count_pixels(int w, int h)
{
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, fc.pixels);
    double sum = 0.0;
    for (size_t i = 0; i < (size_t)w * h; i++) sum += fc.pixels[4 * i];
    return sum;
}

void bench_fragments_draw(GLenum mode, GLint first, GLsizei count, GLsizei instances)
{
    bench_fragment_tally *t = fc.tally;
    if (!t || t->failed) return;
    saved_state s;
    save(&s);
    int w = s.viewport[2], h = s.viewport[3];
    int k = 0;
    while (k < t->draws && t->program[k] != (GLuint)s.program) k++;
    if (k == BENCH_FRAGMENT_DRAWS || !ensure_program() || !ensure_target(w, h)) {
        fprintf(stderr, "bench: fragment count: no counting program or target (%d programs, %dx%d)\n", t->draws, w, h);
        t->failed = true;
        restore(&s);
        return;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fc.fbo);
    glViewport(0, 0, w, h);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glUseProgram(fc.program);
    copy_uniforms((GLuint)s.program);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glBlendEquation(GL_FUNC_ADD);
    fc.tally = NULL; /* the draw below goes through the wrapper too */
    glDrawArraysInstanced(mode, first, count, instances);
    fc.tally = t;
    if (k == t->draws) t->program[t->draws++] = (GLuint)s.program;
    t->fragments[k] += count_pixels(w, h);
    restore(&s);
}

void bench_fragments_destroy(void)
{
    if (fc.program) glDeleteProgram(fc.program);
    if (fc.fbo) glDeleteFramebuffers(1, &fc.fbo), glDeleteRenderbuffers(1, &fc.renderbuffer);
    free(fc.pixels);
    memset(&fc, 0, sizeof(fc));
}
