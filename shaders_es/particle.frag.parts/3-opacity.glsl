#version 300 es
// particle.frag, part 3 of 7: the ray integral and the opacity models
float soft_fade(float x)
{
    x = clamp(x, 0.0, 1.0);
    return x < 0.5 ? 2.0 * x * x : 1.0 - 2.0 * (1.0 - x) * (1.0 - x);
}

// u sqrt(h + u^2) + h asinh(u / sqrt(h)), the antiderivative along the chord; the second term
// odd in u and -> 0 as h -> 0 without dividing by sqrt(h): h (ln(|u| + s) - ln(h) / 2), s =
// sqrt(h + u^2) shared by both terms, ln(h) / 2 (half_log_h) by both ends.
float chord_primitive(float h, float half_log_h, float u)
{
    float s = sqrt(h + u * u);
    float v = h <= 1e-30 ? 0.0 : h * (log(abs(u) + s) - half_log_h);
    return u * s + (u < 0.0 ? -v : v);
}

float chord_integral(float h, float a, float b)
{
    float half_log_h = 0.5 * log(h);
    return 0.5 * (chord_primitive(h, half_log_h, b) - chord_primitive(h, half_log_h, a));
}

// Optical depth along this pixel's ray; `ray` has z = -1, zs = opaque distance along -z.
// `chord`: the length of the ray inside the particle, clipped the same way (fire's soot).
float optical_depth(vec3 c, float r, vec3 ray, float zs, out float chord)
{
    float zc = -c.z;
    chord = 0.0;
#ifdef OPACITY_EXACT
    float inv_length = inversesqrt(dot(ray, ray));
    vec3 u = ray * inv_length;
    float t0 = dot(c, u);
    vec3 closest = c - t0 * u;
    float h = dot(closest, closest);
    float dist = sqrt(h);
    if (dist >= r) return 0.0;
    float w = sqrt((r - dist) * (r + dist));
    float to_t = dot(ray, ray) * inv_length;   // distance along -z -> ray parameter: |ray| (ray.z = -1)
    float a = clamp(u_near * to_t - t0, -w, w);
    float b = clamp(zs * to_t - t0, -w, w);
    if (b <= a) return 0.0;
    chord = b - a;
    return u_tau * max((b - a) - chord_integral(h, a, b) / r, 0.0);
#else
    vec2 q = ray.xy * zc;                  // the ray's point in the centre's depth plane
    float d = length(q - c.xy);
    if (d >= r) return 0.0;
    float w = sqrt((r - d) * (r + d));
    float profile = u_tau * (1.0 - d / r);
#if defined(OPACITY_PLANAR) || defined(OPACITY_SOFT)
    if (zc < u_near) return 0.0;           // the flat billboard is clipped by the near plane
#ifdef OPACITY_PLANAR
    if (zs < zc) return 0.0;               // the depth test of a flat billboard
#endif
    chord = 2.0 * w;
    return profile * 2.0 * w;
#else
    float ds = max(0.0, clamp(zs - zc, -w, w) - clamp(u_near - zc, -w, w));
    chord = ds;
    return profile * ds;
#endif
#endif
}

