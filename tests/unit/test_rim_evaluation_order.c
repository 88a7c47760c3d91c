/* Evaluation order and FMA contraction near d = r (issue 25, docs/gpus.md "Root causes of the
 * NVIDIA failures"). A GPU compiler may fuse any multiply-add of particle.frag's optical depth
 * (the spherical and soft/planar profile: q = ray.xy z_c - c.xy, d = length(q), w = sqrt((r - d)
 * (r + d)), tau (1 - d/r) 2w). Here every one of the 16 ways to fuse its four candidates is
 * evaluated in float, for rays across the rims of test_gl_hard_cases' d_near_r particles, and
 * compared with double. No GL.
 *
 * The bound: alpha = 1 - e^-od moves by at most |d od|. od = tau (1 - d/r) 2w with w <= r; each
 * factor carries at most 8 float roundings (2^-24 each) of quantities of size <= 1 relative to
 * its scale, so |d od| <= tau 2 r 8 2^-24 = 0.8 x 4.8e-7 = 3.8e-7 for tau = 0.4 and r <= 1.
 * Against alpha's 1e-4 tolerance in test_gl_hard_cases, it shows the order of evaluation cannot
 * explain an alpha error of 1e-4 there (NVIDIA's 2.9e-4 came from the texture filter). */
#include <math.h>
#include <stdio.h>
#include "check.h"

#define TAU 0.4f
#define NEAR 0.1f
#define BOUND (TAU * 2.0 * 8.0 * 0x1p-24)

enum { FUSE_Q = 1, FUSE_LENGTH = 2, FUSE_W = 4, FUSE_PROFILE = 8, FUSINGS = 16 };

static float depth_float(const float c[4], float rx, float ry, int fuse)
{
    float zc = -c[2], r = c[3];
    float qx = (fuse & FUSE_Q) ? fmaf(rx, zc, -c[0]) : rx * zc - c[0];
    float qy = (fuse & FUSE_Q) ? fmaf(ry, zc, -c[1]) : ry * zc - c[1];
    float d = sqrtf((fuse & FUSE_LENGTH) ? fmaf(qx, qx, qy * qy) : qx * qx + qy * qy);
    if (d >= r) return 0.0f;
    float w = sqrtf((fuse & FUSE_W) ? fmaf(-d, d, r * r) : (r - d) * (r + d));
    float profile = TAU * ((fuse & FUSE_PROFILE) ? fmaf(-d, 1.0f / r, 1.0f) : 1.0f - d / r);
    float ds = fmaxf(0.0f, w - fmaxf(fminf(NEAR - zc, w), -w)); /* nothing opaque behind */
    return profile * ds;
}

static double depth_double(const float c[4], double rx, double ry)
{
    double zc = -(double)c[2], r = c[3], qx = rx * zc - c[0], qy = ry * zc - c[1], d = sqrt(qx * qx + qy * qy);
    if (d >= r) return 0.0;
    double w = sqrt((r - d) * (r + d)), ds = fmax(0.0, w - fmax(fmin(NEAR - zc, w), -w));
    return TAU * (1.0 - d / r) * ds;
}

CHECK_TEST(fusing_any_multiply_add_moves_alpha_by_less_than_the_bound_at_the_rim)
{
    /* the d_near_r_and_beyond particles: centre and radius */
    const float parts[3][4] = {{1.0f, 0.0f, -5.0f, 1.0f}, {-0.25f, 0.0f, -6.0f, 0.5f}, {0.0f, 0.7f, -4.0f, 0.7f}};
    double worst[FUSINGS] = {0}, most = 0.0;
    int rays = 0;
    for (int p = 0; p < 3; p++)
        for (int k = 0; k < 200000; k++, rays++) {
            /* around the rim, d from r (1 - 1e-2) up to r, densest at r */
            double phi = 0.001 * k, t = 1.0 - 1e-2 * pow((k % 1000) / 1000.0, 4.0);
            double zc = -parts[p][2], r = parts[p][3];
            float rx = (float)((parts[p][0] + r * t * cos(phi)) / zc), ry = (float)((parts[p][1] + r * t * sin(phi)) / zc);
            double ref = -expm1(-depth_double(parts[p], rx, ry));
            for (int v = 0; v < FUSINGS; v++) {
                double e = fabs(-expm1(-(double)depth_float(parts[p], rx, ry, v)) - ref);
                worst[v] = fmax(worst[v], e);
                most = fmax(most, e);
            }
        }
    for (int v = 0; v < FUSINGS; v++)
        printf("# fused:%s%s%s%s%s max |alpha - double| %.2e\n", v ? "" : " none", v & FUSE_Q ? " q" : "",
               v & FUSE_LENGTH ? " length" : "", v & FUSE_W ? " w" : "", v & FUSE_PROFILE ? " 1-d/r" : "", worst[v]);
    printf("# %d rays, worst %.2e, bound %.2e\n", rays, most, BOUND);
    CHECK(most <= BOUND, "alpha moved by %g, over the bound %g", most, BOUND);
    CHECK(most > 0.0, "float and double agree exactly: the rays do not reach the rim");
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
