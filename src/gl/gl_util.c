/* Small GL helpers: error checks that say what failed, program building with defines. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "gl/gl.h"

static const char *gl_error_name(GLenum e)
{
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case 0x0507: return "GL_CONTEXT_LOST";
    default: return "unknown GL error";
    }
}

/* Drains the GL error queue; records the first error against `what`. */
bool sbfx_gl_check(sbfx *fx, const char *what)
{
    GLenum first = glGetError(), e = first;
    while (e != GL_NO_ERROR) e = glGetError();
    if (first == GL_NO_ERROR) return true;
    sbfx_fail(fx, SBFX_ERR_GL, "%s failed with %s (0x%04x)", what, gl_error_name(first), first);
    return false;
}

/* ---- the host's pending errors (issue 18) ---- */

#define GL_CONTEXT_LOST_CODE 0x0507 /* ES 3.2, GL 4.5, KHR_robustness */

static int error_kind(GLenum e)
{
    switch (e) {
    case GL_INVALID_ENUM: return 0;
    case GL_INVALID_VALUE: return 1;
    case GL_INVALID_OPERATION: return 2;
    case GL_INVALID_FRAMEBUFFER_OPERATION: return 3;
    case GL_OUT_OF_MEMORY: return 4;
    default: return 5;
    }
}

/* GL offers no call that posts an error, but a command that fails has no other effect
 * (except GL_OUT_OF_MEMORY): each of these fails with its error and changes nothing. */
static bool post_again(GLenum e)
{
    switch (e) {
    case GL_INVALID_ENUM: glEnable(GL_NONE); return true;
    case GL_INVALID_VALUE: glLineWidth(0.0f); return true;
    case GL_INVALID_OPERATION: glBeginQuery(GL_ANY_SAMPLES_PASSED, 0); return true;
    default: return false;
    }
}

void sbfx_gl_enter(sbfx *fx)
{
    sbfx_host_errors *h = &fx->gl->context.host_errors;
    h->count = 0;
    /* bounded: a lost context may answer GL_CONTEXT_LOST to every call */
    for (int i = 0; i < SBFX_HOST_ERRORS_MAX; i++) {
        GLenum e = glGetError();
        if (e == GL_NO_ERROR) break;
        bool seen = false;
        for (int k = 0; k < h->count; k++) seen = seen || h->code[k] == e;
        if (!seen) h->code[h->count++] = e;
        if (e == GL_CONTEXT_LOST_CODE) break;
    }
}

void sbfx_gl_leave(sbfx *fx, const char *entry)
{
    sbfx_host_errors *h = &fx->gl->context.host_errors;
    for (int k = 0; k < h->count; k++) {
        GLenum e = h->code[k];
        bool posted = post_again(e);
        unsigned bit = 1u << error_kind(e);
        if (h->logged & bit) continue;
        h->logged |= bit;
        sbfx_log(fx, posted ? SBFX_LOG_INFO : SBFX_LOG_WARN,
                 "%s: %s (0x%04x) was pending when it was called: the host's error, not sbfx's; %s "
                 "(logged once)", entry, gl_error_name(e), e,
                 posted ? "posted again on return" : "GL cannot post it again: it is dropped here");
    }
    h->count = 0;
}

bool sbfx_has_extension(const char *name)
{
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; i++) {
        const char *ext = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (ext && strcmp(ext, name) == 0) return true;
    }
    return false;
}

void sbfx_texture_params(GLenum target, GLenum filter, GLenum wrap)
{
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, (GLint)filter);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, (GLint)filter);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, (GLint)wrap);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, (GLint)wrap);
    if (target == GL_TEXTURE_3D) glTexParameteri(target, GL_TEXTURE_WRAP_R, (GLint)wrap);
}

/* A texture of the module: made, bound, its filters and wrap set, counted. */
GLuint sbfx_texture_create(sbfx *fx, GLenum target, GLenum filter, GLenum wrap)
{
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(target, tex);
    sbfx_texture_params(target, filter, wrap);
    fx->counters.textures++;
    return tex;
}

/* SBFX_INJECT_SHADER_FAILURE=WORD (tests): a stage whose defines contain WORD fails as a driver's
 * compiler would refuse it, so the tests can see what a failed build leaves behind (a reload
 * that needs a new variant: the old scene goes on, tests/gl/test_gl_reload.c). */
static bool injected_failure(const char *defines)
{
    const char *word = getenv("SBFX_INJECT_SHADER_FAILURE");
    return word && *word && defines && strstr(defines, word);
}

/* Compiles one stage: the embedded source with `defines` inserted after its #version line (and,
 * on a software rasteriser, mediump defined as highp: context.c). */
static GLuint compile_stage(sbfx *fx, GLenum stage, const char *name, const char *defines)
{
    const char *text = sbfx_shader_source(name);
    if (!text) {
        sbfx_fail(fx, SBFX_ERR_SHADER, "shader %s is not embedded in this build", name);
        return 0;
    }
    const char *body = strchr(text, '\n');
    body = body ? body + 1 : text;
    const char *precision = fx->gl->context.mediump_as_highp ? "#define mediump highp\n" : "";
    if (injected_failure(defines)) {
        sbfx_fail(fx, SBFX_ERR_SHADER, "compiling %s failed: SBFX_INJECT_SHADER_FAILURE names one of its defines "
                  "(%s)", name, getenv("SBFX_INJECT_SHADER_FAILURE"));
        return 0;
    }
    char filter[64] = "";
    const char *library = "";
    if (fx->gl->context.filter_bits > 0 && stage == GL_FRAGMENT_SHADER) { /* SBFX_FILTER_BITS (precision.c) */
        snprintf(filter, sizeof(filter), "#define FILTER_BITS %d\n#define FILTER_LIBRARY\n", fx->gl->context.filter_bits);
        library = sbfx_filter_library();
        if (!library) {
            sbfx_fail(fx, SBFX_ERR_SHADER, "shader filtered.frag is not embedded in this build");
            return 0;
        }
    }
    const char *parts[] = {"#version 300 es\n", precision, filter, library, defines ? defines : "", "#line 2\n", body};
    GLuint shader = glCreateShader(stage);
    if (!shader) {
        sbfx_gl_check(fx, "glCreateShader");
        return 0;
    }
    glShaderSource(shader, (GLsizei)ARRAY_SIZE(parts), parts, NULL);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        glGetShaderInfoLog(shader, sizeof(log), NULL, log);
        sbfx_fail(fx, SBFX_ERR_SHADER, "compiling %s (%s) failed: %s", name,
                  defines && *defines ? defines : "no defines", log);
        glDeleteShader(shader);
        return 0;
    }
    return shader;
}

/* "#define A\n#define B 2\n" -> "A B=2": a variant's name in one line. */
static void variant_name(const char *defines, char *out, size_t size)
{
    size_t n = 0;
    out[0] = '\0';
    for (const char *d = defines ? strstr(defines, "#define ") : NULL; d && n + 1 < size;
         d = strstr(d, "#define ")) {
        d += strlen("#define ");
        if (n > 0) out[n++] = ' ';
        bool value = false;
        for (; *d && *d != '\n' && n + 1 < size; d++) {
            bool space = *d == ' ';
            if (space && value) break;
            out[n++] = space ? '=' : *d;
            value = value || space;
        }
        out[n] = '\0';
    }
}

/* SBFX_SHADER_LOG set: the log (INFO) brackets each program build, so a driver's per-shader
 * statistics printed in between (Mesa's SHADER-DB lines) can be named after the variant. */
static bool shader_log_on(void)
{
    const char *v = getenv("SBFX_SHADER_LOG");
    return v && *v && strcmp(v, "0") != 0;
}

static GLuint build_program(sbfx *fx, const char *vert_name, const char *frag_name, const char *defines);

/* How a program is made: its stages' names, defines and precision (sbfx_hash64). */
static uint64_t program_key(const sbfx *fx, const char *vert_name, const char *frag_name, const char *defines)
{
    uint64_t key = sbfx_hash64(0, vert_name, strlen(vert_name) + 1);
    key = sbfx_hash64(key, frag_name, strlen(frag_name) + 1);
    key = sbfx_hash64(key, defines ? defines : "", defines ? strlen(defines) + 1 : 1);
    return sbfx_hash64(key, &fx->gl->context.mediump_as_highp, sizeof(fx->gl->context.mediump_as_highp));
}

static GLuint build_logged(sbfx *fx, const char *vert_name, const char *frag_name, const char *defines);

/* A program made the same way by the module being replaced is taken over, not compiled again. */
GLuint sbfx_program_build(sbfx *fx, const char *vert_name, const char *frag_name, const char *defines)
{
    uint64_t key = program_key(fx, vert_name, frag_name, defines);
    GLuint program = 0;
    if (sbfx_object_borrow(fx, SBFX_OBJECT_PROGRAM, key, &program, NULL)) {
        fx->counters.programs++;
        return program;
    }
    program = build_logged(fx, vert_name, frag_name, defines);
    if (program) sbfx_object_note(fx, SBFX_OBJECT_PROGRAM, program, key, NULL);
    return program;
}

static GLuint build_logged(sbfx *fx, const char *vert_name, const char *frag_name, const char *defines)
{
    if (!shader_log_on()) return build_program(fx, vert_name, frag_name, defines);
    char name[512];
    variant_name(defines, name, sizeof(name));
    sbfx_log(fx, SBFX_LOG_INFO, "shader build begin: %s %s | %s", vert_name, frag_name, name);
    GLuint program = build_program(fx, vert_name, frag_name, defines);
    sbfx_log(fx, SBFX_LOG_INFO, "shader build end: program %u %s", program, program ? "linked" : "failed");
    return program;
}

static GLuint build_program(sbfx *fx, const char *vert_name, const char *frag_name, const char *defines)
{
    GLuint vs = compile_stage(fx, GL_VERTEX_SHADER, vert_name, defines);
    if (!vs) return 0;
    GLuint fs = compile_stage(fx, GL_FRAGMENT_SHADER, frag_name, defines);
    if (!fs) {
        glDeleteShader(vs);
        return 0;
    }
    GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        glGetProgramInfoLog(program, sizeof(log), NULL, log);
        sbfx_fail(fx, SBFX_ERR_SHADER, "linking %s + %s failed: %s", vert_name, frag_name, log);
        glDeleteProgram(program);
        return 0;
    }
    fx->counters.programs++;
    fx->counters.programs_compiled++;
    return program;
}
