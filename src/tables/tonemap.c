/* The tone curve of the particles' light (composite.frag's tone_curve, sbfx_tone_map in
 * sbfx.h): the identity up to the knee, then a logarithmic shoulder that reaches 1 at the
 * white point. The shoulder is k + (1 - k) ln(1 + s x) / ln(1 + s x_w), x = (v - k) / (1 - k),
 * and its steepness s makes the curve's slope 1 at the knee (no crease in gradients): that
 * needs s = ln(1 + s x_w), found by fixed-point iteration (it contracts by about 1/s per step).
 * A logarithmic shoulder keeps fire's structure: radiance from 1 up to the ceiling spreads over
 * the top of the display range instead of piling up just under 1 as an exponential one would.
 *
 * filmic (docs/look-fire.md) uses the shoulder u = ln(1 + s x) / ln(1 + s x_w) as
 * k + (1 - k)(2u - u^2): it arrives at 1 with slope 0 at its white point (1024), so the light
 * turns white without a crease; slope 1 at the knee then needs s = ln(1 + s x_w) / 2. */
#include <math.h>
#include "tables/tables.h"

static sbfx_tone_curve tone_curve_with_white(double white, bool smooth_white)
{
    sbfx_tone_curve c = {.knee = SBFX_TONE_KNEE, .white = white, .steepness = 1.0, .smooth_white = smooth_white};
    double x_white = (c.white - c.knee) / (1.0 - c.knee), slope = smooth_white ? 0.5 : 1.0;
    for (int i = 0; i < 60; i++) c.steepness = slope * log1p(c.steepness * x_white);
    c.inverse_log_white = 1.0 / log1p(c.steepness * x_white);
    return c;
}

sbfx_tone_curve sbfx_tone_curve_default(void) { return tone_curve_with_white(SBFX_TONE_WHITE, false); }

sbfx_tone_curve sbfx_tone_curve_for(sbfx_tone_map op)
{
    if (op == SBFX_TONE_MAP_FILMIC || op == SBFX_TONE_MAP_DEFAULT)
        return tone_curve_with_white(SBFX_TONE_FILMIC_WHITE, true);
    return sbfx_tone_curve_default();
}

double sbfx_tone_curve_apply(const sbfx_tone_curve *c, double v)
{
    if (!(v > c->knee)) return v > 0.0 ? v : 0.0;
    double x = (v - c->knee) / (1.0 - c->knee);
    double u = fmin(log1p(c->steepness * x) * c->inverse_log_white, 1.0);
    return c->smooth_white ? c->knee + (1.0 - c->knee) * u * (2.0 - u) : c->knee + (1.0 - c->knee) * u;
}

/* The crossover: each channel takes a share of the channels' mean, goes through the curve, and
 * the share is given back (the inset's exact inverse); clamped to [0, 1]. */
static void tone_crossover(const sbfx_tone_curve *c, const double q[3], double x[3])
{
    const double s = SBFX_TONE_INSET;
    double mean_in = (q[0] + q[1] + q[2]) / 3.0, z[3];
    for (int k = 0; k < 3; k++) z[k] = sbfx_tone_curve_apply(c, (1.0 - s) * q[k] + s * mean_in);
    double mean_out = (z[0] + z[1] + z[2]) / 3.0;
    for (int k = 0; k < 3; k++) x[k] = fmin(fmax((z[k] - s * mean_out) / (1.0 - s), 0.0), 1.0);
}

/* composite.frag's tone_filmic, in double: hue kept while the light fits the display (peak <= 1),
 * then blended over two stops (smoothstep of log2(peak) / 2) into the crossover. */
void sbfx_tone_filmic(const sbfx_tone_curve *c, const double q[3], double x[3])
{
    double peak = fmax(q[0], fmax(q[1], q[2]));
    for (int k = 0; k < 3; k++) x[k] = q[k] > 0.0 ? q[k] : 0.0;
    if (!(peak > c->knee)) return;
    double scale = sbfx_tone_curve_apply(c, peak) / peak, crossed[3];
    for (int k = 0; k < 3; k++) x[k] = q[k] * scale;
    if (peak <= 1.0) return;
    tone_crossover(c, q, crossed);
    double t = fmin(0.5 * log2(peak), 1.0), w = t * t * (3.0 - 2.0 * t);
    for (int k = 0; k < 3; k++) x[k] += (crossed[k] - x[k]) * w;
}
