/* A canvas pixel to the ground point it shows (web.h): the camera's ray through the pixel's
 * centre, met with the plane y = 0. The view matrix's rotation is orthonormal, so the ray is
 * made from its rows without inverting anything. */
#include <math.h>

#include "web/web.h"

bool web_pick_ground(const sbfx_scene_camera *camera, double t, int width, int height, double x, double y,
                     float out[3])
{
    if (width <= 0 || height <= 0) return false;
    float view[16], proj[16];
    test_scene_camera(camera, t, (float)width / (float)height, view, proj);
    /* the direction in view space: x_ndc / P00, y_ndc / P11, -1 (the projection is symmetric) */
    double nx = x / width * 2.0 - 1.0, ny = 1.0 - y / height * 2.0;
    double d_view[3] = {nx / proj[0], ny / proj[5], -1.0};
    /* world = R^T view, with R's rows (column-major: R[row][col] = view[col * 4 + row]) */
    double dir[3], eye[3];
    for (int i = 0; i < 3; i++) {
        dir[i] = view[i * 4 + 0] * d_view[0] + view[i * 4 + 1] * d_view[1] + view[i * 4 + 2] * d_view[2];
        eye[i] = -(view[i * 4 + 0] * view[12] + view[i * 4 + 1] * view[13] + view[i * 4 + 2] * view[14]);
    }
    if (dir[1] >= -1e-6) return false; /* level with or above the horizon */
    double s = -eye[1] / dir[1];
    if (s * sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]) > TEST_SCENE_FAR) return false;
    out[0] = (float)(eye[0] + s * dir[0]);
    out[1] = 0.0f;
    out[2] = (float)(eye[2] + s * dir[2]);
    return true;
}
