/* The host's shadow map, computed per point in double precision (ref/shadow_ref.h). */
#include "shadow_ref.h"

#include <math.h>

double sbfx_ref_chord_depth(double tau, double r, double d)
{
    if (!(d < r)) return 0.0;
    double w = sqrt((r - d) * (r + d));
    double h_asinh = d > 0.0 ? d * d * asinh(w / d) : 0.0; /* -> 0 with d */
    return tau * fmax(w - h_asinh / r, 0.0);
}

double sbfx_ref_shadow_transmittance(const sbfx_ref_particle *particles, size_t count,
                                     const double direction[3], const double p[3])
{
    double depth = 0.0;
    for (size_t i = 0; i < count; i++) {
        const sbfx_ref_particle *q = &particles[i];
        double v[3], along = 0.0, d2 = 0.0;
        for (int k = 0; k < 3; k++) v[k] = q->center[k] - p[k];
        for (int k = 0; k < 3; k++) along += v[k] * direction[k];
        for (int k = 0; k < 3; k++) {
            double off = v[k] - along * direction[k];
            d2 += off * off;
        }
        depth += sbfx_ref_chord_depth(q->tau, q->radius, sqrt(d2));
    }
    return exp(-depth);
}
