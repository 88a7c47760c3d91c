/* A tapped pixel's ray onto the ground y = 0 (ground_tap.h). */
#include "ground_tap.h"

#include <math.h>

/* The ray's direction in view space for normalised device coordinates (z = -1: one unit ahead),
 * from the perspective's scales and off-axis terms: clip x = p0 x + p8 z, w = -z. */
static void view_ray(double ndc_x, double ndc_y, const float p[16], double ray[3])
{
    ray[0] = (ndc_x + p[8]) / p[0];
    ray[1] = (ndc_y + p[9]) / p[5];
    ray[2] = -1.0;
}

bool ground_tap(double x, double y, int width, int height, const float view[16], const float projection[16],
                float out[3])
{
    if (width <= 0 || height <= 0 || projection[0] == 0.0f || projection[5] == 0.0f) return false;
    double ndc_x = 2.0 * x / width - 1.0, ndc_y = 1.0 - 2.0 * y / height, r[3], dir[3], eye[3];
    view_ray(ndc_x, ndc_y, projection, r);
    /* view = [R | t]: the world direction is R^T r, the eye -R^T t (column-major: R's row i is
     * view[i], view[4 + i], view[8 + i]) */
    for (int i = 0; i < 3; i++) {
        dir[i] = view[4 * i] * r[0] + view[4 * i + 1] * r[1] + view[4 * i + 2] * r[2];
        eye[i] = -(view[4 * i] * view[12] + view[4 * i + 1] * view[13] + view[4 * i + 2] * view[14]);
    }
    if (!(dir[1] < 0.0) || !(eye[1] > 0.0)) return false; /* level or upward, or the eye below ground */
    double t = -eye[1] / dir[1];
    if (!isfinite(t)) return false;
    out[0] = (float)(eye[0] + t * dir[0]);
    out[1] = 0.0f;
    out[2] = (float)(eye[2] + t * dir[2]);
    return isfinite(out[0]) && isfinite(out[2]);
}
