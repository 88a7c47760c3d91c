#version 300 es
// One particle along the light: exp of the exact model's optical depth of the linearly falling
// density tau (1 - |x - c| / r) over the whole chord at distance d from the centre,
// tau (w - d^2 asinh(w / d) / r) with w = sqrt(r^2 - d^2): tau r through the centre, 0 at the
// rim. The map blends r, g, b by multiplication (dst * src) and a by MIN, so the order does not
// matter:
//   r: the transmittance, the product of exp(-depth);
//   g: the product of exp(-depth x z), z the centre's map depth: log g / log r is the
//      optical-depth-weighted mean depth of what absorbs (a chord's mean is its centre);
//   b: the product of exp(-depth x (z^2 + the chord's own variance in map depth)): with the
//      mean, the spread of the absorbing along the light;
//   a: the nearest map depth where any particle begins (the front of its chord).
// The chord's variance along itself, s from its middle: int s^2 rho / int rho, rho = 1 -
// sqrt(d^2 + s^2) / r over |s| <= w; int s^2 rho = 2 w^3 / 3 - (w (2 w^2 + d^2) r - d^4 asinh(w / d)) / 4r.
precision highp float;

in vec2 v_offset;
flat in vec2 v_radius_tau;
flat in vec2 v_depth;

out vec4 o_transmittance;

void main()
{
    float r = v_radius_tau.x;
    float d = length(v_offset);
    if (d >= r) discard;
    float w = sqrt((r - d) * (r + d));
    // asinh(w / d) = log((w + r) / d); d^2 times it goes to 0 with d (d is kept above 0 so
    // that the product stays 0 there rather than 0 * inf).
    float h = d * d;
    float asinh_wd = log((w + r) / max(d, 1e-30 * r));
    float m0 = max(w - h * asinh_wd / r, 0.0);
    float depth = v_radius_tau.y * m0;
    float m2 = max(2.0 * w * w * w / 3.0 - (w * (2.0 * w * w + h) * r - h * h * asinh_wd) / (4.0 * r), 0.0);
    float variance = m0 > 0.0 ? m2 / m0 * v_depth.y * v_depth.y : 0.0;
    float z = v_depth.x;
    o_transmittance = vec4(exp(-depth), exp(-depth * z), exp(-depth * (z * z + variance)), z - v_depth.y * w);
}
