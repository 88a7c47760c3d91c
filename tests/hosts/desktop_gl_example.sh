#!/bin/sh
# The desktop OpenGL example host (examples/desktop-gl/host.c, docs/hosts/desktop-gl.md) as a user
# runs it: an OpenGL 3.3 core profile context on Mesa surfaceless, its own GLSL 330 scene, sbfx's
# explosion over it; it checks its own picture and exits 0 when the explosion shows, sbfx drew into
# an RGBA16F particle target and no GL error is left. Usage: tests/hosts/desktop_gl_example.sh BUILD
build=${1:-build}
bin="$build/examples/sbfx-desktop-gl"
if [ ! -x "$bin" ]; then
    echo "not ok - desktop-gl-example/runs: $bin was not built (make test-hosts)"
    exit 0
fi
if out=$(timeout -k 5 120 "$bin" 2>&1); then
    echo "ok - desktop-gl-example/runs ($(printf '%s\n' "$out" | tail -n 1))"
else
    echo "not ok - desktop-gl-example/runs: exit status $?: $(printf '%s' "$out" | tail -n 3 | tr '\n' ' ')"
fi
