#version 300 es
// particle.frag, part 7 of 7: opacity, the table probe, main and its outputs
// 1 - exp(-x) without losing the small values to cancellation.
float opacity_from_depth(float x)
{
    return x < 1e-3 ? x * (1.0 - 0.5 * x) : 1.0 - exp(-x);
}

#ifdef TABLE_PROBE
uniform vec2 u_probe;            // kelvin, cos theta
void main()
{
    vec3 rgb = vec3(0.0);
    float p = 0.0;
#ifdef MEDIUM_EMITS
    rgb = blackbody(u_probe.x);
#endif
#ifdef MEDIUM_SCATTERS
    p = phase(u_probe.y);
#endif
    o_color = vec4(rgb, p);
}
#else
void main()
{
#ifdef OPACITY_FLOOR
    o_color = vec4(0.01, 0.01, 0.01, 0.05);   // the cheapest fragment that still blends
#ifdef HAS_DISTORTION_TARGET
    o_distortion = vec4(0.0);
#endif
#ifdef HAS_MOTION_TARGET
    o_velocity = vec4(0.0);
#endif
    return;
#endif
    vec3 c = v_center_radius.xyz;
    float r = v_center_radius.w;
    // ndc = 2 gl_FragCoord / size - 1, ray.xy = (ndc + P[8], P[9]) / (P[0], P[5]): folded on the CPU
    vec3 ray = vec3(gl_FragCoord.xy * u_ray_map.xy + u_ray_map.zw, -1.0);
    float e = texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r;
    float zs = e > 0.0 ? u_near / e : 1e30;   // no surface: nothing clips the ray
    float intensity = v_detail.w;

    float tau_scale = 1.0;
    float detail = 0.5;
#ifdef HAS_DETAIL
    detail = detail_sample(c, r, ray);
#if defined(MEDIUM_SCATTERS) || defined(MEDIUM_EMITS)
    tau_scale = detail_density_scale(detail, intensity, u_detail_strength);
#endif
#ifdef MEDIUM_EMITS
    detail = detail_fire_temperature(detail, particle_rho(c, r, ray), intensity, u_detail_strength);
#endif
#endif
    tau_scale *= intensity;
    float chord;
    float depth = optical_depth(c, r, ray, zs, chord) * tau_scale;
    float alpha = opacity_from_depth(depth);   // what emits (and scatters)
    float coverage = alpha;                    // what absorbs: the same, but for fire's soot
#ifdef MEDIUM_EMITS
    float cooled = 1.0 - u_temperature.z * (1.0 - intensity);
    float glow = 1.0;                          // the share of the opacity that glows
#ifdef HAS_DETAIL   // soot is part of the detail's look: strength 0 (or no detail) has none
    glow = fire_glow_share(detail, intensity, u_detail_strength);
    float soot = u_detail_strength * fire_soot(detail, cooled, intensity);
    coverage = opacity_from_depth(depth * (1.0 + u_temperature.w * (1.0 - glow)) +
                                  soot * u_tau * tau_scale * (chord * chord / (2.0 * r)));
#endif
#endif
#ifdef OPACITY_SOFT
    // RTR's soft particle: the flat billboard's alpha faded by the depth left behind it.
    float fade = soft_fade((zs + c.z) / (u_soft_scale > 0.0 ? u_soft_scale : r));
    alpha *= fade;
    coverage *= fade;
#endif
    mediump vec3 light = vec3(0.0);
    float shade = 1.0;
#if defined(MEDIUM_SCATTERS) && defined(HAS_DETAIL) && !defined(LIGHTING_LIT)
    shade = detail_light_scale(detail, u_detail_strength);   // lit smoke shades by its own maps
#endif
    mediump vec3 fire = vec3(0.0);
#if defined(FIRE_LIGHT) && !defined(LIGHTING_LIT)   // lit media add it in lit_scattered
    fire = fire_scattered(ray, c);
#endif
#if defined(MEDIUM_SCATTERS) && defined(LIGHT_PER_PARTICLE)
    light += u_albedo_color * (shade * (v_light + fire));
#elif defined(MEDIUM_SCATTERS) && defined(LIGHTING_LIT)
    light += u_albedo_color * lit_scattered(ray, c, r, tau_scale);
#elif defined(MEDIUM_SCATTERS)
    light += u_albedo_color * (shade * (in_scattered(ray, c) + fire));
#endif
#ifdef MEDIUM_EMITS
    light += emitted((u_temperature.x + u_temperature.y * detail) * cooled) * glow;
#endif
#ifdef MEDIUM_HEAT
    // Heat neither absorbs nor lights: it adds a screen offset, two decorrelated detail
    // samples shaped by the particle's opacity profile (zero where the sphere is clipped). The
    // shimmer is the detail's turbulence, so it scales with the detail strength like every
    // medium's perturbation: 0 leaves the picture behind the heat as it was (docs/look.md).
#ifdef HAS_DETAIL
    // the second sample as at a centre moved by (0.37, 0.61) r across the view: the same window
    // shifted by half of that (the window spans 2r)
    vec3 shifted = detail_coordinate(c, r, ray) - vec3(vec2(0.185, 0.305) * u_detail_window, 0.0);
    vec2 noise = u_detail_strength * (vec2(detail, detail_fetch(u_detail, shifted).r) - 0.5);
#else
    vec2 noise = v_detail.xy - 0.5;   // without the volume: one random direction per particle
#endif
    o_color = vec4(0.0);
#ifdef HAS_DISTORTION_TARGET
    o_distortion = vec4(2.0 * u_heat_strength * alpha * noise, 0.0, 0.0);
#endif
#ifdef HAS_MOTION_TARGET
    o_velocity = vec4(0.0);
#endif
#else
    o_color = vec4(light * alpha, coverage);
#ifdef HAS_DISTORTION_TARGET
    o_distortion = vec4(0.0, 0.0, 0.0, coverage);   // shimmer behind this particle is covered
#endif
#ifdef HAS_MOTION_TARGET
    o_velocity = vec4(v_velocity * coverage, -c.z * coverage, coverage);
#endif
#endif
}
#endif
