/* Fragment counts of the module's programs: see bench_fragments.h. */
#include "bench_fragments.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SOURCES 64 /* counting programs, one per vertex shader source: every example scene's in one run */

typedef struct counting_program {
    uint64_t hash; /* of the vertex shader's source */
    GLuint program;
} counting_program;

/* A tally slot's target: the draws of one program at one viewport size, added up. */
typedef struct slot_target {
    GLuint fbo, renderbuffer;
    int width, height;
    bool dirty;     /* holds counts not read back */
    GLuint counter; /* the counting program of the slot's program */
} slot_target;

static struct {
    bench_fragment_tally *tally;
    counting_program programs[SOURCES];
    int program_count;
    slot_target slots[BENCH_FRAGMENT_DRAWS];
    float *pixels;
    size_t pixel_capacity;
} fc;

static const char count_fs[] = "#version 300 es\nprecision mediump float;\nout vec4 o_count;\n"
                               "void main() { o_count = vec4(1.0); }\n";

static uint64_t fnv1a(const char *s)
{
    uint64_t h = 1469598103934665603ull;
    for (; *s; s++) h = (h ^ (uint8_t)*s) * 1099511628211ull;
    return h;
}

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

static GLuint link(const char *vs_text)
{
    GLuint vs = compile(GL_VERTEX_SHADER, vs_text), fs = compile(GL_FRAGMENT_SHADER, count_fs);
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
    return p;
}

/* The source of the vertex shader attached to `program` (malloc'd), or NULL. */
static char *vertex_source(GLuint program)
{
    GLuint shaders[4];
    GLsizei n = 0;
    glGetAttachedShaders(program, 4, &n, shaders);
    for (GLsizei i = 0; i < n; i++) {
        GLint type = 0, length = 0;
        glGetShaderiv(shaders[i], GL_SHADER_TYPE, &type);
        if (type != GL_VERTEX_SHADER) continue;
        glGetShaderiv(shaders[i], GL_SHADER_SOURCE_LENGTH, &length);
        char *text = length > 0 ? malloc((size_t)length) : NULL;
        if (text) glGetShaderSource(shaders[i], length, NULL, text);
        return text;
    }
    return NULL;
}

/* The counting program for `program`'s vertex shader, made once per source. */
static GLuint counting_program_for(GLuint program)
{
    char *source = vertex_source(program);
    if (!source) {
        fprintf(stderr, "bench: fragment count: program %u has no vertex shader source\n", program);
        return 0;
    }
    uint64_t h = fnv1a(source);
    GLuint found = 0;
    for (int i = 0; i < fc.program_count && !found; i++)
        if (fc.programs[i].hash == h) found = fc.programs[i].program;
    if (!found && fc.program_count == SOURCES)
        fprintf(stderr, "bench: fragment count: more than %d vertex shader sources (SOURCES)\n", SOURCES);
    else if (!found && (found = link(source)))
        fc.programs[fc.program_count++] = (counting_program){h, found};
    free(source);
    return found;
}

/* One uniform (location from in `from`, to in the current program) copied, by its type. */
static void copy_uniform(GLuint from, GLint src, GLint dst, GLenum type)
{
    GLfloat f[16];
    GLint i[4];
    switch (type) {
    case GL_FLOAT: glGetUniformfv(from, src, f), glUniform1fv(dst, 1, f); break;
    case GL_FLOAT_VEC2: glGetUniformfv(from, src, f), glUniform2fv(dst, 1, f); break;
    case GL_FLOAT_VEC3: glGetUniformfv(from, src, f), glUniform3fv(dst, 1, f); break;
    case GL_FLOAT_VEC4: glGetUniformfv(from, src, f), glUniform4fv(dst, 1, f); break;
    case GL_FLOAT_MAT4: glGetUniformfv(from, src, f), glUniformMatrix4fv(dst, 1, GL_FALSE, f); break;
    case GL_INT: case GL_BOOL: case GL_SAMPLER_2D: glGetUniformiv(from, src, i), glUniform1iv(dst, 1, i); break;
    case GL_INT_VEC2: glGetUniformiv(from, src, i), glUniform2iv(dst, 1, i); break;
    default: fprintf(stderr, "bench: fragment count: vertex uniform type 0x%04x not copied\n", type);
    }
}

/* The vertex stage's uniforms (the counting program's, all of them) from the module's program. */
static void copy_uniforms(GLuint from, GLuint to)
{
    GLint n = 0;
    glGetProgramiv(to, GL_ACTIVE_UNIFORMS, &n);
    for (GLint u = 0; u < n; u++) {
        char name[128], element[160];
        GLint size = 0;
        GLenum type = 0;
        glGetActiveUniform(to, (GLuint)u, sizeof(name), NULL, &size, &type, name);
        char *bracket = strstr(name, "[0]");
        if (bracket) *bracket = '\0';
        for (GLint e = 0; e < size; e++) {
            if (size > 1) snprintf(element, sizeof(element), "%s[%d]", name, e);
            else snprintf(element, sizeof(element), "%s", name);
            GLint src = glGetUniformLocation(from, element), dst = glGetUniformLocation(to, element);
            if (src >= 0 && dst >= 0) copy_uniform(from, src, dst, type);
        }
    }
}

static double read_count(slot_target *s)
{
    size_t n = (size_t)s->width * s->height * 4;
    if (n > fc.pixel_capacity) {
        free(fc.pixels);
        fc.pixels = malloc(n * sizeof(float));
        fc.pixel_capacity = fc.pixels ? n : 0;
        if (!fc.pixels) return 0.0;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    glReadPixels(0, 0, s->width, s->height, GL_RGBA, GL_FLOAT, fc.pixels);
    double sum = 0.0;
    for (size_t i = 0; i < n; i += 4) sum += fc.pixels[i];
    s->dirty = false;
    return sum;
}

/* Slot k's target at w x h (what it held read back into the tally first), cleared. */
static bool slot_ready(int k, int w, int h)
{
    slot_target *s = &fc.slots[k];
    if (s->dirty && (s->width != w || s->height != h)) fc.tally->fragments[k] += read_count(s);
    if (!s->fbo) glGenFramebuffers(1, &s->fbo), glGenRenderbuffers(1, &s->renderbuffer);
    if (s->width != w || s->height != h) {
        glBindRenderbuffer(GL_RENDERBUFFER, s->renderbuffer);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA16F, w, h);
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s->renderbuffer);
        GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            fprintf(stderr, "bench: fragment count target %dx%d RGBA16F: status 0x%04x\n", w, h, status);
            s->width = s->height = 0;
            return false;
        }
        s->width = w, s->height = h;
    }
    if (!s->dirty) {
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
        glClearColor(0, 0, 0, 0);
        glClear(GL_COLOR_BUFFER_BIT);
    }
    return true;
}

void bench_fragments_begin(bench_fragment_tally *tally)
{
    memset(tally, 0, sizeof(*tally));
    for (int k = 0; k < BENCH_FRAGMENT_DRAWS; k++) fc.slots[k].dirty = false;
    fc.tally = tally;
}

/* What the counting draw changes, put back afterwards. */
typedef struct saved_state {
    GLint program, fbo, read_fbo, viewport[4], src_rgb, dst_rgb, src_a, dst_a, eq_rgb, eq_a, renderbuffer;
    GLboolean blend, mask[4];
    GLfloat clear[4];
} saved_state;

static void save(saved_state *s)
{
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->fbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fbo);
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
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_fbo);
    glBindRenderbuffer(GL_RENDERBUFFER, (GLuint)s->renderbuffer);
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    glUseProgram((GLuint)s->program);
    glBlendFuncSeparate((GLenum)s->src_rgb, (GLenum)s->dst_rgb, (GLenum)s->src_a, (GLenum)s->dst_a);
    glBlendEquationSeparate((GLenum)s->eq_rgb, (GLenum)s->eq_a);
    if (s->blend) glEnable(GL_BLEND);
    else glDisable(GL_BLEND);
    glColorMask(s->mask[0], s->mask[1], s->mask[2], s->mask[3]);
    glClearColor(s->clear[0], s->clear[1], s->clear[2], s->clear[3]);
}

/* A draw whose depth test masks it shades only where the test passes: its counting draw is
 * tested against the same depth, attached to the counting target. Mixed resolution's
 * refinement (render/refine.c) masks with a depth texture: what passes is the refinement's,
 * counted apart too (tally.masked); early termination (render/terminate.c) with a depth
 * renderbuffer: what passes is the particle pass's own. The depth function and mask stay as
 * the draw had them; a pass that writes depth tests ALWAYS and every fragment counts. */
typedef struct draw_mask {
    GLenum type; /* GL_TEXTURE, GL_RENDERBUFFER or GL_NONE: no mask */
    GLuint name;
} draw_mask;

static draw_mask depth_mask_of_draw(void)
{
    draw_mask none = {GL_NONE, 0};
    GLboolean writes = GL_TRUE;
    glGetBooleanv(GL_DEPTH_WRITEMASK, &writes);
    GLint func = GL_ALWAYS, fbo = 0, type = GL_NONE, name = 0;
    glGetIntegerv(GL_DEPTH_FUNC, &func);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    if (!glIsEnabled(GL_DEPTH_TEST) || writes || func == GL_ALWAYS || fbo == 0) return none;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type != GL_TEXTURE && type != GL_RENDERBUFFER) return none;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
    return (draw_mask){(GLenum)type, (GLuint)name};
}

static void attach_mask(draw_mask m, bool on)
{
    if (m.type == GL_TEXTURE) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, on ? m.name : 0, 0);
    if (m.type == GL_RENDERBUFFER) glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, on ? m.name : 0);
}

/* The tally's slot of the current program (a new one the first time), or -1 when full. */
static int slot_of(bench_fragment_tally *t, GLuint program)
{
    int k = 0;
    while (k < t->draws && t->program[k] != program) k++;
    if (k < t->draws) return k;
    if (k == BENCH_FRAGMENT_DRAWS) return -1;
    fc.slots[k].counter = counting_program_for(program);
    if (!fc.slots[k].counter) return -1;
    t->program[t->draws++] = program;
    return k;
}

void bench_fragments_draw(GLenum mode, GLint first, GLsizei count, GLsizei instances)
{
    bench_fragment_tally *t = fc.tally;
    if (!t || t->failed) return;
    saved_state s;
    save(&s);
    int w = s.viewport[2], h = s.viewport[3];
    draw_mask mask = depth_mask_of_draw(); /* of the module's framebuffer, before a slot is bound */
    int k = slot_of(t, (GLuint)s.program);
    if (k < 0 || !slot_ready(k, w, h)) {
        fprintf(stderr, "bench: fragment count: no counting program or target (%d programs, %dx%d)\n", t->draws, w, h);
        t->failed = true;
        restore(&s);
        return;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fc.slots[k].fbo);
    attach_mask(mask, true);
    glViewport(0, 0, w, h);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glUseProgram(fc.slots[k].counter);
    copy_uniforms((GLuint)s.program, fc.slots[k].counter);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glBlendEquation(GL_FUNC_ADD);
    fc.tally = NULL; /* the draw below goes through the wrapper too */
    if (instances > 0) glDrawArraysInstanced(mode, first, count, instances);
    else glDrawArrays(mode, first, count);
    fc.tally = t;
    fc.slots[k].dirty = true;
    attach_mask(mask, false);
    if (mask.type == GL_TEXTURE) {
        /* what passed the mask is the refinement's: counted apart as well (read back now) */
        double before = t->fragments[k];
        t->fragments[k] += read_count(&fc.slots[k]);
        t->masked[k] += t->fragments[k] - before;
        t->masked_fragments += t->fragments[k] - before;
        slot_ready(k, w, h);
    }
    restore(&s);
}

void bench_fragments_end(void)
{
    bench_fragment_tally *t = fc.tally;
    if (!t) return;
    GLint fbo = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &fbo);
    for (int k = 0; k < t->draws; k++)
        if (fc.slots[k].dirty) t->fragments[k] += read_count(&fc.slots[k]);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
    fc.tally = NULL;
}

void bench_fragments_destroy(void)
{
    for (int i = 0; i < fc.program_count; i++) glDeleteProgram(fc.programs[i].program);
    for (int k = 0; k < BENCH_FRAGMENT_DRAWS; k++)
        if (fc.slots[k].fbo) glDeleteFramebuffers(1, &fc.slots[k].fbo), glDeleteRenderbuffers(1, &fc.slots[k].renderbuffer);
    free(fc.pixels);
    memset(&fc, 0, sizeof(fc));
}
