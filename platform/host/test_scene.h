/* The opaque host scene the demo, the GL tests and the benchmark render explosions into.
 *
 * A large checkered ground plane (y = 0; the checker makes depth edges and halos visible) and
 * three boxes placed where the built-in explosion (centred at the origin, 3-4 m across, rising
 * to about 5 m) intersects them: a 1.2 m box straddling the cloud, a thin tall pillar it wraps
 * around and a wall behind it. Lambert lighting from a directional sun plus a sky/ground
 * hemisphere ambient, distance fog towards the sky colour.
 *
 * Rendered with GLES 3.0 into the scene's own framebuffer: an RGBA8 colour texture holding
 * display-ready (sRGB-encoded) colour with alpha 1, and a DEPTH_COMPONENT24 depth texture with
 * NEAREST filters, both of the size given at creation — what sbfx_frame wants as
 * scene_color_texture and scene_depth_texture. Needs a current GLES 3.0 context. */
#ifndef SBFX_TEST_SCENE_H
#define SBFX_TEST_SCENE_H

#include <GLES3/gl3.h>
#include <stdbool.h>
#include <stddef.h>
#include "sbfx.h"

struct test_scene {
    bool reversed_z;        /* test_scene_use_reversed_z */
    void (*clip_control)(GLenum origin, GLenum depth);
    GLuint framebuffer;
    GLuint color_texture;   /* RGBA8, LINEAR, clamp to edge */
    GLuint depth_texture;   /* DEPTH_COMPONENT24, NEAREST, compare mode NONE */
    int width, height;
    GLuint program, vao, vbo;
    GLint u_model, u_normal_matrix, u_view_proj, u_eye, u_albedo, u_checker;
    /* the light (test_scene_set_daylight; the fixed daylight below by default), linear RGB */
    float to_sun[3], sun_color[3], sky_color[3], bounce_color[3], fog_color[3], exposure;
    GLuint shadow_texture;  /* test_scene_set_shadow: sbfx's map, 0 none */
    float shadow_matrix[16];
    int point_count;        /* test_scene_set_point_lights */
    float point_position[16][3], point_color_radius[16][4];
};
#define TEST_SCENE_POINT_LIGHTS 16 /* SBFX_MAX_POINT_LIGHTS */

/* 0, or -EINVAL (bad size), -ENOMEM (GL out of memory), -EIO (shader, framebuffer or another
 * GL failure) with a message in err. */
int test_scene_create(struct test_scene *scene, int width, int height, char *err, size_t n);
/* Draws the scene into scene->framebuffer (whole viewport), then binds framebuffer 0 and
 * leaves depth test, culling, program and vertex array unbound/disabled.
 * Returns 0, or -EIO if GL reported an error (glGetError, which is drained). */
int test_scene_draw(struct test_scene *scene, const float view[16], const float projection[16]);
void test_scene_destroy(struct test_scene *scene);

/* Reversed-Z, as a host with GL_EXT_clip_control draws it: the depth texture becomes
 * DEPTH_COMPONENT32F, cleared to 0 and tested GL_GREATER, and each draw runs under
 * glClipControlEXT(GL_LOWER_LEFT, GL_ZERO_TO_ONE) (put back to the default afterwards). Give
 * test_scene_draw a reversed-Z projection (sbfx_reverse_z) and sbfx_frame.clip_depth_mode =
 * SBFX_CLIP_DEPTH_ZERO_TO_ONE. Returns 0, -ENOTSUP without the extension, -EIO if the new
 * depth texture cannot be attached; err says which. */
int test_scene_use_reversed_z(struct test_scene *scene, char *err, size_t n);

/* A scene file's camera (sbfx_scene_camera: the eye circling its target) at time `seconds`:
 * view and projection, near 0.1, far 200. */
#define TEST_SCENE_NEAR 0.1f
#define TEST_SCENE_FAR 200.0f
void test_scene_camera(const sbfx_scene_camera *camera, double seconds, float aspect, float view[16],
                       float projection[16]);
/* The demo camera, a scene's camera when it has none (sbfx_scene_camera_get): a slow orbit
 * (about 3.4 degrees per second) around the origin, 8.5 m away, 2.6 m high, looking at
 * (0, 1.5, 0); 50 degree vertical fov. */
void test_scene_orbit_camera(double seconds, float aspect, float view[16], float projection[16]);

/* The daylight of a scene file that gives a `sky` (sbfx_scene_host_get): the sun from its first
 * directional light (none without one), the hemisphere ambient from `ambient` (the lower half
 * 0.45 of it, light from the ground), fog and background from `sky`, everything times the
 * scene's exposure as sbfx's particles are. Without `sky` the fixed daylight below (a day
 * scene's light colours are the particles' irradiance, brighter than this ground wants), its
 * sun turned to the scene's first directional light (shadows fall from there). Takes effect at
 * the next draw. */
void test_scene_set_daylight(struct test_scene *scene, const sbfx_scene_host *host);
/* The sun's visibility through the smoke: sbfx_render_shadow_map's texture and view_projection,
 * sampled on unit 0 by the next draws (0: no shadow). */
void test_scene_set_shadow(struct test_scene *scene, GLuint texture, const float view_projection[16]);

/* The fire's lights (sbfx_emitted_lights), shaded with the falloff include/sbfx.h gives, times the
 * exposure; up to TEST_SCENE_POINT_LIGHTS, the rest ignored; 0: none. Takes effect at the next
 * draw. */
void test_scene_set_point_lights(struct test_scene *scene, const sbfx_point_light *lights, int count);

/* The scene's light, for hosts that light particles to match: the direction sunlight
 * travels in (world space, unit), the sun's colour and the sky ambient (linear RGB). */
void test_scene_light(float direction[3], float color[3], float ambient[3]);

#endif
