#!/bin/sh
# On a desktop (X11 or Wayland): the camera with sbfx's effects in a glimagesink window; a click
# starts the scene's first effect on the ground under the pointer (docs/hosts/gstreamer.md).
# Environment: VIDEO (/dev/video0), SCENE (the installed explosion), CAMERA (the source element
# and caps; e.g. CAMERA=videotestsrc without a camera).
: "${VIDEO:=/dev/video0}" "${SCENE:=/usr/local/share/sbfx/scenes/explosion.cfg}"
: "${CAMERA:=v4l2src device=$VIDEO}"
# shellcheck disable=SC2086 # CAMERA is a pipeline fragment: gst-launch-1.0 joins its words
exec gst-launch-1.0 $CAMERA ! videoconvert ! glupload ! sbfx scene="$SCENE" ! glimagesink
