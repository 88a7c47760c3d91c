/* Where a tap on the picture meets the ground (docs/hosts/gstreamer.md, "Triggers"): the ray
 * from the camera through the tapped pixel, intersected with the plane y = 0 of the world.
 * Pure arithmetic on the frame's matrices (column-major, OpenGL's, as sbfx_frame holds them). */
#ifndef SBFX_GST_GROUND_TAP_H
#define SBFX_GST_GROUND_TAP_H

#include <stdbool.h>

/* x, y: the tap in the picture's pixels, (0, 0) its top-left corner, width x height its size.
 * view: world -> view, a rigid transform (sbfx_look_at); projection: a perspective (sbfx_frame's
 * kind, p[11] = -1). Writes the ground point into out and returns true; false when the ray
 * does not come down to the ground in front of the camera (a tap on the sky) or the input is
 * not usable (a size of 0, a degenerate matrix). */
bool ground_tap(double x, double y, int width, int height, const float view[16], const float projection[16],
                float out[3]);

#endif
