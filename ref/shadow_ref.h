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

#endif
