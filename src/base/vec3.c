/* A 3-vector to unit length (a zero vector stays zero): directional lights, the look-at matrix. */
#include <math.h>
#include "base/base.h"

void sbfx_normalize3(float v[3])
{
    float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (len > 0) v[0] /= len, v[1] /= len, v[2] /= len;
}
