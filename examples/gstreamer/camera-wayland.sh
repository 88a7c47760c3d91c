#!/bin/sh
# A kiosk in a Wayland compositor, as a plain user: `cage -- camera-wayland.sh` (or any
# compositor's session). The camera, sbfx's effects over it, waylandsink in the window the
# compositor gives it (cage: the whole output; scaled to it where the compositor offers
# wp_viewporter, centred otherwise); a tap on the screen starts the scene's first effect on the
# ground under it (docs/hosts/gstreamer.md). Not fullscreen=true: GStreamer 1.22's waylandsink
# then finds no window size in cage and stops.
# Environment: VIDEO (/dev/video0), SCENE (the installed explosion), CAMERA (the source element
# and caps).
: "${VIDEO:=/dev/video0}" "${SCENE:=/usr/local/share/sbfx/scenes/explosion.cfg}"
: "${CAMERA:=v4l2src device=$VIDEO ! video/x-raw,width=640,height=480}"
# shellcheck disable=SC2086 # CAMERA is a pipeline fragment: gst-launch-1.0 joins its words
exec gst-launch-1.0 $CAMERA ! videoconvert ! glupload \
    ! sbfx scene="$SCENE" detail-from-input=true \
    ! gldownload ! videoconvert ! waylandsink
