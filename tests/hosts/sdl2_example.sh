#!/bin/sh
# The SDL2 example program as a user runs it, headless: 60 frames through SDL's offscreen
# driver (its event loop, swaps) with the timer every 20 ms (a full pool refuses some: sbfx logs that on stderr); exit status 0, explosions started. Usage: tests/hosts/sdl2_example.sh BUILD
build=${1:-build}
bin="$build/examples/sbfx-sdl2"
if [ ! -x "$bin" ]; then
    echo "not ok - sdl2-example/runs: $bin was not built (make test-hosts; libsdl2-dev)"
    exit 0
fi
if out=$(SDL_VIDEODRIVER=offscreen "$bin" --size 320x180 --frames 60 --every 20 2>/dev/null | tail -n 1); then
    case "$out" in
        *"sbfx-sdl2: 0 explosions"*) echo "not ok - sdl2-example/runs: the timer started no explosion ($out)" ;;
        *) echo "ok - sdl2-example/runs ($out)" ;;
    esac
else
    echo "not ok - sdl2-example/runs: $(printf '%s' "$out" | tail -n 3 | tr '\n' ' ')"
fi
