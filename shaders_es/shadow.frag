#version 300 es
// One particle's transmittance along the light: exp of the exact model's optical depth of the
// linearly falling density tau (1 - |x - c| / r) over the whole chord at distance d from the
// centre, tau (w - d^2 asinh(w / d) / r) with w = sqrt(r^2 - d^2): tau r through the centre, 0
// at the rim. The map blends by multiplication (dst * src), so the order does not matter.
precision highp float;

in vec2 v_offset;
flat in vec2 v_radius_tau;

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
    float depth = v_radius_tau.y * max(w - h * log((w + r) / max(d, 1e-30 * r)) / r, 0.0);
    o_transmittance = vec4(exp(-depth));
}
