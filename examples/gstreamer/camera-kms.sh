#!/bin/sh
# A kiosk without a compositor: a V4L2 camera, sbfx's effects over it (its luma also feeding the
# effects' detail), full screen through DRM/KMS (docs/hosts/gstreamer.md). GL runs offscreen on
# the GPU's EGL device; kmssink scans the frames out. Taps need a touch screen's events in a
# compositor: here the scene's timeline (or an application's `trigger`) starts the effects.
# Environment: VIDEO (/dev/video0), SCENE (the installed explosion), CAMERA (the source element
# and caps), KMSSINK (kmssink's properties: driver-name=NAME where kmssink does not know the
# driver, force-modesetting=true where the display's planes cannot scale the video, as vkms's).
: "${VIDEO:=/dev/video0}" "${SCENE:=/usr/local/share/sbfx/scenes/explosion.cfg}"
: "${CAMERA:=v4l2src device=$VIDEO ! video/x-raw,width=640,height=480}"
export GST_GL_PLATFORM=egl GST_GL_WINDOW=egl-device
# shellcheck disable=SC2086 # CAMERA, KMSSINK: pipeline fragments; gst-launch-1.0 joins its words
exec gst-launch-1.0 $CAMERA ! videoconvert ! glupload \
    ! sbfx scene="$SCENE" detail-from-input=true \
    ! gldownload ! videoconvert ! kmssink $KMSSINK
