#version 300 es
// particle.frag, part 5 of 7: light: phase function, lights, fire light, lit smoke
#ifdef MEDIUM_SCATTERS
mediump float phase(float cos_theta)
{
#ifdef PHASE_ANALYTIC
    // Cornette-Shanks, cos_theta between the light's travel and the way to the eye:
    // 3 (1 - g^2) / (8 pi (2 + g^2)) (1 + cos^2) / base^1.5, base = 1 + g^2 - 2 g cos written
    // (1-|g|)^2 + 2|g| (1 - sign(g) cos): no cancellation at the peak (1 - cos is exact there).
    // The constants per medium (src/gl/luts.c); base^-1.5 as a cubed inverse square root.
    float base = max(u_phase_analytic.y + u_phase_analytic.z * (1.0 - u_phase_analytic.w * cos_theta), 1e-6);
    float r = inversesqrt(base);
    return u_phase_analytic.x * (1.0 + cos_theta * cos_theta) * (r * r * r);
#else
    // The table's coordinate (sbfx_phase_coordinate): ln of the base for a peaked function,
    // cos itself for a nearly flat one; then the two entries around it, interpolated here.
    float s = u_phase_warp.x * cos_theta;
    float t = u_phase_warp.z > 0.0 ? log(u_phase_warp.y + u_phase_warp.z * (1.0 - s)) * u_phase_warp.w + u_phase_shift.x
                                   : 0.5 * s + 0.5;
    float pos = clamp(t, 0.0, 1.0) * u_phase_shift.y;
    float i = min(floor(pos), u_phase_shift.y - 1.0);
    float a = texelFetch(u_phase_lut, ivec2(int(i), u_phase_row), 0).r;
    float b = texelFetch(u_phase_lut, ivec2(int(i) + 1, u_phase_row), 0).r;
    return mix(a, b, pos - i);
#endif
}

// Single scattering of every light toward the eye at point p; the 4π (folded into the colours
// by the CPU) makes a light of colour E scattered isotropically give back E. Point lights fall off as 1/d², no closer than 0.5 m
// (a flash inside the particle stays finite).
mediump vec3 in_scattered(vec3 ray, vec3 p)
{
    vec3 to_eye = -normalize(ray);
    mediump vec3 sum = u_ambient;
    for (int i = 0; i < LIGHT_SLOTS; i++) {
        if (i >= u_light_count) break;
        vec4 l = u_light_vector[i];
        vec3 travel = l.xyz;
        float falloff = 1.0;
        if (l.w > 0.5) {
            vec3 d = p - l.xyz;
            float s = inversesqrt(max(dot(d, d), 0.25));
            travel = d * s;
            falloff = s * s;
        }
        sum += u_light_color[i] * (falloff * phase(dot(travel, to_eye)));
    }
    return sum;
}
#endif

#if defined(FIRE_LIGHT) && !defined(LIGHTING_LIT)
// The fire's light (src/sim/fire_light.h, sbfx_fire_scatter_instance): the phase model evaluated at
// the centre on the CPU; across the particle (its centre's depth plane) the first-order change of
// 1/d² from the fire, so smoke above a fireball glows from below. Zero without live fire. In
// mediump, like the light it adds to (the gradient is at most 1 / radius: never negative).
mediump vec3 fire_scattered(vec3 ray, vec3 c)
{
    mediump vec2 e = ray.xy * (-c.z) - c.xy;
    return v_fire * (1.0 + dot(e, v_fire_gradient));
}
#endif

#ifdef LIGHTING_LIT
// The lit-smoke seed, mirrored by ref/lit_ref.c (see there for the texture space). The view
// matrix is the tangent basis of these screen-aligned particles: tangent = view x, bitangent =
// view y, normal = view +z (toward the eye), so a normal-map texel is already a view-space normal.
#ifdef LIT_SHADOW
// Transmittance toward the key light: midpoint samples of the slab density max(0, h - 2|z|)
// over one diameter (1 in texture units, the longest chord of the particle's sphere, which holds
// all of the slab) from the front surface, n = nMin + (N.V)(nMax - nMin) steps (the seed's eq.
// 5.2.5, rounded half up). tau_2r = extinction x diameter. Stops once the optical depth passes
// 20 (transmittance < 2e-9: nothing left to see, the rest is cost).
float lit_shadow(vec3 start, vec3 l, float layer, float lod, float n_dot_v, float tau_2r)
{
    float n = floor(u_steps.x + clamp(n_dot_v, 0.0, 1.0) * u_steps.y);
    if (n < 0.5) return 1.0;
    float dt = 1.0 / n, w = tau_2r * dt, sum = 0.0;
    vec3 step = dt * l, p = start + 0.5 * step;
    for (int k = 0; k < MAX_STEPS; k++) {
        if (float(k) >= n) break;
        sum += max(filtered_array_lod(u_smoke, vec3(p.xy, layer), lod).w - 2.0 * abs(p.z), 0.0);
        if (w * sum > 20.0) break;
        p += step;
    }
    return exp(-w * sum);
}
#endif

// albedo is applied by the caller: B (ambient + (1 - dampening) sum_i E_i F_i (wrap_i + back_i)
// S_i), wrap_i = max(0, N.L/(1+w) + w/(1+w)) (N the filtered normal 2 rgb - 1 as it is, not
// renormalised), back_i = translucency x map x max(0, -V.L) with V the particle's centre toward
// the eye (the seed prints min(0, E.L) x map, which would darken smoke lit from behind; its
// magnitude brightens the thin rim of backlit smoke and adds nothing for a light in front). The
// key light, the frame's first (the scene's first light), is lit at the relief's front surface
// p (direction and falloff F_0 = 1/max(d², 1/4) per pixel; one at p itself has no direction,
// only the wrap's bias lights it) and self-shadowed (S_0, the march). The others (S_i = 1) are
// seen from the particle's centre: direction, falloff and back-light per particle
// (particle.vert), the wrap per pixel.
// With FIRE_LIGHT the fire's light at the particle's centre (isotropic for lit media: no phase
// function) joins the lights' sum, per particle like the fill lights. It rides in v_lit and
// v_view's free components: that keeps 32 registers on both Malis (a vec3 varying of its own
// took the G52 to 64, the per-pixel gradient both), at 9.29 G52 / 3.00 G610 cycles against the
// lit variant's 9.29 / 2.48 (docs/gpus.md; the G610's varying unit bounds it). The fire is
// gathered per particle without a direction, so it lights the relief the way a light wrapped
// all around it would: through the brightness map, not the normals, unshadowed, with the
// lights' dampening (ref/lit_ref.c, sbfx_lit_fire_radiance).
vec3 lit_scattered(vec3 ray, vec3 c, float r, float tau_scale)
{
    vec2 q = ray.xy * (-c.z);
    vec2 st = (q - c.xy) / (2.0 * r) + 0.5;
    float layer = v_lit.x, lod = v_lit.y;
    vec4 a = filtered_array_lod(u_smoke, vec3(st, layer), lod);   // normal * 0.5 + 0.5, height
    vec2 maps = filtered_array_lod(u_smoke, vec3(st, layer + 1.0), lod).xy;   // brightness, translucency
    vec3 wn = a.xyz * (2.0 * u_wrap.x) - u_wrap.x;     // N / (1 + w)
    float translucency = u_translucency * maps.y;
    vec3 sum = vec3(0.0);
#if LIGHT_SLOTS > 1
    for (int i = 1; i < LIT_SLOTS; i++) {
        if (i >= u_light_count) break;
        vec4 f = v_fill[i - 1];
        sum += u_light_color[i] * (f.w * max(dot(wn, f.xyz) + u_wrap.y, 0.0) + translucency * v_fill_back[i - 1]);
    }
#endif
    if (u_light_count > 0) {
        vec4 lv = u_light_vector[0];
        bool point = lv.w > 0.5;
        vec3 d = point ? lv.xyz - vec3(q, c.z + r * a.w) : -lv.xyz;
        float s = inversesqrt(max(dot(d, d), 1e-24));
        vec3 l = d * s;
        float key = (point ? min(s * s, 4.0) : 1.0) *
                    (max(dot(wn, l) + u_wrap.y, 0.0) + translucency * max(-dot(v_view.xyz, l), 0.0));
#ifdef LIT_SHADOW
        key *= lit_shadow(vec3(st, 0.5 * a.w), l, layer, lod, dot(wn, v_view.xyz) * u_wrap.z, u_tau * tau_scale * 2.0 * r);
#endif
        sum += u_light_color[0] * key;
    }
#ifdef FIRE_LIGHT
    sum += vec3(v_lit.zw, v_view.w);   // the fire's light at the centre, like the fill lights
#endif
    return maps.x * (u_ambient + u_direct * sum);
}
#endif

