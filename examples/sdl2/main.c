/* sbfx-sdl2: sbfx in an SDL2 window (docs/hosts/sdl2.md). Space starts an explosion, one starts
 * by itself every two seconds; Escape or closing the window quits.
 *   sbfx-sdl2 [--scene FILE] [--effect NAME] [--size WxH] [--frames N] [--every MS]
 * --frames N stops after N frames (0: until closed); --every MS: the timer's period (2000);
 * SDL_VIDEODRIVER=offscreen runs it without a display. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sdl2_host.h"

int main(int argc, char **argv)
{
    const char *scene = NULL, *effect = "explosion";
    int width = 960, height = 540;
    long frames = 0, every_ms = 2000;
    for (int i = 1; i < argc; i++) {
        bool has_value = i + 1 < argc;
        if (strcmp(argv[i], "--scene") == 0 && has_value) scene = argv[++i];
        else if (strcmp(argv[i], "--effect") == 0 && has_value) effect = argv[++i];
        else if (strcmp(argv[i], "--frames") == 0 && has_value) frames = strtol(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--every") == 0 && has_value) every_ms = strtol(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--size") == 0 && has_value && sscanf(argv[i + 1], "%dx%d", &width, &height) == 2) i++;
        else {
            fprintf(stderr, "usage: %s [--scene FILE] [--effect NAME] [--size WxH] [--frames N] [--every MS]\n", argv[0]);
            return 2;
        }
    }
    struct sdl2_host host;
    int rc = sdl2_host_open(&host, width, height, scene, effect, every_ms > 0 ? (Uint32)every_ms : 0);
    Uint64 last = SDL_GetPerformanceCounter();
    for (long frame = 0; rc == 0 && (frames == 0 || frame < frames); frame++) {
        SDL_Event event;
        bool running = true;
        while (SDL_PollEvent(&event)) running = running && sdl2_host_handle(&host, &event);
        if (!running) break;
        Uint64 now = SDL_GetPerformanceCounter();
        double dt = (double)(now - last) / (double)SDL_GetPerformanceFrequency();
        last = now;
        rc = sdl2_host_frame(&host, dt);
        if (rc == 0) sdl2_host_present(&host);
    }
    printf("sbfx-sdl2: %d explosions\n", host.triggers);
    sdl2_host_close(&host);
    return rc == 0 ? 0 : 1;
}
