#version 300 es
// particle.frag, part 6 of 7: emission: the black body, the radiance ceiling
// -expm1(-x) = 1 - e^-x, accurate for small x too
float expm1_safe(float x)
{
    return abs(x) < 1e-3 ? x * (1.0 + 0.5 * x) : exp(x) - 1.0;
}

#ifdef MEDIUM_EMITS
// Normalised linear sRGB of the black body (luminance 1 at desc.blackbody_max_kelvin); 0 at
// T <= 0. Hotter than 1e7 K the colour no longer changes (Y/T is constant to 1e-5).
vec3 blackbody(float kelvin)
{
    if (!(kelvin > 0.0)) return vec3(0.0);
    float t = min(kelvin, 1e7);
#ifdef BLACKBODY_ANALYTIC
    // Planck x CIE 1931 per band (λ in µm, C2 = hc/k = 14387.77 µm K), like the table's rows.
    vec3 rgb = vec3(0.0);
    for (int i = 0; i < MAX_BANDS; i++) {
        if (i >= u_cmf_count) break;
        float lambda = u_cmf_band[i];
        float x = 14387.77 / (lambda * t);
        if (x > 80.0) continue;                   // e^-x underflows: no light in this band
        float l2 = lambda * lambda;
        rgb += u_cmf_rgb[i] * (exp(-x) / (-expm1_safe(-x) * l2 * l2 * lambda));
    }
    return max(rgb, vec3(0.0));                   // out of gamut: clipped like the table
#else
    // Entries uniform in 1/T, interpolated here (and carried on along the end cells outside the
    // table: Wien's law for ln(Y/T) below it), the clip to the gamut after interpolation.
    float pos = (1.0 / t - u_blackbody_map.x) * u_blackbody_map.y;
    float i = clamp(floor(pos), 0.0, u_blackbody_map.z), f = pos - i;
    vec4 a = texelFetch(u_blackbody, ivec2(int(i), 0), 0);
    vec4 b = texelFetch(u_blackbody, ivec2(int(i) + 1, 0), 0);
    return max(mix(a.rgb, b.rgb, f) * (exp(mix(a.w, b.w, f)) * t), vec3(0.0));
#endif
}

mediump vec3 emitted(float kelvin)
{
    return min(blackbody(kelvin) * u_emission_scale, vec3(RADIANCE_CEILING));
}
#endif

