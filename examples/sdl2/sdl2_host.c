/* A complete small SDL2 host for sbfx: sdl2_host.h. */
#include "sdl2_host.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The host's opaque scene: a checkered ground and a wall behind the effects. */
static const char *scene_vertex =
    "#version 300 es\n"
    "layout(location = 0) in vec3 position;\n"
    "uniform mat4 view_projection;\n"
    "out vec3 world;\n"
    "void main() { world = position; gl_Position = view_projection * vec4(position, 1.0); }\n";
static const char *scene_fragment =
    "#version 300 es\n"
    "precision mediump float;\n"
    "in vec3 world;\n"
    "out vec4 color;\n"
    "void main() {\n"
    "    float checker = mod(floor(world.x) + floor(world.y + 0.001) + floor(world.z), 2.0);\n"
    "    color = vec4(vec3(0.22, 0.24, 0.27) + 0.12 * checker, 1.0);\n"
    "}\n";
static const float scene_triangles[] = {
    -20, 0, -20, 20, 0, -20, 20, 0, 20, -20, 0, -20, 20, 0, 20, -20, 0, 20, /* ground */
    -4, 0, -3, 4, 0, -3, 4, 5, -3, -4, 0, -3, 4, 5, -3, -4, 5, -3,         /* wall */
};

static int fail(const char *what, const char *why)
{
    fprintf(stderr, "sbfx-sdl2: %s failed: %s\n", what, why);
    return -1;
}

static int gl_failed(const char *what)
{
    GLenum e = glGetError();
    if (e == GL_NO_ERROR) return 0;
    char code[32];
    snprintf(code, sizeof(code), "GL error 0x%04x", e);
    return fail(what, code);
}

static void log_sbfx(sbfx_log_level level, const char *message, void *user)
{
    (void)user;
    if (level != SBFX_LOG_INFO) fprintf(stderr, "sbfx: %s\n", message);
}

/* SDL's offscreen driver (SDL_VIDEODRIVER=offscreen) gives the same context through EGL. */
static int open_window(struct sdl2_host *h, int width, int height)
{
    if (SDL_Init(SDL_INIT_VIDEO | SDL_INIT_TIMER) != 0) return fail("SDL_Init", SDL_GetError());
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_ES);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 0);
    SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 24);
    h->window = SDL_CreateWindow("sbfx in SDL2 (space: explosion)", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED,
                                 width, height, SDL_WINDOW_OPENGL | SDL_WINDOW_ALLOW_HIGHDPI);
    if (!h->window) return fail("SDL_CreateWindow", SDL_GetError());
    h->context = SDL_GL_CreateContext(h->window);
    if (!h->context) return fail("SDL_GL_CreateContext (OpenGL ES 3.0)", SDL_GetError());
    SDL_GL_SetSwapInterval(1);
    SDL_GL_GetDrawableSize(h->window, &h->width, &h->height);
    return 0;
}

static GLuint compile(GLenum stage, const char *source)
{
    GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 1, &source, NULL);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetShaderInfoLog(shader, sizeof(log), NULL, log);
        fail("compiling the scene's shader", log);
    }
    return shader;
}

static int make_scene_program(struct sdl2_host *h)
{
    GLuint vs = compile(GL_VERTEX_SHADER, scene_vertex), fs = compile(GL_FRAGMENT_SHADER, scene_fragment);
    h->program = glCreateProgram();
    glAttachShader(h->program, vs);
    glAttachShader(h->program, fs);
    glLinkProgram(h->program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(h->program, GL_LINK_STATUS, &ok);
    if (!ok) return fail("linking the scene's program", "see the compile errors above");
    h->view_projection = glGetUniformLocation(h->program, "view_projection");
    glGenVertexArrays(1, &h->vertex_array);
    glGenBuffers(1, &h->vertex_buffer);
    glBindVertexArray(h->vertex_array);
    glBindBuffer(GL_ARRAY_BUFFER, h->vertex_buffer);
    glBufferData(GL_ARRAY_BUFFER, sizeof(scene_triangles), scene_triangles, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, NULL);
    glBindVertexArray(0);
    return gl_failed("creating the scene's vertex buffer");
}

static GLuint scene_texture(GLenum internal, GLenum format, GLenum type, int width, int height)
{
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, width, height, 0, format, type, NULL);
    return texture;
}

/* sbfx reads the opaque scene's colour and depth as textures: the host draws into them. */
static int make_scene_framebuffer(struct sdl2_host *h)
{
    h->color = scene_texture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, h->width, h->height);
    h->depth = scene_texture(GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, h->width, h->height);
    glGenFramebuffers(1, &h->framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, h->framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, h->color, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, h->depth, 0);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) return fail("the scene's framebuffer", "incomplete");
    return gl_failed("creating the scene's framebuffer");
}

static int make_module(struct sdl2_host *h, const char *scene_path)
{
    char err[512];
    sbfx_scene *scene = NULL;
    if (scene_path && sbfx_scene_load(scene_path, &scene, err, sizeof(err)) != SBFX_OK)
        return fail("loading the scene", err);
    sbfx_desc desc = {.scene = scene, .log = log_sbfx};
    sbfx_result r = sbfx_create(&desc, &h->fx);
    sbfx_scene_free(scene);
    if (r != SBFX_OK) return fail("sbfx_create", sbfx_result_string(r));
    if (!sbfx_has_effect(h->fx, h->effect)) return fail("the trigger's effect", "the scene has no effect of that name");
    return 0;
}

/* SDL runs timer callbacks on a thread of its own: it only posts an event. */
static Uint32 on_timer(Uint32 interval, void *user)
{
    SDL_Event event = {.type = *(const Uint32 *)user};
    SDL_PushEvent(&event);
    return interval;
}

int sdl2_host_open(struct sdl2_host *h, int width, int height, const char *scene_path, const char *effect,
                   Uint32 timer_ms)
{
    memset(h, 0, sizeof(*h));
    h->effect = effect ? effect : "explosion";
    if (open_window(h, width, height) || make_scene_program(h) || make_scene_framebuffer(h) ||
        make_module(h, scene_path))
        return -1;
    h->timer_event = SDL_RegisterEvents(1);
    if (timer_ms > 0 && h->timer_event != (Uint32)-1) {
        h->timer = SDL_AddTimer(timer_ms, on_timer, &h->timer_event);
        if (!h->timer) return fail("SDL_AddTimer", SDL_GetError());
    }
    return 0;
}

/* A trigger the full particle pool refuses is logged by sbfx (log_sbfx) and dropped. */
static void trigger(struct sdl2_host *h, const float position[3])
{
    if (sbfx_trigger(h->fx, h->effect, position) == SBFX_OK) h->triggers++;
}

bool sdl2_host_handle(struct sdl2_host *h, const SDL_Event *event)
{
    if (event->type == SDL_QUIT) return false;
    if (event->type == SDL_KEYDOWN && event->key.keysym.sym == SDLK_ESCAPE) return false;
    if (event->type == SDL_KEYDOWN && event->key.keysym.sym == SDLK_SPACE && !event->key.repeat) {
        float x = (float)(h->triggers % 3) - 1.0f; /* left, middle, right in turn */
        trigger(h, (const float[3]){1.5f * x, 0.0f, 0.0f});
    }
    if (event->type == h->timer_event) trigger(h, (const float[3]){0.0f, 0.0f, 0.0f});
    return true;
}

/* An eye circling the origin at 12 m, 3.5 m up. */
static void camera(struct sdl2_host *h)
{
    double angle = fmod(h->time * 0.1, 2.0 * M_PI) - 0.6;
    const float eye[3] = {12.0f * (float)sin(angle), 3.5f, 12.0f * (float)cos(angle)};
    sbfx_look_at(h->view, eye, (const float[3]){0, 2, 0}, (const float[3]){0, 1, 0});
    sbfx_perspective(h->projection, 0.9f, (float)h->width / (float)h->height, 0.1f, 200.0f);
}

static void multiply(const float a[16], const float b[16], float out[16])
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            out[c * 4 + r] = 0.0f;
            for (int k = 0; k < 4; k++) out[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
        }
}

static void draw_scene(struct sdl2_host *h)
{
    float view_projection[16];
    multiply(h->projection, h->view, view_projection);
    glBindFramebuffer(GL_FRAMEBUFFER, h->framebuffer);
    glViewport(0, 0, h->width, h->height);
    glClearColor(0.45f, 0.55f, 0.7f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glUseProgram(h->program);
    glUniformMatrix4fv(h->view_projection, 1, GL_FALSE, view_projection);
    glBindVertexArray(h->vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, (GLsizei)(sizeof(scene_triangles) / sizeof(float) / 3));
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
    /* the scene in the window; sbfx composites over it there */
    glBindFramebuffer(GL_READ_FRAMEBUFFER, h->framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, h->width, h->height, 0, 0, h->width, h->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

int sdl2_host_frame(struct sdl2_host *h, double dt)
{
    h->time += dt;
    camera(h);
    draw_scene(h);
    if (gl_failed("drawing the scene")) return -1;
    sbfx_frame frame = {.scene_color_texture = h->color, .scene_depth_texture = h->depth,
                        .out_framebuffer = 0, .width = h->width, .height = h->height};
    memcpy(frame.view, h->view, sizeof(frame.view));
    memcpy(frame.projection, h->projection, sizeof(frame.projection));
    if (sbfx_update(h->fx, dt) != SBFX_OK || sbfx_render(h->fx, &frame) != SBFX_OK)
        return fail("sbfx", sbfx_last_error(h->fx));
    return 0;
}

void sdl2_host_present(struct sdl2_host *h) { SDL_GL_SwapWindow(h->window); }

void sdl2_host_close(struct sdl2_host *h)
{
    if (h->timer) SDL_RemoveTimer(h->timer);
    if (h->context) {
        sbfx_destroy(h->fx);
        glDeleteFramebuffers(1, &h->framebuffer);
        GLuint textures[] = {h->color, h->depth};
        glDeleteTextures(2, textures);
        glDeleteProgram(h->program);
        glDeleteVertexArrays(1, &h->vertex_array);
        glDeleteBuffers(1, &h->vertex_buffer);
        SDL_GL_DeleteContext(h->context);
    }
    if (h->window) SDL_DestroyWindow(h->window);
    SDL_Quit();
    memset(h, 0, sizeof(*h));
}
