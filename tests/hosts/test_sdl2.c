/* The SDL2 example host (examples/sdl2/, docs/hosts/sdl2.md) headless: SDL_VIDEODRIVER=offscreen
 * gives an OpenGL ES context through an EGL pbuffer on Mesa. The explosion started by the
 * space key and by the timer draws: the window's pixels change against the frame without
 * effect, the particle target is finite, and no GL error is left. */
#include <stdlib.h>
#include "check.h"
#include "internal.h"
#include "sdl2_host.h"

#define W 320
#define H 180

static int open_host(struct sdl2_host *h, Uint32 timer_ms)
{
    setenv("SDL_VIDEODRIVER", "offscreen", 0);
    if (sdl2_host_open(h, W, H, NULL, "explosion", timer_ms) != 0) {
        bool no_video = h->window == NULL;
        sdl2_host_close(h);
        if (no_video) CHECK_SKIP("SDL's offscreen video driver opened no window with an OpenGL ES 3.0 context");
        return -1;
    }
    return 0;
}

/* The window's pixels after a frame at camera time 0 (read before the swap). */
static void frame_pixels(struct sdl2_host *h, uint8_t *rgba)
{
    h->time = 0.0;
    CHECK(sdl2_host_frame(h, 0.0) == 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    sdl2_host_present(h);
}

static void check_explosion_drawn(struct sdl2_host *h, const uint8_t *before, const char *how)
{
    static uint8_t after[W * H * 4];
    CHECK(sbfx_update(h->fx, 0.3) == SBFX_OK);
    frame_pixels(h, after);
    int changed = 0;
    for (int i = 0; i < W * H; i++) changed += memcmp(&before[4 * i], &after[4 * i], 3) != 0;
    printf("# %s: %d of %d pixels changed\n", how, changed, W * H);
    CHECK(changed > W * H / 50, "%s: only %d pixels changed", how, changed);
    sbfx_counters c;
    sbfx_stats(h->fx, &c);
    CHECK(c.particles_alive > 0 && c.draw_calls > 0, "%s: %d particles, %d draw calls", how, c.particles_alive,
          c.draw_calls);
    static float target[4 * W * H];
    int tw = 0, th = 0;
    CHECK(sbfx_read_particle_target(h->fx, target, 4 * W * H, &tw, &th) == SBFX_OK, "%s", sbfx_last_error(h->fx));
    int bad = 0;
    for (int i = 0; i < 4 * tw * th; i++) bad += !isfinite(target[i]);
    CHECK(bad == 0, "%s: %d particle target values are not finite", how, bad);
    GLenum e = glGetError();
    CHECK(e == GL_NO_ERROR, "%s: GL error 0x%04x", how, e);
}

CHECK_TEST(space_key_starts_an_explosion)
{
    struct sdl2_host h;
    if (open_host(&h, 0) != 0) return;
    printf("# %s, %dx%d drawable\n", (const char *)glGetString(GL_VERSION), h.width, h.height);
    static uint8_t before[W * H * 4];
    frame_pixels(&h, before);
    SDL_Event key = {.type = SDL_KEYDOWN};
    key.key.keysym.sym = SDLK_SPACE;
    CHECK(sdl2_host_handle(&h, &key));
    CHECK(h.triggers == 1, "%d triggers", h.triggers);
    check_explosion_drawn(&h, before, "space key");
    SDL_Event escape = {.type = SDL_KEYDOWN};
    escape.key.keysym.sym = SDLK_ESCAPE;
    CHECK(!sdl2_host_handle(&h, &escape), "Escape did not quit");
    sdl2_host_close(&h);
}

CHECK_TEST(timer_starts_explosions)
{
    struct sdl2_host h;
    if (open_host(&h, 50) != 0) return;
    static uint8_t before[W * H * 4];
    frame_pixels(&h, before);
    SDL_Event event;
    Uint32 start = SDL_GetTicks();
    while (h.triggers == 0 && SDL_GetTicks() - start < 5000)
        if (SDL_WaitEventTimeout(&event, 100)) sdl2_host_handle(&h, &event);
    CHECK(h.triggers >= 1, "the 50 ms timer started nothing in 5 s");
    check_explosion_drawn(&h, before, "timer");
    sdl2_host_close(&h);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
