/* The tone curve of the particles' light (composite.frag's tone_curve, sbfx_tone_map in
 * sbfx.h): the identity up to the knee, then a logarithmic shoulder that reaches 1 at the
 * white point. The shoulder is k + (1 - k) ln(1 + s x) / ln(1 + s x_w), x = (v - k) / (1 - k),
 * and its steepness s makes the curve's slope 1 at the knee (no crease in gradients): that
 * needs s = ln(1 + s x_w), found by fixed-point iteration (it contracts by about 1/s per step).
 * A logarithmic shoulder keeps fire's structure: radiance from 1 to 64 spreads over a quarter
 * of the display range instead of piling up just under 1 as an exponential one would. */
#include <math.h>
#include "tables.h"

sbfx_tone_curve sbfx_tone_curve_default(void)
{
    sbfx_tone_curve c = {.knee = SBFX_TONE_KNEE, .white = SBFX_TONE_WHITE, .steepness = 1.0};
    double x_white = (c.white - c.knee) / (1.0 - c.knee);
    for (int i = 0; i < 60; i++) c.steepness = log1p(c.steepness * x_white);
    c.inverse_log_white = 1.0 / log1p(c.steepness * x_white);
    return c;
}

double sbfx_tone_curve_apply(const sbfx_tone_curve *c, double v)
{
    if (!(v > c->knee)) return v > 0.0 ? v : 0.0;
    double x = (v - c->knee) / (1.0 - c->knee);
    return fmin(c->knee + (1.0 - c->knee) * log1p(c->steepness * x) * c->inverse_log_white, 1.0);
}
