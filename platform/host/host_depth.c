/* A host's opaque depth plane (host_depth.h). */
#include "host/host_depth.h"

#include <EGL/egl.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>

#define GL_LOWER_LEFT_EXT 0x8CA1
#define GL_NEGATIVE_ONE_TO_ONE_EXT 0x935E
#define GL_ZERO_TO_ONE_EXT 0x935F

typedef void (*clip_control_fn)(GLenum origin, GLenum depth);

static bool has_extension(const char *name)
{
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++)
        if (strcmp((const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i), name) == 0) return true;
    return false;
}

/* Desktop OpenGL's version string starts with its number, ES's with "OpenGL ES". */
static bool desktop_version(int *version)
{
    const char *v = (const char *)glGetString(GL_VERSION);
    int major = 0, minor = 0;
    if (!v || strncmp(v, "OpenGL ES", 9) == 0 || sscanf(v, "%d.%d", &major, &minor) != 2) return false;
    *version = major * 10 + minor;
    return true;
}

static bool advertises_clip_control(void)
{
    int version = 0;
    if (desktop_version(&version)) return version >= 45 || has_extension("GL_ARB_clip_control");
    return has_extension("GL_EXT_clip_control");
}

static clip_control_fn clip_control_function(void)
{
    int version = 0;
    return (clip_control_fn)eglGetProcAddress(desktop_version(&version) ? "glClipControl" : "glClipControlEXT");
}

/* Advertised and reachable: Chromium's WebGL 2 offers EXT_clip_control, whose function Debian
 * 12's emscripten (3.1.6) does not bind (docs/web.md), so the name alone is not enough. */
bool host_depth_has_clip_control(void) { return advertises_clip_control() && clip_control_function() != NULL; }

void (*host_depth_clip_control(void))(GLenum origin, GLenum depth)
{
    return advertises_clip_control() ? clip_control_function() : NULL;
}

/* A full-screen quad at clip w = distance, clip z = the depth row at view z = -distance. */
static GLuint plane_program(void)
{
    static const char *vs = "#version 300 es\n"
                            "uniform vec2 u_row;       // projection[10], projection[14]\n"
                            "uniform float u_distance;\n"
                            "void main() {\n"
                            "    vec2 c = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 4.0 - 1.0;\n"
                            "    gl_Position = vec4(c * u_distance, u_row.x * -u_distance + u_row.y, u_distance);\n"
                            "}\n";
    static const char *fs = "#version 300 es\nvoid main() {}\n";
    GLuint prog = glCreateProgram();
    const char *src[2] = {vs, fs};
    const GLenum stages[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    for (int i = 0; i < 2; i++) {
        GLuint sh = glCreateShader(stages[i]);
        glShaderSource(sh, 1, &src[i], NULL);
        glCompileShader(sh);
        glAttachShader(prog, sh);
        glDeleteShader(sh);
    }
    glLinkProgram(prog);
    return prog;
}

static void draw_plane(const float projection[16], double distance)
{
    GLuint prog = plane_program(), vao = 0;
    glGenVertexArrays(1, &vao);
    glUseProgram(prog);
    glUniform2f(glGetUniformLocation(prog, "u_row"), projection[10], projection[14]);
    glUniform1f(glGetUniformLocation(prog, "u_distance"), (float)distance);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glBindVertexArray(0);
    glUseProgram(0);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(prog);
}

int host_depth_plane(GLuint *texture, int w, int h, GLenum format, const float projection[16], bool zero_to_one,
                     double distance)
{
    clip_control_fn clip_control = NULL;
    if (zero_to_one) {
        clip_control = host_depth_clip_control();
        if (!clip_control) return -ENOTSUP;
    }
    bool reversed = projection[14] > 0.0f;
    if (*texture) glDeleteTextures(1, texture);
    glGenTextures(1, texture);
    glBindTexture(GL_TEXTURE_2D, *texture);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    GLuint fbo = 0;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, *texture, 0);
    bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    if (complete) {
        if (clip_control) clip_control(GL_LOWER_LEFT_EXT, GL_ZERO_TO_ONE_EXT);
        glViewport(0, 0, w, h);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glDepthFunc(reversed ? GL_GREATER : GL_LESS);
        glClearDepthf(reversed ? 0.0f : 1.0f);
        glClear(GL_DEPTH_BUFFER_BIT);
        draw_plane(projection, distance);
        if (clip_control) clip_control(GL_LOWER_LEFT_EXT, GL_NEGATIVE_ONE_TO_ONE_EXT);
        glDisable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glClearDepthf(1.0f);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    bool errors = false;
    while (glGetError() != GL_NO_ERROR) errors = true;
    return complete && !errors ? 0 : -EIO;
}
