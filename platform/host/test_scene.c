/* The opaque host scene: ground plane and boxes, Lambert-lit, into its own colour + depth
 * FBO. Host code, so its two small shaders live here rather than in shaders_es/. */
#include "host/test_scene.h"

#include <EGL/egl.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "host/host_depth.h"
#include "sbfx.h"

#define GL_LOWER_LEFT_EXT 0x8CA1
#define GL_NEGATIVE_ONE_TO_ONE_EXT 0x935E
#define GL_ZERO_TO_ONE_EXT 0x935F

#define ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))

/* Linear RGB. The sun comes from the side (+x, a little +z) so that the faces of a box
 * the demo camera sees get three clearly different shades. */
static const float to_sun[3] = {0.7547f, 0.5535f, 0.3522f}; /* unit */
static const float sun_color[3] = {0.90f, 0.84f, 0.74f};
static const float sky_color[3] = {0.34f, 0.47f, 0.66f};
static const float bounce_color[3] = {0.16f, 0.15f, 0.13f}; /* light from the ground */

struct box {
    float center[3], size[3];
    float yaw; /* radians about +y */
    float albedo[3];
};

static const struct box boxes[] = {
    /* straddles the cloud: half of it inside, so the billboards' depth clipping shows */
    {{1.3f, 0.6f, 0.8f}, {1.2f, 1.2f, 1.2f}, 0.35f, {0.60f, 0.38f, 0.24f}},
    /* thin and tall: the cloud wraps around it, both in front and behind */
    {{-1.8f, 1.5f, -0.5f}, {0.35f, 3.0f, 0.35f}, 0.0f, {0.55f, 0.55f, 0.58f}},
    /* behind the cloud from the demo camera: the smoke's edge meets it */
    {{0.3f, 1.1f, -2.9f}, {4.0f, 2.2f, 0.5f}, -0.12f, {0.42f, 0.48f, 0.40f}},
};

static const char vertex_source[] =
    "#version 300 es\n"
    "precision highp float;\n"
    "layout(location = 0) in vec3 a_position;\n"
    "layout(location = 1) in vec3 a_normal;\n"
    "uniform mat4 u_model;\n"
    "uniform mat3 u_normal_matrix;\n"
    "uniform mat4 u_view_proj;\n"
    "out vec3 v_world;\n"
    "out vec3 v_normal;\n"
    "void main() {\n"
    "    vec4 world = u_model * vec4(a_position, 1.0);\n"
    "    v_world = world.xyz;\n"
    "    v_normal = u_normal_matrix * a_normal;\n"
    "    gl_Position = u_view_proj * world;\n"
    "}\n";

/* The checker is box-filtered over the pixel footprint (fwidth) so that it fades to grey
 * towards the horizon instead of aliasing into moiré. */
static const char fragment_source[] =
    "#version 300 es\n"
    "precision highp float;\n"
    "in vec3 v_world;\n"
    "in vec3 v_normal;\n"
    "uniform vec3 u_albedo;\n"
    "uniform int u_checker;\n"
    "uniform vec3 u_eye;\n"
    "uniform vec3 u_to_sun;\n"
    "uniform vec3 u_sun_color;\n"
    "uniform vec3 u_sky_color;\n"     /* the hemisphere ambient's upper half */
    "uniform vec3 u_bounce_color;\n"  /* its lower half, light from the ground */
    "uniform vec3 u_fog_color;\n"
    "uniform float u_exposure;\n"
    "uniform int u_shadowed;\n"
    "uniform mat4 u_shadow_matrix;\n"
    "uniform sampler2D u_shadow;\n"
    "uniform int u_point_count;\n"
    "uniform vec3 u_point_position[16];\n"
    "uniform vec4 u_point_color_radius[16];\n"
    "out vec4 o_color;\n"
    /* the fire's lights (sbfx_emitted_lights) with the falloff include/sbfx.h documents */
    "vec3 point_lights(vec3 world, vec3 n) {\n"
    "    vec3 sum = vec3(0.0);\n"
    "    for (int i = 0; i < u_point_count; i++) {\n"
    "        vec3 to_light = u_point_position[i] - world;\n"
    "        float d = length(to_light);\n"
    "        float x = d / u_point_color_radius[i].w, window = clamp(1.0 - x * x * x * x, 0.0, 1.0);\n"
    "        float lambert = max(dot(n, to_light / max(d, 1e-6)), 0.0);\n"
    "        sum += u_point_color_radius[i].rgb * (window * window / max(d * d, 0.25) * lambert);\n"
    "    }\n"
    "    return sum;\n"
    "}\n"
    /* the smoke's transmittance towards the sun (sbfx_render_shadow_map, docs/embedding.md's
     * smoke_visibility): the map is 1 on its border, so CLAMP_TO_EDGE reads 1 outside the smoke;
     * a surface in front of where the smoke begins along the light is not shaded, one inside it
     * by the share of the smoke's optical depth in front of it */
    "float sun_visibility(vec3 world) {\n"
    "    if (u_shadowed == 0) return 1.0;\n"
    "    vec3 m = (u_shadow_matrix * vec4(world, 1.0)).xyz * 0.5 + 0.5;\n"
    "    vec4 s = texture(u_shadow, m.xy);\n"
    "    if (m.z <= s.a || s.r >= 1.0) return 1.0;\n"
    "    if (s.r <= 1e-4) return s.r;\n"
    "    float mean = log(s.g) / log(s.r);\n"
    "    float half_width = sqrt(3.0 * max(log(s.b) / log(s.r) - mean * mean, 0.0));\n"
    "    float begin = max(s.a, mean - half_width), end = mean + half_width;\n"
    "    float share = end > begin ? clamp((m.z - begin) / (end - begin), 0.0, 1.0) : 1.0;\n"
    "    return pow(s.r, share);\n"
    "}\n"
    "float checker(vec2 p) {\n"
    "    vec2 w = max(fwidth(p), vec2(1e-4));\n"
    "    vec2 i = 2.0 * (abs(fract((p - 0.5 * w) * 0.5) - 0.5) -\n"
    "                    abs(fract((p + 0.5 * w) * 0.5) - 0.5)) / w;\n"
    "    return 0.5 - 0.5 * i.x * i.y;\n"
    "}\n"
    "void main() {\n"
    "    vec3 n = normalize(v_normal);\n"
    "    vec3 albedo = u_albedo;\n"
    "    if (u_checker != 0) albedo *= mix(0.6, 1.0, checker(v_world.xz));\n"
    "    vec3 ambient = mix(u_bounce_color, u_sky_color, 0.5 + 0.5 * n.y);\n"
    "    vec3 sun = u_sun_color * (max(dot(n, u_to_sun), 0.0) * sun_visibility(v_world));\n"
    "    vec3 c = albedo * (sun + ambient + point_lights(v_world, n)) * u_exposure;\n"
    "    float fog = 1.0 - exp(-0.012 * distance(v_world, u_eye));\n"
    "    c = mix(c, u_fog_color * u_exposure, fog);\n"
    "    o_color = vec4(pow(clamp(c, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);\n"
    "}\n";

/* ---- small matrix helpers (column-major) ------------------------------------------------ */

static void mat4_mul(float out[16], const float a[16], const float b[16])
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            float s = 0.0f;
            for (int k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
            out[c * 4 + r] = s;
        }
}

/* model = translate(center) * rotate_y(yaw) * scale(size); normals get rotate_y * scale^-1. */
static void box_matrices(const struct box *b, float model[16], float normal[9])
{
    float c = cosf(b->yaw), s = sinf(b->yaw);
    const float *k = b->size;
    const float m[16] = {c * k[0], 0, -s * k[0], 0, 0, k[1], 0, 0, s * k[2], 0, c * k[2], 0,
                         b->center[0], b->center[1], b->center[2], 1};
    const float nm[9] = {c / k[0], 0, -s / k[0], 0, 1 / k[1], 0, s / k[2], 0, c / k[2]};
    memcpy(model, m, sizeof(m));
    memcpy(normal, nm, sizeof(nm));
}

/* Camera position from a rigid view matrix: eye = -R^T t. */
static void view_eye(const float view[16], float eye[3])
{
    for (int i = 0; i < 3; i++)
        eye[i] = -(view[i * 4 + 0] * view[12] + view[i * 4 + 1] * view[13] +
                   view[i * 4 + 2] * view[14]);
}

/* ---- geometry ------------------------------------------------------------------------- */

/* A unit cube, 6 vertices (position, normal) per face, counter-clockwise from outside.
 * Face 2 (+y) doubles as the ground plane. */
#define CUBE_VERTICES 36
#define GROUND_FIRST 12

static void cube_vertices(float out[CUBE_VERTICES][6])
{
    /* normal, u, v with u x v = normal */
    static const float faces[6][3][3] = {
        {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}},
    };
    static const float corner[6][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, -1}, {1, 1}, {-1, 1}};
    for (int f = 0; f < 6; f++)
        for (int v = 0; v < 6; v++) {
            float *o = out[f * 6 + v];
            for (int i = 0; i < 3; i++) {
                o[i] = 0.5f * (faces[f][0][i] + corner[v][0] * faces[f][1][i] +
                               corner[v][1] * faces[f][2][i]);
                o[3 + i] = faces[f][0][i];
            }
        }
}

static int create_geometry(struct test_scene *scene)
{
    float vertices[CUBE_VERTICES][6];
    cube_vertices(vertices);
    glGenVertexArrays(1, &scene->vao);
    glGenBuffers(1, &scene->vbo);
    glBindVertexArray(scene->vao);
    glBindBuffer(GL_ARRAY_BUFFER, scene->vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof(vertices), vertices, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          (const void *)(3 * sizeof(float)));
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    return glGetError() == GL_OUT_OF_MEMORY ? -ENOMEM : 0;
}

/* ---- program -------------------------------------------------------------------------- */

static GLuint compile(GLenum type, const char *source, char *err, size_t n)
{
    GLuint shader = glCreateShader(type);
    if (!shader) {
        snprintf(err, n, "test scene: glCreateShader failed (0x%x)", glGetError());
        return 0;
    }
    glShaderSource(shader, 1, &source, NULL);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetShaderInfoLog(shader, sizeof(log), NULL, log);
        snprintf(err, n, "test scene: %s shader: %s",
                 type == GL_VERTEX_SHADER ? "vertex" : "fragment", log);
        glDeleteShader(shader);
        return 0;
    }
    return shader;
}

static void default_daylight(struct test_scene *scene)
{
    memcpy(scene->to_sun, to_sun, sizeof(to_sun));
    memcpy(scene->sun_color, sun_color, sizeof(sun_color));
    memcpy(scene->sky_color, sky_color, sizeof(sky_color));
    memcpy(scene->bounce_color, bounce_color, sizeof(bounce_color));
    memcpy(scene->fog_color, sky_color, sizeof(sky_color));
    scene->exposure = 1.0f;
}

static void set_light_uniforms(const struct test_scene *scene)
{
    GLuint p = scene->program;
    glUniform3fv(glGetUniformLocation(p, "u_to_sun"), 1, scene->to_sun);
    glUniform3fv(glGetUniformLocation(p, "u_sun_color"), 1, scene->sun_color);
    glUniform3fv(glGetUniformLocation(p, "u_sky_color"), 1, scene->sky_color);
    glUniform3fv(glGetUniformLocation(p, "u_bounce_color"), 1, scene->bounce_color);
    glUniform3fv(glGetUniformLocation(p, "u_fog_color"), 1, scene->fog_color);
    glUniform1f(glGetUniformLocation(p, "u_exposure"), scene->exposure);
    glUniform1i(glGetUniformLocation(p, "u_shadowed"), scene->shadow_texture != 0);
    glUniformMatrix4fv(glGetUniformLocation(p, "u_shadow_matrix"), 1, GL_FALSE, scene->shadow_matrix);
    glUniform1i(glGetUniformLocation(p, "u_shadow"), 0);
    glUniform1i(glGetUniformLocation(p, "u_point_count"), scene->point_count);
    if (scene->point_count > 0) {
        glUniform3fv(glGetUniformLocation(p, "u_point_position"), scene->point_count, scene->point_position[0]);
        glUniform4fv(glGetUniformLocation(p, "u_point_color_radius"), scene->point_count,
                     scene->point_color_radius[0]);
    }
    if (scene->shadow_texture) {
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, scene->shadow_texture);
    }
}

static int create_program(struct test_scene *scene, char *err, size_t n)
{
    GLuint vs = compile(GL_VERTEX_SHADER, vertex_source, err, n);
    if (!vs) return -EIO;
    GLuint fs = compile(GL_FRAGMENT_SHADER, fragment_source, err, n);
    if (!fs) goto err_vs;
    scene->program = glCreateProgram();
    glAttachShader(scene->program, vs);
    glAttachShader(scene->program, fs);
    glLinkProgram(scene->program);
    glDeleteShader(vs); /* flagged for deletion; they go when the program does */
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(scene->program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetProgramInfoLog(scene->program, sizeof(log), NULL, log);
        snprintf(err, n, "test scene: link: %s", log);
        return -EIO;
    }
    GLuint p = scene->program;
    scene->u_model = glGetUniformLocation(p, "u_model");
    scene->u_normal_matrix = glGetUniformLocation(p, "u_normal_matrix");
    scene->u_view_proj = glGetUniformLocation(p, "u_view_proj");
    scene->u_eye = glGetUniformLocation(p, "u_eye");
    scene->u_albedo = glGetUniformLocation(p, "u_albedo");
    scene->u_checker = glGetUniformLocation(p, "u_checker");
    return 0;

err_vs:
    glDeleteShader(vs);
    return -EIO;
}

/* ---- framebuffer ---------------------------------------------------------------------- */

static GLuint create_texture(GLenum format, GLint filter, int width, int height)
{
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    return texture;
}

static int create_framebuffer(struct test_scene *scene, char *err, size_t n)
{
    int w = scene->width, h = scene->height;
    scene->color_texture = create_texture(GL_RGBA8, GL_LINEAR, w, h);
    scene->depth_texture = create_texture(GL_DEPTH_COMPONENT24, GL_NEAREST, w, h);
    glBindTexture(GL_TEXTURE_2D, scene->depth_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glBindTexture(GL_TEXTURE_2D, 0);
    GLenum gl_err = glGetError();
    if (gl_err != GL_NO_ERROR) {
        snprintf(err, n, "test scene: %dx%d textures failed (GL error 0x%x)", w, h, gl_err);
        return gl_err == GL_OUT_OF_MEMORY ? -ENOMEM : -EIO;
    }
    glGenFramebuffers(1, &scene->framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, scene->framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                           scene->color_texture, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D,
                           scene->depth_texture, 0);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(err, n, "test scene: RGBA8 + DEPTH_COMPONENT24 framebuffer incomplete (0x%x)",
                 status);
        return -EIO;
    }
    return 0;
}

static int check_size(int width, int height, char *err, size_t n)
{
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (width < 1 || height < 1 || width > max_size || height > max_size) {
        snprintf(err, n, "test scene: size %dx%d is outside 1..%d", width, height, max_size);
        return -EINVAL;
    }
    return 0;
}

int test_scene_create(struct test_scene *scene, int width, int height, char *err, size_t n)
{
    memset(scene, 0, sizeof(*scene));
    while (glGetError() != GL_NO_ERROR) {} /* errors from before are not ours */
    int rc = check_size(width, height, err, n);
    if (rc) return rc;
    scene->width = width;
    scene->height = height;
    default_daylight(scene);
    rc = create_framebuffer(scene, err, n);
    if (rc) goto err_scene;
    rc = create_program(scene, err, n);
    if (rc) goto err_scene;
    rc = create_geometry(scene);
    if (rc) {
        snprintf(err, n, "test scene: out of GL memory for the geometry");
        goto err_scene;
    }
    GLenum gl_err = glGetError();
    if (gl_err != GL_NO_ERROR) {
        snprintf(err, n, "test scene: GL error 0x%x while creating", gl_err);
        rc = gl_err == GL_OUT_OF_MEMORY ? -ENOMEM : -EIO;
        goto err_scene;
    }
    return 0;

err_scene: /* deleting name 0 is a no-op, so one label undoes any prefix of the above */
    test_scene_destroy(scene);
    return rc;
}

/* ---- drawing -------------------------------------------------------------------------- */

static void draw_box(struct test_scene *scene, const struct box *b)
{
    float model[16], normal[9];
    box_matrices(b, model, normal);
    glUniformMatrix4fv(scene->u_model, 1, GL_FALSE, model);
    glUniformMatrix3fv(scene->u_normal_matrix, 1, GL_FALSE, normal);
    glUniform3fv(scene->u_albedo, 1, b->albedo);
    glDrawArrays(GL_TRIANGLES, 0, CUBE_VERTICES);
}

static void draw_ground(struct test_scene *scene)
{
    /* the cube's +y face, 200 m wide, moved down so that it lies at y = 0 */
    static const struct box ground = {{0, -0.5f, 0}, {200, 1, 200}, 0, {0.50f, 0.48f, 0.44f}};
    float model[16], normal[9];
    box_matrices(&ground, model, normal);
    glUniformMatrix4fv(scene->u_model, 1, GL_FALSE, model);
    glUniformMatrix3fv(scene->u_normal_matrix, 1, GL_FALSE, normal);
    glUniform3fv(scene->u_albedo, 1, ground.albedo);
    glUniform1i(scene->u_checker, 1);
    glDrawArrays(GL_TRIANGLES, GROUND_FIRST, 6);
    glUniform1i(scene->u_checker, 0);
}

static void begin_pass(struct test_scene *scene)
{
    glBindFramebuffer(GL_FRAMEBUFFER, scene->framebuffer);
    glViewport(0, 0, scene->width, scene->height);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    /* the clear colour is the fog colour, sRGB-encoded like the shader's output */
    float clear[3];
    for (int i = 0; i < 3; i++) clear[i] = powf(fminf(scene->fog_color[i] * scene->exposure, 1.0f), 1 / 2.2f);
    glClearColor(clear[0], clear[1], clear[2], 1.0f);
    glClearDepthf(scene->reversed_z ? 0.0f : 1.0f);
    glDepthFunc(scene->reversed_z ? GL_GREATER : GL_LESS);
    if (scene->reversed_z) scene->clip_control(GL_LOWER_LEFT_EXT, GL_ZERO_TO_ONE_EXT);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

static void end_pass(struct test_scene *scene)
{
    if (scene->reversed_z) scene->clip_control(GL_LOWER_LEFT_EXT, GL_NEGATIVE_ONE_TO_ONE_EXT);
    if (scene->shadow_texture) glBindTexture(GL_TEXTURE_2D, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

int test_scene_draw(struct test_scene *scene, const float view[16], const float projection[16])
{
    float view_proj[16], eye[3];
    mat4_mul(view_proj, projection, view);
    view_eye(view, eye);
    begin_pass(scene);
    glUseProgram(scene->program);
    glBindVertexArray(scene->vao);
    glUniformMatrix4fv(scene->u_view_proj, 1, GL_FALSE, view_proj);
    glUniform3fv(scene->u_eye, 1, eye);
    set_light_uniforms(scene);
    draw_ground(scene);
    for (size_t i = 0; i < ARRAY_SIZE(boxes); i++) draw_box(scene, &boxes[i]);
    end_pass(scene);
    int rc = 0;
    while (glGetError() != GL_NO_ERROR) rc = -EIO;
    return rc;
}

void test_scene_destroy(struct test_scene *scene)
{
    if (!scene) return;
    glDeleteFramebuffers(1, &scene->framebuffer);
    glDeleteTextures(1, &scene->color_texture);
    glDeleteTextures(1, &scene->depth_texture);
    glDeleteProgram(scene->program);
    glDeleteVertexArrays(1, &scene->vao);
    glDeleteBuffers(1, &scene->vbo);
    memset(scene, 0, sizeof(*scene));
}

/* ---- camera and light ----------------------------------------------------------------- */

void test_scene_camera(const sbfx_scene_camera *camera, double seconds, float aspect, float view[16],
                       float projection[16])
{
    /* the angle reduced in double (docs/design.md §7): an orbit an hour in is where it is at t mod 360 */
    double degrees = fmod(camera->azimuth + camera->orbit * seconds, 360.0);
    double angle = degrees * M_PI / 180.0;
    const float *t = camera->target;
    const float eye[3] = {t[0] + camera->distance * (float)sin(angle), camera->height,
                          t[2] + camera->distance * (float)cos(angle)};
    const float up[3] = {0.0f, 1.0f, 0.0f};
    sbfx_look_at(view, eye, t, up);
    sbfx_perspective(projection, camera->fov * (float)M_PI / 180.0f, aspect, TEST_SCENE_NEAR, TEST_SCENE_FAR);
}

void test_scene_orbit_camera(double seconds, float aspect, float view[16], float projection[16])
{
    sbfx_scene_camera orbit;
    sbfx_scene_camera_get(NULL, &orbit);
    test_scene_camera(&orbit, seconds, aspect, view, projection);
}

void test_scene_light(float direction[3], float color[3], float ambient[3])
{
    for (int i = 0; i < 3; i++) {
        direction[i] = -to_sun[i];
        color[i] = sun_color[i];
        ambient[i] = sky_color[i];
    }
}

void test_scene_set_daylight(struct test_scene *scene, const sbfx_scene_host *host)
{
    default_daylight(scene);
    /* the sun stands where the scene's is (its shadows fall from there) */
    if (host->has_sun)
        for (int i = 0; i < 3; i++) scene->to_sun[i] = -host->sun_direction[i];
    if (!host->has_sky) return;
    for (int i = 0; i < 3; i++) {
        scene->to_sun[i] = host->has_sun ? -host->sun_direction[i] : 0.0f;
        scene->sun_color[i] = host->has_sun ? host->sun_color[i] : 0.0f;
        scene->sky_color[i] = host->ambient[i];
        /* light from the ground: the ambient's, reflected by ground of about the default
         * bounce's share of the default sky (0.16 / 0.34) */
        scene->bounce_color[i] = 0.45f * host->ambient[i];
        scene->fog_color[i] = host->sky[i];
    }
    scene->exposure = host->exposure > 0.0f ? host->exposure : 1.0f;
}

void test_scene_set_shadow(struct test_scene *scene, GLuint texture, const float view_projection[16])
{
    scene->shadow_texture = texture;
    if (texture) memcpy(scene->shadow_matrix, view_projection, sizeof(scene->shadow_matrix));
}

void test_scene_set_point_lights(struct test_scene *scene, const sbfx_point_light *lights, int count)
{
    scene->point_count = count < 0 ? 0 : count > TEST_SCENE_POINT_LIGHTS ? TEST_SCENE_POINT_LIGHTS : count;
    for (int i = 0; i < scene->point_count; i++) {
        memcpy(scene->point_position[i], lights[i].position, sizeof(scene->point_position[i]));
        memcpy(scene->point_color_radius[i], lights[i].color, 3 * sizeof(float));
        scene->point_color_radius[i][3] = lights[i].radius;
    }
}

int test_scene_use_reversed_z(struct test_scene *scene, char *err, size_t n)
{
    if (!host_depth_has_clip_control()) {
        snprintf(err, n, "test scene: reversed-Z needs GL_EXT_clip_control, which this context does not offer");
        return -ENOTSUP;
    }
    scene->clip_control = host_depth_clip_control();
    glDeleteTextures(1, &scene->depth_texture);
    scene->depth_texture = create_texture(GL_DEPTH_COMPONENT32F, GL_NEAREST, scene->width, scene->height);
    glBindFramebuffer(GL_FRAMEBUFFER, scene->framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, scene->depth_texture, 0);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (!scene->clip_control || status != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(err, n, "test scene: RGBA8 + DEPTH_COMPONENT32F framebuffer incomplete (0x%x)", status);
        return -EIO;
    }
    scene->reversed_z = true;
    return 0;
}
