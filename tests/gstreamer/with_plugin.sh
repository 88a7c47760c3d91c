#!/bin/sh
# Runs COMMAND with the build's GStreamer element and GstGL headless (tests/run.sh's gstreamer
# suites): GST_PLUGIN_PATH at BUILD/gstreamer (libgstsbfx.so), LD_LIBRARY_PATH at BUILD (its
# libsbfx.so.1, for the process and for GStreamer's plugin scanner), a registry of the build's own
# (written atomically, so suites running at once may share it), and GST_GL_PLATFORM=egl
# GST_GL_WINDOW=egl-device unless the environment says otherwise (shared/notes: surfaceless and
# gbm find no display without /dev/dri). GST_GL_API passes through (gles2: OpenGL ES).
# Usage: tests/gstreamer/with_plugin.sh BUILD COMMAND [ARGS...]
build=${1:?usage: with_plugin.sh BUILD COMMAND...}
shift
case $build in /*) ;; *) build=$PWD/$build ;; esac
mkdir -p "$build/tests/gstreamer"
export GST_PLUGIN_PATH="$build/gstreamer"
export LD_LIBRARY_PATH="$build${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export GST_REGISTRY="$build/tests/gstreamer/registry.bin"
export GST_GL_PLATFORM="${GST_GL_PLATFORM:-egl}" GST_GL_WINDOW="${GST_GL_WINDOW:-egl-device}"
exec "$@"
