#!/bin/sh
# A video file in, the same video with sbfx's effects out as H.264 in MP4 (docs/hosts/gstreamer.md).
# The effects follow the file's timestamps, not the machine's speed: the same file gives the
# same recording. Headless: GstGL on an EGL device, no display needed.
# Usage: record-mp4.sh IN OUT.mp4 [SCENE]   (SCENE: the installed explosion)
in=${1:?usage: record-mp4.sh IN OUT.mp4 [SCENE]}
out=${2:?usage: record-mp4.sh IN OUT.mp4 [SCENE]}
scene=${3:-/usr/local/share/sbfx/scenes/explosion.cfg}
export GST_GL_PLATFORM=egl GST_GL_WINDOW=egl-device
exec gst-launch-1.0 -e filesrc location="$in" ! decodebin ! videoconvert ! glupload \
    ! sbfx scene="$scene" \
    ! gldownload ! videoconvert ! x264enc ! mp4mux ! filesink location="$out"
