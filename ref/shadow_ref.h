/* CPU reference of the host's transmittance shadow map (sbfx_render_shadow_map), in double
 * precision: the particles seen along parallel rays of a directional light. Pure libc. */
#ifndef SBFX_SHADOW_REF_H
#define SBFX_SHADOW_REF_H

#include "reference.h"

/* Optical depth of one particle of the exact model (density tau (1 - |x - c| / r)) along its
 * whole chord at distance d from the centre: tau (w - d^2 asinh(w / d) / r), w = sqrt(r^2 - d^2);
 * tau r through the centre, 0 from the rim on. */
double sbfx_ref_chord_depth(double tau, double r, double d);

/* Transmittance at world point p along a light travelling in unit direction `direction`:
 * the product over particles (world-space centres) of exp(-chord depth), where d is the
 * distance of the particle's centre from the light's ray through p. */
double sbfx_ref_shadow_transmittance(const sbfx_ref_particle *particles, size_t count,
                                     const double direction[3], const double p[3]);

/* The map's four values on the light's ray through p (shadow.frag): r = that transmittance,
 * g = the product of exp(-chord depth x z), z the centre's map depth, b = the product of
 * exp(-chord depth x (z^2 + the chord's variance along itself, in map depth)), a = the least map
 * depth where a particle's chord begins (1 where none is). A point x's map depth is
 * depth_row . (x, 1) (the host's matrix: (view_projection x).z * 0.5 + 0.5). */
void sbfx_ref_shadow_texel(const sbfx_ref_particle *particles, size_t count, const double direction[3],
                           const double p[3], const double depth_row[4], double out[4]);

/* What a host makes of the map at a receiver of map depth `depth` (docs/embedding.md,
 * smoke_visibility): 1 in front of where the smoke begins (a) or where there is none; else the
 * optical depth -log r spread evenly over mean -+ sqrt(3) sd (a uniform spread of that mean and
 * variance: mean = log g / log r, mean of squares log b / log r), begun no earlier than a, and
 * the share of it in front of the receiver: r^share. Behind all of it: r. Where r < 1e-4 (the
 * moments are not known to half precision) all of it is in front. */
double sbfx_ref_shadow_visibility(const double texel[4], double depth);

/* The exact transmittance from the light to the point p: each particle's chord only as far as p
 * (the antiderivative of its linear density along the ray). */
double sbfx_ref_shadow_transmittance_to(const sbfx_ref_particle *particles, size_t count,
                                        const double direction[3], const double p[3]);

#endif
