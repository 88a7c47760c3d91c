/* CPU reference renderer of whole particle frames: see reference_frame.h.
 *
 * Every function here mirrors one of particle.frag's, in the same order of operations, so that
 * the difference between this and the GPU is the model and the precision, never a forgotten
 * term. Pure libc + reference.h. */
#include "reference_frame.h"
#include "base/float16.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FOUR_PI 12.566370614359172

/* IEEE half rounding (nearest even) where the shader has a mediump value, else nothing. */
static double mp(const sbfx_rf_frame *f, double v)
{
    return f->precision == SBFX_RF_MEDIUMP ? (double)(sbfx_float16)v : v;
}

static double clampd(double x, double lo, double hi)
{
    return x > lo ? (x < hi ? x : hi) : lo; /* NaN -> lo */
}

bool sbfx_rf_particle_valid(const sbfx_rf_particle *p)
{
    for (int i = 0; i < 3; i++)
        if (!isfinite(p->center[i]) || !isfinite(p->detail[i])) return false;
    return isfinite(p->radius) && p->radius > 0.0 && isfinite(p->intensity) &&
           (unsigned)p->medium < SBFX_MEDIUM_COUNT;
}

/* ---- order ------------------------------------------------------------------------------ */

/* sort.c's key: the float distance's IEEE bits, inverted so that far comes first. The float
 * arithmetic is the same expression on the same float inputs, so the keys are bit-identical. */
static uint32_t sort_key(const sbfx_rf_particle *p)
{
    float c0 = (float)p->center[0], c1 = (float)p->center[1], c2 = (float)p->center[2];
    float distance = sqrtf(c0 * c0 + c1 * c1 + c2 * c2);
    uint32_t bits;
    memcpy(&bits, &distance, sizeof(bits));
    return ~bits;
}

/* Insertion sort by ascending key, stable: the radix sort's result, with no allocation. */
void sbfx_rf_sort(const sbfx_rf_particle *particles, int count, int *order)
{
    for (int i = 0; i < count; i++) {
        uint32_t key = sort_key(&particles[i]);
        int at = i;
        while (at > 0 && sort_key(&particles[order[at - 1]]) > key) {
            order[at] = order[at - 1];
            at--;
        }
        order[at] = i;
    }
}

/* ---- per fragment ----------------------------------------------------------------------- */

void sbfx_rf_pixel_ray(const sbfx_rf_frame *f, int x, int y, double ray[3])
{
    double ndc_x = (x + 0.5) / f->width * 2.0 - 1.0, ndc_y = (y + 0.5) / f->height * 2.0 - 1.0;
    ray[0] = (ndc_x + f->projection[2]) / f->projection[0];
    ray[1] = (ndc_y + f->projection[3]) / f->projection[1];
    ray[2] = -1.0;
}

static int wrap(int i, int n)
{
    int m = i % n;
    return m < 0 ? m + n : m;
}

/* GL LINEAR + REPEAT on one axis: texel-centre convention, the two texels and the weight. */
static void linear_taps(double coord, int n, int *i0, int *i1, double *frac)
{
    double x = coord * n - 0.5, fl = floor(x);
    *frac = x - fl;
    /* fmod keeps huge coordinates (a long-running time axis) inside int range */
    double base = fmod(fl, (double)n);
    *i0 = wrap((int)base, n);
    *i1 = wrap(*i0 + 1, n);
}

static double detail_texel(const sbfx_rf_frame *f, int x, int y, int t)
{
    size_t n = (size_t)f->detail_size;
    return f->detail[((size_t)t * n + (size_t)y) * n + (size_t)x];
}

/* texture(u_detail, uvw).r, trilinear with REPEAT on all three axes. *spread (when not NULL):
 * the most that rounding each weight by `rounding` can move it. The value is multilinear in the
 * three weights, so along one axis it moves by at most rounding x the largest difference of the
 * cell's edges along that axis; the axes add. */
static double detail_lookup(const sbfx_rf_frame *f, const double uvw[3], double rounding, double *spread)
{
    int x0, x1, y0, y1, t0, t1;
    double fx, fy, ft;
    linear_taps(uvw[0], f->detail_size, &x0, &x1, &fx);
    linear_taps(uvw[1], f->detail_size, &y0, &y1, &fy);
    linear_taps(uvw[2], f->detail_frames, &t0, &t1, &ft);
    double slice[2], edge[3] = {0.0, 0.0, 0.0}, v[2][2][2];
    for (int s = 0; s < 2; s++)
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++) v[s][j][i] = detail_texel(f, i ? x1 : x0, j ? y1 : y0, s ? t1 : t0);
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            edge[0] = fmax(edge[0], fabs(v[a][b][1] - v[a][b][0]));
            edge[1] = fmax(edge[1], fabs(v[a][1][b] - v[a][0][b]));
            edge[2] = fmax(edge[2], fabs(v[1][a][b] - v[0][a][b]));
        }
    if (spread) *spread = rounding * (edge[0] + edge[1] + edge[2]);
    for (int s = 0; s < 2; s++) {
        double a = v[s][0][0] * (1 - fx) + v[s][0][1] * fx;
        double b = v[s][1][0] * (1 - fx) + v[s][1][1] * fx;
        slice[s] = a * (1 - fy) + b * fy;
    }
    return slice[0] * (1 - ft) + slice[1] * ft;
}


/* detail_sample(): the particle's window of the volume, 0..1 across its billboard. */
static double detail_sample(const sbfx_rf_frame *f, const sbfx_rf_particle *p, const sbfx_rf_medium *m,
                            const double ray[3], double *spread)
{
    if (spread) *spread = 0.0;
    if (!f->detail || f->detail_size < 1 || f->detail_frames < 1) return 0.5;
    const double *c = p->center;
    double zc = -c[2], uvw[3];
    for (int k = 0; k < 2; k++) {
        double local = (ray[k] * zc - c[k]) / (2.0 * p->radius) + 0.5;
        uvw[k] = p->detail[k] + local * m->detail_window;
    }
    uvw[2] = p->detail[2] + f->detail_time;
    return detail_lookup(f, uvw, f->filter_weight_error, spread);
}

static double phase(const sbfx_rf_frame *f, sbfx_medium medium, double cos_theta, double g)
{
    if (f->phase_tables[medium])
        return sbfx_phase_table_lookup(f->phase_tables[medium], f->phase_table_size, g, cos_theta);
    return sbfx_phase(cos_theta, g);
}

/* in_scattered(): single scattering of every light toward the eye at the particle centre. */
static void in_scattered(const sbfx_rf_frame *f, sbfx_medium medium, const double c[3], const double ray[3],
                         double sum[3])
{
    double len = sqrt(ray[0] * ray[0] + ray[1] * ray[1] + ray[2] * ray[2]);
    double to_eye[3] = {-ray[0] / len, -ray[1] / len, -ray[2] / len};
    for (int k = 0; k < 3; k++) sum[k] = mp(f, f->ambient[k]);
    int n = f->light_count < SBFX_RF_MAX_LIGHTS ? f->light_count : SBFX_RF_MAX_LIGHTS;
    for (int i = 0; i < n; i++) {
        const sbfx_rf_light *l = &f->lights[i];
        double travel[3] = {l->vector[0], l->vector[1], l->vector[2]}, falloff = 1.0;
        if (l->vector[3] > 0.5) {
            double d[3] = {c[0] - l->vector[0], c[1] - l->vector[1], c[2] - l->vector[2]};
            double d2 = fmax(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], SBFX_RF_MIN_LIGHT_D2);
            for (int k = 0; k < 3; k++) travel[k] = d[k] / sqrt(d2);
            falloff = 1.0 / d2;
        }
        double cos_theta = travel[0] * to_eye[0] + travel[1] * to_eye[1] + travel[2] * to_eye[2];
        double ph = mp(f, phase(f, medium, cos_theta, f->media[medium].phase_g));
        /* the 4 pi is folded into the colours the shader gets (float uniforms) */
        for (int k = 0; k < 3; k++)
            sum[k] = mp(f, sum[k] + (double)((float)l->color[k] * (float)FOUR_PI) * (falloff * ph));
    }
}

static void blackbody(const sbfx_rf_frame *f, double kelvin, double rgb[3])
{
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (!(kelvin > 0.0)) return;
    double t = fmin(kelvin, 1e7);
    if (f->blackbody_table)
        sbfx_blackbody_table_lookup(f->blackbody_table, f->blackbody_table_size, f->blackbody_lo, f->blackbody_hi, t,
                                    rgb);
    else if (f->cmf)
        sbfx_blackbody_rgb(f->cmf, t, f->blackbody_norm, rgb);
}

static double frame_exposure(const sbfx_rf_frame *f) { return f->exposure > 0.0 ? f->exposure : 1.0; }

/* emitted(): black body x emission scale x (1 - albedo) x exposure, capped at the radiance
 * ceiling. */
static void emitted(const sbfx_rf_frame *f, const sbfx_rf_medium *m, double kelvin, double e[3])
{
    double bb[3];
    blackbody(f, kelvin, bb);
    /* the shader gets the scale as a float uniform: emission_scale * (1 - albedo) * exposure */
    double scale = (double)((float)(m->emission_scale * (1.0 - m->albedo)) * (float)frame_exposure(f));
    for (int k = 0; k < 3; k++) e[k] = mp(f, fmin(bb[k] * scale, SBFX_RF_RADIANCE_CEILING));
}

/* particle.frag's detail_density_scale: erosion with a threshold rising with age. */
static double detail_density_scale(double detail, double intensity, double strength)
{
    double threshold = SBFX_RF_EROSION_THRESHOLD + SBFX_RF_EROSION_AGE * (1.0 - fmin(fmax(intensity, 0.0), 1.0));
    double eroded = fmin(fmax((detail - threshold) * SBFX_RF_EROSION_SHARPNESS, 0.0), 1.0) * SBFX_RF_EROSION_GAIN;
    return 1.0 + (eroded - 1.0) * strength; /* mix(1, eroded, strength) */
}

/* particle.frag's detail_light_scale: denser detail shades itself. */
static double detail_light_scale(double detail, double strength)
{
    return 1.0 + SBFX_RF_DETAIL_SHADE * (0.5 - detail) * strength;
}

/* particle.frag's particle_rho: distance from the centre in its depth plane / radius. */
static double particle_rho(const sbfx_rf_particle *p, const double ray[3])
{
    double qx = ray[0] * -p->center[2] - p->center[0], qy = ray[1] * -p->center[2] - p->center[1];
    return sqrt(qx * qx + qy * qy) / p->radius;
}

/* Fire's coverage with its soot: 1 - e^-(scale x depth + soot x chord^2 / 2r), scale = 1 + the cool
 * share's soot, soft mode's fade on it as on the emitting alpha a (particle.frag). */
static double fire_coverage(sbfx_opacity_mode mode, const sbfx_ref_particle *rp, const sbfx_ref_pixel *px, double a,
                            double scale, double soot)
{
    double chord = sbfx_ref_chord(mode, rp, px), extra = soot * (chord * chord / (2.0 * rp->radius));
    if (mode != SBFX_OPACITY_SOFT) return -expm1(-(scale * sbfx_ref_optical_depth(mode, rp, px) + extra));
    sbfx_ref_pixel unclipped = *px;   /* soft: the planar alpha times the fade */
    unclipped.opaque_depth = INFINITY;
    double planar = -expm1(-sbfx_ref_optical_depth(SBFX_OPACITY_PLANAR, rp, &unclipped));
    double fade = planar > 0.0 ? a / planar : 0.0;
    return -expm1(-(scale * sbfx_ref_optical_depth(SBFX_OPACITY_PLANAR, rp, &unclipped) + extra)) * fade;
}

/* particle.frag's fire_scattered (mediump): the fire light at the centre, changing across the
 * particle (its centre's depth plane) with the gradient of 1/d² from the fire. */
static void fire_scattered(const sbfx_rf_frame *f, const sbfx_rf_particle *p, const double ray[3], double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    if (!f->fire_light || p->medium == SBFX_FIRE) return;
    double v[8];
    sbfx_fire_scatter_instance(&p->fire, p->center, p->radius, v);
    for (int k = 0; k < 8; k++) v[k] = mp(f, (double)(float)v[k]); /* the instance data, a mediump varying */
    double e[2] = {mp(f, ray[0] * -p->center[2] - p->center[0]), mp(f, ray[1] * -p->center[2] - p->center[1])};
    double factor = mp(f, 1.0 + mp(f, e[0] * v[4] + e[1] * v[5]));
    for (int k = 0; k < 3; k++) out[k] = mp(f, v[k] * factor);
}

/* Only dust, smoke and fire add light and opacity; other media (heat) displace the scene in the
 * composite instead, which this reference does not model. */
static bool shaded(const sbfx_rf_frame *f, const sbfx_rf_particle *p)
{
    return sbfx_rf_particle_valid(p) && f->opacity != SBFX_OPACITY_FLOOR &&
           (p->medium == SBFX_DUST || p->medium == SBFX_SMOKE || p->medium == SBFX_FIRE);
}

/* The particle at one pixel given the detail volume's value there. */
static void shade_with_detail(const sbfx_rf_frame *f, const sbfx_rf_particle *p, const double ray[3],
                              double opaque_distance, double detail, double rgb[3], double *alpha)
{
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    *alpha = 0.0;
    const sbfx_rf_medium *m = &f->media[p->medium];
    bool scatters = m->albedo > 0.0, emits = p->medium == SBFX_FIRE;
    double tau_scale = 1.0;
    if (m->has_detail) {
        tau_scale = detail_density_scale(detail, p->intensity, m->detail_strength);
        if (emits) detail = sbfx_fire_coordinate(detail, particle_rho(p, ray), p->intensity, m->detail_strength);
    }
    tau_scale *= p->intensity;
    /* optical depth is linear in tau in every mode: the scale folds into the particle's tau */
    sbfx_ref_particle rp = {{p->center[0], p->center[1], p->center[2]}, p->radius, m->tau * tau_scale};
    sbfx_ref_pixel px = {{ray[0], ray[1], ray[2]}, opaque_distance, f->near, f->soft_scale};
    double a = sbfx_ref_opacity(f->opacity, &rp, &px), coverage = a;
    if (!(a > 0.0)) return; /* the shader multiplies its light by 0 */
    double cooled = 1.0 - m->cooling * (1.0 - p->intensity);
    /* only the share of the opacity hot enough to glow emits (particle.frag's fire_glow_share) */
    double glow = emits && m->has_detail ? sbfx_fire_glow_share(detail, p->intensity, m->detail_strength) : 1.0;
    /* soot: absorbs without glowing where cool (particle.frag's fire_soot and the cool share's
     * soot, media.fire.soot), with the detail */
    if (emits && m->has_detail)
        coverage = fire_coverage(f->opacity, &rp, &px, a, 1.0 + sbfx_fire_cool_soot(1.0, glow, m->soot),
                                 m->detail_strength * m->tau * tau_scale * sbfx_fire_soot(detail, cooled, p->intensity));
    double light[3] = {0.0, 0.0, 0.0};
    if (scatters) {
        double s[3], fire[3];
        in_scattered(f, p->medium, p->center, ray, s);
        fire_scattered(f, p, ray, fire);
        double shade = m->has_detail ? detail_light_scale(detail, m->detail_strength) : 1.0;
        for (int k = 0; k < 3; k++)
            light[k] = mp(f, light[k] + m->albedo * frame_exposure(f) * m->color[k] * (shade * mp(f, s[k] + fire[k])));
    }
    if (emits) {
        double e[3];
        emitted(f, m, (m->t0 + m->t1 * detail) * cooled, e);
        for (int k = 0; k < 3; k++) light[k] = mp(f, light[k] + e[k] * glow);
    }
    for (int k = 0; k < 3; k++) rgb[k] = light[k] * a;
    *alpha = coverage;
}

void sbfx_rf_shade(const sbfx_rf_frame *f, const sbfx_rf_particle *p, const double ray[3],
                   double opaque_distance, double rgb[3], double *alpha)
{
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    *alpha = 0.0;
    if (!shaded(f, p)) return;
    const sbfx_rf_medium *m = &f->media[p->medium];
    double detail = m->has_detail ? detail_sample(f, p, m, ray, NULL) : 0.5;
    shade_with_detail(f, p, ray, opaque_distance, detail, rgb, alpha);
}

/* sbfx_rf_shade, and in d[] how far the filter's rounded weights can move rgb and alpha: the
 * particle shaded at detail -+ the lookup's spread (every step after the lookup is monotone in
 * the detail over so small a change, so the ends bound it). */
static void shade_bounded(const sbfx_rf_frame *f, const sbfx_rf_particle *p, const double ray[3],
                          double opaque_distance, double rgb[3], double *alpha, double d[4])
{
    rgb[0] = rgb[1] = rgb[2] = *alpha = 0.0;
    d[0] = d[1] = d[2] = d[3] = 0.0;
    if (!shaded(f, p)) return;
    const sbfx_rf_medium *m = &f->media[p->medium];
    double spread = 0.0, detail = m->has_detail ? detail_sample(f, p, m, ray, &spread) : 0.5;
    shade_with_detail(f, p, ray, opaque_distance, detail, rgb, alpha);
    if (!(spread > 0.0)) return;
    for (int s = -1; s <= 1; s += 2) {
        double end[3], a;
        shade_with_detail(f, p, ray, opaque_distance, detail + s * spread, end, &a);
        for (int k = 0; k < 3; k++) d[k] = fmax(d[k], fabs(end[k] - rgb[k]));
        d[3] = fmax(d[3], fabs(a - *alpha));
    }
}

/* ---- whole frame ------------------------------------------------------------------------ */

typedef struct pixel_rect { int x0, x1, y0, y1; } pixel_rect;

/* Range of slope x / (-z) over the sphere (particle.vert's slope_range). */
static void slope_range(double cx, double zc, double r, double out[2])
{
    double denom = (zc - r) * (zc + r);
    double root = r * sqrt(fmax(cx * cx + denom, 0.0));
    out[0] = (cx * zc - root) / denom;
    out[1] = (cx * zc + root) / denom;
}

static void slopes_to_pixels(double s0, double s1, double scale, double offset, int n, int *lo, int *hi)
{
    double a = ((s0 * scale - offset) + 1.0) * 0.5 * n, b = ((s1 * scale - offset) + 1.0) * 0.5 * n;
    double mn = fmin(a, b) - 2.0, mx = fmax(a, b) + 2.0; /* 2 px of margin on each side */
    *lo = mn < 0.0 ? 0 : (mn > n ? n : (int)mn);
    *hi = mx < 0.0 ? -1 : (mx > n - 1 ? n - 1 : (int)mx);
}

/* Pixels the particle can touch (a generous superset of particle.vert's quad); false when the
 * sphere is wholly behind the near plane (the GPU draws no fragment of it either). */
static bool particle_rect(const sbfx_rf_frame *f, const sbfx_rf_particle *p, pixel_rect *out)
{
    double zc = -p->center[2], r = p->radius;
    if (zc + r <= f->near) return false;
    *out = (pixel_rect){0, f->width - 1, 0, f->height - 1};
    if (zc - r <= f->near) return true; /* camera inside or near: the whole grid */
    double sx[2], sy[2];
    slope_range(p->center[0], zc, r, sx);
    slope_range(p->center[1], zc, r, sy);
    slopes_to_pixels(sx[0], sx[1], f->projection[0], f->projection[2], f->width, &out->x0, &out->x1);
    slopes_to_pixels(sy[0], sy[1], f->projection[1], f->projection[3], f->height, &out->y0, &out->y1);
    return out->x0 <= out->x1 && out->y0 <= out->y1;
}

/* The ray passes within the radius of the centre, in front of the camera (depth ignored). */
static bool ray_hits_sphere(const sbfx_rf_particle *p, const double ray[3])
{
    double len = sqrt(ray[0] * ray[0] + ray[1] * ray[1] + ray[2] * ray[2]), u[3];
    for (int k = 0; k < 3; k++) u[k] = ray[k] / len;
    const double *c = p->center;
    double cross[3] = {c[1] * u[2] - c[2] * u[1], c[2] * u[0] - c[0] * u[2], c[0] * u[1] - c[1] * u[0]};
    double dist = sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
    double t0 = c[0] * u[0] + c[1] * u[1] + c[2] * u[2];
    return dist < p->radius && t0 > -p->radius;
}

/* What a pixel carries through "over" or "under" besides its colour: the filter's bound and the
 * target's rounding bound (sbfx_rf_frame's filter_bound and rounding_bound). */
typedef struct pixel_bounds {
    double filter[4], rounding[4];
} pixel_bounds;

/* One blend back to front, C' = rgb + (1 - a) C and T' = (1 - a) T, and what it does to the
 * bounds. The filter's: C' moves by at most d_rgb + (1 - a + d_a) d_C + d_a |C|, T' by d_a T +
 * (1 - a + d_a) d_T. The target's rounding e: C' by e (|rgb| + |C| + |C'|) + (1 - a)(1 + 2e) r_C,
 * T' by e (2 T + T') + (1 - a)(1 + 2e) r_T. */
static void blend_over(double e, const double rgb[3], double a, const double d[4], double c[3], double *t,
                       pixel_bounds *b)
{
    double keep = 1.0 - a + d[3], carry = (1.0 - a) * (1.0 + 2.0 * e);
    for (int k = 0; k < 3; k++) {
        double next = rgb[k] + c[k] * (1.0 - a);
        b->filter[k] = d[k] + keep * b->filter[k] + d[3] * fabs(c[k]);
        b->rounding[k] = e * (fabs(rgb[k]) + fabs(c[k]) + fabs(next)) + carry * b->rounding[k];
        c[k] = next;
    }
    double next = *t * (1.0 - a);
    b->filter[3] = d[3] * *t + keep * b->filter[3];
    b->rounding[3] = e * (2.0 * *t + next) + carry * b->rounding[3];
    *t = next;
}

/* One blend nearest first ("under", particles.c), C' = C + T rgb and T' = (1 - a) T, and what it
 * does to the bounds. The filter's: C' moves by at most d_C + (T + d_T) d_rgb + |rgb| d_T, T' by
 * d_a T + (1 - a + d_a) d_T. The target's rounding e, each rounding at most e of its result: the
 * source, the product T rgb and the sum may round (e (2 T |rgb| + |C'|), to first order in e,
 * with |C| + |C'| for the sum's inputs as the "over" bound had), and what is carried grows by
 * (1 + 3e): C' by e (2 T |rgb| + |C| + |C'|) + (1 + 3e)(r_C + |rgb| r_T); T' as "over"'s, the
 * same blend of alpha: e (2 T + T') + (1 - a)(1 + 2e) r_T, plus the format's floor (the spacing
 * of its smallest values, which a relative e does not cover): "under" multiplies the stored T
 * into every later particle's light, so a T that rounds to 0 or a subnormal loses up to
 * floor x |rgb| of the light behind it (sbfx_rf_frame.target_floor). */
static void blend_under(double e, double floor, const double rgb[3], double a, const double d[4], double c[3],
                        double *t, pixel_bounds *b)
{
    double grow = 1.0 + 3.0 * e;
    for (int k = 0; k < 3; k++) {
        double next = c[k] + *t * rgb[k];
        b->filter[k] = b->filter[k] + (*t + b->filter[3]) * d[k] + fabs(rgb[k]) * b->filter[3];
        b->rounding[k] = e * (2.0 * *t * fabs(rgb[k]) + fabs(c[k]) + fabs(next)) +
                         grow * (b->rounding[k] + fabs(rgb[k]) * b->rounding[3]);
        c[k] = next;
    }
    double next = *t * (1.0 - a);
    b->filter[3] = d[3] * *t + (1.0 - a + d[3]) * b->filter[3];
    b->rounding[3] = e * (2.0 * *t + next) + floor + (1.0 - a) * (1.0 + 2.0 * e) * b->rounding[3];
    *t = next;
}

/* One pixel: the sorted particles that may touch it (order is back to front), blended as the
 * module draws them: back to front, or nearest first where it terminates early (front_to_back). */
static void render_pixel(const sbfx_rf_frame *f, const sbfx_rf_particle *v, const int *order,
                         const pixel_rect *rects, int n, int x, int y, double *out, uint8_t *footprint)
{
    double ray[3], c[3] = {0.0, 0.0, 0.0}, t = 1.0;
    pixel_bounds bounds = {{0.0}, {0.0}};
    sbfx_rf_pixel_ray(f, x, y, ray);
    size_t at = (size_t)y * f->width + x;
    double zs = f->opaque_distance[at];
    bool hit = false;
    for (int j = 0; j < n; j++) {
        int i = f->front_to_back ? n - 1 - j : j;
        const pixel_rect *r = &rects[order[i]];
        if (x < r->x0 || x > r->x1 || y < r->y0 || y > r->y1) continue;
        const sbfx_rf_particle *p = &v[order[i]];
        double rgb[3], a, d[4];
        shade_bounded(f, p, ray, zs, rgb, &a, d);
        if (f->front_to_back) blend_under(f->target_rounding, f->target_floor, rgb, a, d, c, &t, &bounds);
        else blend_over(f->target_rounding, rgb, a, d, c, &t, &bounds);
        if (footprint && !hit) hit = ray_hits_sphere(p, ray);
    }
    memcpy(out, c, sizeof(c));
    out[3] = t;
    if (f->filter_bound) memcpy(&f->filter_bound[4 * at], bounds.filter, sizeof(bounds.filter));
    if (f->rounding_bound) memcpy(&f->rounding_bound[4 * at], bounds.rounding, sizeof(bounds.rounding));
    if (footprint) footprint[(size_t)y * f->width + x] = hit;
}

static void model_blackbody(const void *ctx, double kelvin, double rgb[3]) { blackbody(ctx, kelvin, rgb); }

int sbfx_rf_fire_lights(const sbfx_rf_frame *f, const sbfx_rf_particle *particles, int count, sbfx_fire_gathered *out,
                        int max)
{
    const sbfx_rf_medium *m = &f->media[SBFX_FIRE];
    sbfx_fire_model model = {.tau = m->tau, .t0 = m->t0, .t1 = m->t1, .cooling = m->cooling,
                             .soot = m->soot, .detail_strength = m->has_detail ? m->detail_strength : 0.0,
                             .emission_scale = (double)(float)m->emission_scale * (1.0 - (double)(float)m->albedo),
                             .ceiling = SBFX_RF_RADIANCE_CEILING / frame_exposure(f),
                             .blackbody = model_blackbody, .blackbody_ctx = f};
    sbfx_fire_detail_levels(f->detail, f->detail ? f->detail_size : 0, f->detail_frames, model.detail);
    size_t n = count > 0 ? (size_t)count : 1;
    sbfx_fire_particle *fire = calloc(n, sizeof(*fire));
    sbfx_fire_work *work = calloc(n, sizeof(*work));
    int fires = 0, lights = -1;
    if (fire && work) {
        for (int i = 0; i < count; i++) {
            const sbfx_rf_particle *p = &particles[i];
            if (p->medium != SBFX_FIRE || !sbfx_rf_particle_valid(p)) continue;
            fire[fires++] = (sbfx_fire_particle){{p->center[0], p->center[1], p->center[2]}, p->radius, p->intensity};
        }
        lights = sbfx_fire_gather(&model, fire, fires, work, out, max);
    }
    free(fire), free(work);
    return lights;
}

/* The frame's fire light at each dust or smoke particle of the phase model (the module's
 * particle_fire, src/render/particles.c). */
static int light_by_fire(const sbfx_rf_frame *f, sbfx_rf_particle *valid, int count)
{
    sbfx_fire_gathered lights[SBFX_FIRE_GATHER_MAX];
    int n = sbfx_rf_fire_lights(f, valid, count, lights, SBFX_FIRE_GATHER_MAX);
    if (n < 0) return -1;
    for (int i = 0; i < count; i++) {
        sbfx_rf_particle *p = &valid[i];
        const sbfx_rf_medium *m = &f->media[p->medium];
        memset(&p->fire, 0, sizeof(p->fire));
        if (p->medium == SBFX_FIRE || !(m->albedo > 0.0) || n == 0) continue;
        sbfx_fire_scatter_at(lights, n, frame_exposure(f), p->center, m->phase_g, &p->fire);
    }
    return 0;
}

int sbfx_rf_render_layer(const sbfx_rf_frame *f, const sbfx_rf_particle *particles, int count,
                         double *layer, uint8_t *footprint)
{
    size_t n = count > 0 ? (size_t)count : 1;
    sbfx_rf_particle *valid = calloc(n, sizeof(*valid));
    int *order = calloc(n, sizeof(*order));
    pixel_rect *rects = calloc(n, sizeof(*rects));
    if (!valid || !order || !rects) {
        free(valid), free(order), free(rects);
        return -1;
    }
    int kept = 0, skipped = 0;
    for (int i = 0; i < count; i++) {
        if (!sbfx_rf_particle_valid(&particles[i])) skipped++;
        else valid[kept++] = particles[i]; /* the module keeps input order, then sorts */
    }
    if (f->fire_light && light_by_fire(f, valid, kept) < 0) {
        free(valid), free(order), free(rects);
        return -1;
    }
    sbfx_rf_sort(valid, kept, order);
    for (int i = 0; i < kept; i++)
        if (!particle_rect(f, &valid[i], &rects[i])) rects[i] = (pixel_rect){1, 0, 1, 0};
    for (int y = 0; y < f->height; y++)
        for (int x = 0; x < f->width; x++)
            render_pixel(f, valid, order, rects, kept, x, y, &layer[4 * ((size_t)y * f->width + x)], footprint);
    free(valid), free(order), free(rects);
    return skipped;
}

void sbfx_rf_tone_map(sbfx_tone_map op, const double c[3], double t, const double dst[3], double out[3])
{
    double room[3];
    for (int k = 0; k < 3; k++) {
        out[k] = c[k];
        room[k] = fmax(1.0 - t * (dst ? clampd(dst[k], 0.0, 1.0) : 0.0), 1.0 / 1024.0);
    }
    if (op == SBFX_TONE_MAP_NONE) return;
    if (op == SBFX_TONE_MAP_DEFAULT) op = SBFX_TONE_MAP_FILMIC;
    sbfx_tone_curve curve = sbfx_tone_curve_for(op);
    if (op == SBFX_TONE_MAP_FILMIC) {
        double q[3], x[3];
        for (int k = 0; k < 3; k++) q[k] = out[k] / room[k];
        sbfx_tone_filmic(&curve, q, x);
        for (int k = 0; k < 3; k++) out[k] = room[k] * x[k];
        return;
    }
    if (op == SBFX_TONE_MAP_PER_CHANNEL) {
        for (int k = 0; k < 3; k++) out[k] = room[k] * sbfx_tone_curve_apply(&curve, out[k] / room[k]);
        return;
    }
    double r = fmax(out[0] / room[0], fmax(out[1] / room[1], out[2] / room[2]));
    double scale = r > curve.knee ? sbfx_tone_curve_apply(&curve, r) / r : 1.0;
    for (int k = 0; k < 3; k++) out[k] *= scale;
}

void sbfx_rf_composite(const double *layer, const uint8_t *scene_rgba8, int width, int height, sbfx_tone_map op,
                       double *out_rgb)
{
    size_t n = (size_t)width * (size_t)height;
    for (size_t i = 0; i < n; i++) {
        double c[3], dst[3] = {scene_rgba8[4 * i] / 255.0, scene_rgba8[4 * i + 1] / 255.0,
                               scene_rgba8[4 * i + 2] / 255.0};
        sbfx_rf_tone_map(op, &layer[4 * i], layer[4 * i + 3], dst, c);
        for (int k = 0; k < 3; k++) {
            double v = scene_rgba8[4 * i + k] / 255.0 * layer[4 * i + 3] + c[k];
            out_rgb[3 * i + k] = clampd(v, 0.0, 1.0) * 255.0;
        }
    }
}
