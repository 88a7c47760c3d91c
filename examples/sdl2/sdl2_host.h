/* A complete small SDL2 host for sbfx (docs/hosts/sdl2.md): an OpenGL ES 3.0 window, the
 * host's opaque scene drawn into its own colour and depth textures and shown in the window,
 * sbfx composited over it; explosions on the space key and from an SDL timer.
 *
 * sdl2_host_open() initialises SDL's video and timer, opens the window and its context, makes
 * the scene's framebuffer and program and the sbfx module. Each frame: sdl2_host_handle() for
 * every event, sdl2_host_frame() (scene, sbfx_update, sbfx_render into the window's
 * framebuffer), sdl2_host_present() (swap). All return 0 or -1 with a message on stderr that
 * says what failed. */
#ifndef SBFX_SDL2_HOST_H
#define SBFX_SDL2_HOST_H

#include <SDL.h>
#include <GLES3/gl3.h>
#include <stdbool.h>
#include "sbfx.h"

struct sdl2_host {
    SDL_Window *window;
    SDL_GLContext context;
    int width, height;             /* the window's drawable size in pixels */
    GLuint framebuffer, color, depth; /* the host's scene: RGBA8 colour and 24-bit depth textures */
    GLuint program, vertex_array, vertex_buffer;
    GLint view_projection;
    sbfx *fx;
    const char *effect;            /* what the triggers start ("explosion") */
    SDL_TimerID timer;
    Uint32 timer_event;            /* SDL_RegisterEvents: the timer's trigger */
    int triggers;                  /* explosions started (keys and timer) */
    double time;                   /* seconds of animation: the camera's orbit */
    float view[16], projection[16];
};

/* scene_path NULL: the built-in explosion; effect: the scene's effect the triggers start;
 * timer_ms 0: no timer triggers. */
int sdl2_host_open(struct sdl2_host *h, int width, int height, const char *scene_path, const char *effect,
                   Uint32 timer_ms);
/* Space: an explosion in front of the camera; the timer's event: one at the origin. Returns
 * false when the user asked to quit (window closed, Escape). */
bool sdl2_host_handle(struct sdl2_host *h, const SDL_Event *event);
int sdl2_host_frame(struct sdl2_host *h, double dt);
void sdl2_host_present(struct sdl2_host *h);
void sdl2_host_close(struct sdl2_host *h);

#endif
