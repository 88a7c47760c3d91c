/* CPU reference of the particle opacity, in double precision, usable without GL. Tests, the
 * probe and the benchmark compare the GPU against these functions; with ref/reference_frame.h
 * (whole frames) and ref/lit_ref.h (lit smoke) it makes libsbfx_ref.a, which is not part of the
 * runtime library. The tables the module builds at load are in src/tables/tables.h. Pure libc. */
#ifndef SBFX_REFERENCE_H
#define SBFX_REFERENCE_H

#include <stddef.h>
#include <stdint.h>
#include "sbfx.h"
#include "tables/tables.h"

/* ---- opacity (docs/design.md §2.1) ----------------------------------------------------------- */

/* One spherical particle in view space (camera at origin, looking down -z, so center[2] < 0
 * for a particle in front of the camera). tau is the extinction at the centre. */
typedef struct sbfx_ref_particle {
    double center[3];
    double radius;
    double tau;
} sbfx_ref_particle;

/* The pixel's situation: ray = direction through the pixel scaled so that ray[2] == -1
 * (i.e. x/(-z), y/(-z), -1); opaque_depth = distance along -z of the opaque surface (Zs);
 * near = near-plane distance; soft_scale = depth range of the soft-particle fade (soft mode). */
typedef struct sbfx_ref_pixel {
    double ray[3];
    double opaque_depth;
    double near;
    double soft_scale;
} sbfx_ref_pixel;

/* Opacity alpha in [0,1] of one particle for one pixel, in the given mode (DEFAULT = EXACT, the
 * module's default).
 * Always finite; a particle with a NaN/Inf input or radius <= 0 gives 0. */
double sbfx_ref_opacity(sbfx_opacity_mode mode, const sbfx_ref_particle *p, const sbfx_ref_pixel *px);
/* Optical depth (the exponent) instead of alpha; +inf never returned (clamped to 1e30). */
double sbfx_ref_optical_depth(sbfx_opacity_mode mode, const sbfx_ref_particle *p,
                              const sbfx_ref_pixel *px);
/* The length of the pixel's ray inside the particle, clipped as the mode clips it (exact: near
 * plane and opaque surface along the true ray; spherical: the parallel ray's chord; planar and
 * soft: the whole chord 2w where the billboard is drawn). particle.frag's `chord`. */
double sbfx_ref_chord(sbfx_opacity_mode mode, const sbfx_ref_particle *p, const sbfx_ref_pixel *px);
/* ∫_a^b sqrt(h + u^2) du, stable as h -> 0 (h >= 0). */
double sbfx_ref_chord_integral(double h, double a, double b);
/* RTR soft-particle contrast curve: 0.5*(2x)^p for x<0.5 else 1-0.5*(2(1-x))^p, x clamped. */
double sbfx_ref_soft_fade(double x, double power);

#endif
