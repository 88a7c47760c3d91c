/* host.c: a desktop OpenGL renderer (3.3 core profile, GLSL 330 shaders of its own, libOpenGL)
 * that adds sbfx's explosion to its picture (docs/hosts/desktop-gl.md). sbfx runs on the same
 * context: desktop OpenGL has its GLES 3.0 calls under the same names and compiles its GLSL ES
 * 3.00 shaders (4.3+, or 3.3 with GL_ARB_ES3_compatibility). Headless (EGL surfaceless with
 * EGL_OPENGL_API), so it runs wherever Mesa does; a windowed host (GLFW, SDL, Qt's desktop
 * context) differs only in make_context() and in drawing to its window.
 *   cc -std=c11 host.c $(pkg-config --cflags --libs sbfx opengl egl glesv2) -o host && ./host
 * make test builds and runs it (tests/hosts/desktop_gl_example.sh). */
#define GL_GLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <stdio.h>
#include <string.h>
#include <sbfx.h>

enum { W = 320, H = 180 };

static void log_stderr(sbfx_log_level level, const char *message, void *user)
{
    (void)user;
    fprintf(stderr, "sbfx: %s: %s\n", level == SBFX_LOG_ERROR ? "error" : "note", message);
}

/* An OpenGL 3.3 core profile context, as a simulator or a GLFW program asks for one. */
static int make_context(void)
{
    EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                     EGL_NONE};
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
    EGLConfig config;
    EGLint configs = 0;
    if (!eglInitialize(display, NULL, NULL) || !eglBindAPI(EGL_OPENGL_API) ||
        !eglChooseConfig(display, config_attribs, &config, 1, &configs) || configs < 1)
        return -1;
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
    if (context == EGL_NO_CONTEXT) return -1;
    return eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) ? 0 : -1;
}

/* The host's opaque scene in its own desktop GLSL: a ground plane, 100 m square. */
static const char *ground_vs =
    "#version 330 core\n"
    "uniform mat4 view, projection;\n"
    "void main() {\n"
    "    vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1) * 100.0 - 50.0;\n"
    "    gl_Position = projection * view * vec4(corner.x, 0.0, corner.y, 1.0);\n"
    "}\n";
static const char *ground_fs =
    "#version 330 core\n"
    "out vec4 color;\n"
    "void main() { color = vec4(0.35, 0.32, 0.28, 1.0); }\n";

static GLuint compile(GLenum stage, const char *source)
{
    GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 1, &source, NULL);
    glCompileShader(shader);
    return shader;
}

static GLuint texture(GLenum format)
{
    GLuint id;
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_2D, id);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, W, H);
    return id;
}

static GLuint framebuffer(GLuint color, GLuint depth)
{
    GLuint id;
    glGenFramebuffers(1, &id);
    glBindFramebuffer(GL_FRAMEBUFFER, id);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color, 0);
    if (depth) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth, 0);
    return id;
}

/* The host's GL objects: its scene's colour + depth textures, the framebuffer sbfx composites
 * over (a windowed host uses its window's, 0), the ground's program and the core profile's
 * vertex array, bound for the host's draws. */
struct host {
    GLuint scene_color, scene_depth, scene_fbo, out_color, out_fbo, ground, vertex_array;
    GLint view, projection;
};

static void host_create(struct host *h)
{
    h->scene_color = texture(GL_RGBA8);
    h->scene_depth = texture(GL_DEPTH_COMPONENT24);
    h->scene_fbo = framebuffer(h->scene_color, h->scene_depth);
    h->out_color = texture(GL_RGBA8);
    h->out_fbo = framebuffer(h->out_color, 0);
    h->ground = glCreateProgram();
    glAttachShader(h->ground, compile(GL_VERTEX_SHADER, ground_vs));
    glAttachShader(h->ground, compile(GL_FRAGMENT_SHADER, ground_fs));
    glLinkProgram(h->ground);
    h->view = glGetUniformLocation(h->ground, "view");
    h->projection = glGetUniformLocation(h->ground, "projection");
    glGenVertexArrays(1, &h->vertex_array);
    glBindVertexArray(h->vertex_array);
}

/* The host's frame: its scene into its colour + depth textures, its picture into the
 * framebuffer sbfx composites over. */
static void host_draw(const struct host *h, const sbfx_frame *frame)
{
    glBindFramebuffer(GL_FRAMEBUFFER, h->scene_fbo);
    glViewport(0, 0, W, H);
    glEnable(GL_DEPTH_TEST);
    glClearColor(0.55f, 0.65f, 0.8f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(h->ground);
    glUniformMatrix4fv(h->view, 1, GL_FALSE, frame->view);
    glUniformMatrix4fv(h->projection, 1, GL_FALSE, frame->projection);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, h->out_fbo);
    glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

/* The check of this example: the explosion shows over the scene, drawn into a float particle
 * target (desktop OpenGL renders to RGBA16F in core), and no GL error. */
static int host_check(const struct host *h, sbfx *fx)
{
    static unsigned char scene[W * H * 4], composite[W * H * 4];
    glBindFramebuffer(GL_FRAMEBUFFER, h->scene_fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, scene);
    glBindFramebuffer(GL_FRAMEBUFFER, h->out_fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, composite);
    int changed = 0;
    for (int i = 0; i < W * H; i++) changed += memcmp(scene + 4 * i, composite + 4 * i, 3) != 0;
    sbfx_counters c;
    sbfx_stats(fx, &c);
    GLenum error = glGetError();
    printf("host: %s; the explosion covers %d of %d pixels; particle target %s; GL error 0x%x\n",
           (const char *)glGetString(GL_VERSION), changed, W * H,
           c.target_format == SBFX_FORMAT_RGBA16F ? "RGBA16F" : "not RGBA16F", error);
    return changed > W * H / 100 && c.target_format == SBFX_FORMAT_RGBA16F && error == GL_NO_ERROR ? 0 : 1;
}

int main(void)
{
    if (make_context() != 0) {
        fprintf(stderr, "host: no OpenGL 3.3 core profile context (EGL error 0x%x)\n", eglGetError());
        return 1;
    }
    struct host host;
    host_create(&host);

    /* the same calls as on OpenGL ES: sbfx looks at the context it is created on */
    sbfx_desc desc = {.log = log_stderr, .ignore_timeline = true};
    sbfx *fx = NULL;
    if (sbfx_create(&desc, &fx) != SBFX_OK) return 1; /* the reason went to log_stderr */
    const float origin[3] = {0.0f, 0.0f, 0.0f};
    sbfx_trigger(fx, "explosion", origin);
    sbfx_frame frame = {
        .scene_color_texture = host.scene_color,
        .scene_depth_texture = host.scene_depth,
        .out_framebuffer = host.out_fbo,
        .width = W,
        .height = H,
    };
    const float eye[3] = {4.0f, 3.0f, 11.0f}, target[3] = {0.0f, 1.5f, 0.0f}, up[3] = {0, 1, 0};
    sbfx_look_at(frame.view, eye, target, up);
    sbfx_perspective(frame.projection, 0.87f /* 50 degrees */, (float)W / H, 0.1f, 200.0f);
    for (int i = 0; i < 30; i++) { /* half a second at 60 Hz */
        host_draw(&host, &frame);
        sbfx_update(fx, 1.0 / 60.0);
        if (sbfx_render(fx, &frame) != SBFX_OK) {
            fprintf(stderr, "host: %s\n", sbfx_last_error(fx));
            return 1;
        }
    }
    int result = host_check(&host, fx);
    sbfx_destroy(fx); /* with the same context current */
    return result;
}
