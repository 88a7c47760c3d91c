/* CPU reference of the particle opacity (docs/design.md §2.1), all four modes, in double precision.
 *
 * View space: camera at the origin looking down -z; depths (opaque_depth Zs, near n, the
 * centre depth zc = -center[2]) are positive distances along -z.
 *
 * Conventions shared by every mode (the "bad particle is skipped" rule of docs/design.md §2.2):
 *  - a NaN anywhere in the particle or the pixel, an infinite centre, radius, tau, ray, near or
 *    soft_scale, radius < SMALLEST_RADIUS, or tau <= 0 gives optical depth 0 and opacity 0;
 *  - opaque_depth may be +inf (nothing opaque, the depth texture's far clear value); -inf means
 *    the opaque surface covers everything, which also gives 0;
 *  - near < 0 is treated as 0: the camera sees nothing behind itself;
 *  - the ray is scaled so that ray[2] == -1 (a ray with ray[2] >= 0 never goes forward: 0);
 *  - optical depth is clamped to OD_MAX, so alpha = -expm1(-od) reaches 1 exactly, never NaN.
 *
 * Every chord is written relative to the particle centre (clamp(Zs - zc, -w, w) rather than
 * min(Zs, zc + w)): the clamped terms are of the size of the particle, so a small particle far
 * away (zc = 1e4, r = 0.05) keeps its full relative precision. */
#include <float.h>
#include <math.h>
#include "reference.h"

/* Optical depth never exceeds this (+inf would make downstream products NaN). */
#define OD_MAX 1e30
/* sqrt(DBL_MIN) ≈ 1.5e-154: a smaller radius is treated as no particle. Its optical depth is
 * at most 2*tau*r, invisible for any sane tau, and its square (which shaders and callers form)
 * would underflow to 0 and turn d/r-type ratios into inf or NaN. */
#define SMALLEST_RADIUS 1.4916681462400413e-154
/* The closed-form chord integral is a difference of two terms of the size of the chord; when the
 * mean density along the clipped chord falls below this fraction of the centre density, the
 * difference would cancel and a quadrature of a cancellation-free integrand is used instead. */
#define CLOSED_FORM_MIN_MEAN 0.05
#define LN2 0.69314718055994530942

static double clamp(double x, double lo, double hi)
{
    /* Written so that a NaN x falls to lo rather than propagating. */
    return x > lo ? (x < hi ? x : hi) : lo;
}

static int finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static int inputs_valid(const sbfx_ref_particle *p, const sbfx_ref_pixel *px)
{
    if (!p || !px) return 0;
    if (!finite3(p->center) || !finite3(px->ray)) return 0;
    if (!isfinite(p->radius) || !isfinite(p->tau) || !isfinite(px->near)) return 0;
    if (!isfinite(px->soft_scale) || isnan(px->opaque_depth)) return 0;
    if (!(p->radius >= SMALLEST_RADIUS) || !(p->tau > 0.0)) return 0;
    return px->ray[2] < 0.0;
}

/* Half-length of the chord at distance d from the centre: sqrt(r-d)*sqrt(r+d) is the
 * cancellation-free sqrt(r^2 - d^2) of docs/design.md §2.1, and the two square roots cannot overflow or
 * underflow the way the product (r-d)(r+d) can for extreme radii. Requires 0 <= d < r. */
static double half_chord(double r, double d)
{
    return sqrt(r - d) * sqrt(r + d);
}

/* ---- spherical, planar, soft: the seed's parallel-ray model ---------------------------- */

/* Parallel-ray geometry: the ray through the billboard point Q = ray * zc, at distance d from the
 * centre, chord half-length w. Returns 0 if the ray misses the sphere. */
static int parallel_geometry(const sbfx_ref_particle *p, const sbfx_ref_pixel *px, double *zc,
                             double *d, double *w)
{
    double scale = 1.0 / -px->ray[2]; /* ray[2] == -1 per the contract; tolerate other scales */
    *zc = -p->center[2];
    double qx = px->ray[0] * scale * *zc, qy = px->ray[1] * scale * *zc;
    *d = hypot(qx - p->center[0], qy - p->center[1]);
    if (!(*d < p->radius)) return 0; /* also catches an overflowed (inf or NaN) d */
    *w = half_chord(p->radius, *d);
    return 1;
}

/* Radial profile factor (1 - d/r), as (r - d)/r which is exact near d = r. */
static double profile(double r, double d)
{
    return (r - d) / r;
}

static double od_clamp(double od)
{
    if (!(od > 0.0)) return 0.0; /* negative zero, NaN */
    return od < OD_MAX ? od : OD_MAX;
}

static double od_spherical(const sbfx_ref_particle *p, const sbfx_ref_pixel *px, double near)
{
    double zc, d, w;
    if (!parallel_geometry(p, px, &zc, &d, &w)) return 0.0;
    double back = clamp(px->opaque_depth - zc, -w, w); /* Zs = +inf clamps to w */
    double front = clamp(near - zc, -w, w);
    double ds = back - front;
    if (!(ds > 0.0)) return 0.0;
    return od_clamp(p->tau * profile(p->radius, d) * ds);
}

/* Classic billboard: the full chord 2w with the radial profile, drawn as a plane at zc with the
 * depth test on and clipped by the near plane, hence the clipping and popping artifacts. */
static double od_planar(const sbfx_ref_particle *p, const sbfx_ref_pixel *px, double near)
{
    double zc, d, w;
    if (!parallel_geometry(p, px, &zc, &d, &w)) return 0.0;
    if (zc < near) return 0.0;               /* the plane is clipped by the near plane */
    if (px->opaque_depth < zc) return 0.0;   /* the plane is behind the opaque surface */
    return od_clamp(p->tau * profile(p->radius, d) * 2.0 * w);
}

/* ---- exact: perspective ray, exact integral of tau*(1 - |x - c|/r) ---------------------- */

/* 16-point Gauss–Legendre nodes and weights on [-1, 1] (positive half; symmetric). */
static const double gauss16[8][2] = {
    {0.98940093499164993, 0.027152459411754095},
    {0.94457502307323258, 0.062253523938647893},
    {0.86563120238783174, 0.095158511682492785},
    {0.75540440835500303, 0.12462897125553387},
    {0.61787624440264375, 0.14959598881657673},
    {0.45801677765722739, 0.16915651939500254},
    {0.28160355077925891, 0.18260341504492359},
    {0.09501250983763744, 0.1894506104550685},
};

/* The chord integrals below work in units of the radius (r = 1): every length is divided by r
 * first, so neither h = dist^2 nor any product can overflow or underflow, whatever the scale of
 * the particle; the caller multiplies the result by r. */

/* Density profile 1 - sqrt(h + s^2) along the ray, rewritten as (w-s)(w+s)/(1 + q) with
 * w^2 = 1 - h, which has no cancellation where the density is small (near the surface). */
static double stable_profile(double h, double w, double s)
{
    double q = hypot(sqrt(h), s);
    return (w - s) * (w + s) / (1.0 + q);
}

/* ∫_a^b (1 - sqrt(h+s^2)) ds for a clipped interval where the density is at most about
 * 2*CLOSED_FORM_MIN_MEAN everywhere (the profile is concave, so its maximum is at most twice
 * its mean). There sqrt(h+s^2) >= 0.9 on [a, b], the integrand's branch points ±i sqrt(h) lie
 * far outside the interval relative to its length (Bernstein ellipse parameter >= 4), and
 * 16-point Gauss–Legendre is exact to rounding; tests check it against brute-force sums. */
static double profile_integral_quadrature(double h, double w, double a, double b)
{
    double mid = 0.5 * (a + b), half = 0.5 * (b - a), sum = 0.0;
    for (int i = 0; i < 8; i++) {
        double x = gauss16[i][0] * half, wt = gauss16[i][1];
        sum += wt * (stable_profile(h, w, mid - x) + stable_profile(h, w, mid + x));
    }
    return sum * half;
}

/* ∫_a^b (1 - sqrt(h + s^2)) ds, -w <= a < b <= w, w = sqrt(1 - h), unit radius. The closed
 * form is (b - a) - chord_integral; it is exact where the density is not small, and where it is
 * small the two terms nearly cancel, so the quadrature of the stable integrand takes over. */
static double profile_integral(double h, double w, double a, double b)
{
    double length = b - a;
    double closed = length - sbfx_ref_chord_integral(h, a, b);
    if (closed > CLOSED_FORM_MIN_MEAN * length) return closed;
    return profile_integral_quadrature(h, w, a, b);
}

/* Unit vector along the pixel ray. |ray| >= 1 because ray[2] is about -1; computed with a
 * scaled norm so that huge x/y cannot overflow. */
static void unit_ray(const double ray[3], double u[3])
{
    double len = hypot(hypot(ray[0], ray[1]), ray[2]);
    for (int i = 0; i < 3; i++) u[i] = ray[i] / len;
}

static double od_exact(const sbfx_ref_particle *p, const sbfx_ref_pixel *px, double near)
{
    const double *c = p->center;
    double u[3];
    unit_ray(px->ray, u);
    double t0 = c[0] * u[0] + c[1] * u[1] + c[2] * u[2]; /* ray parameter of the closest point */
    /* Ray–centre distance from the perpendicular vector c - t0 u, not sqrt(|c|^2 - t0^2): the
     * latter cancels completely for a small particle far away (zc = 1e4, r = 0.05). */
    double e[3] = {c[0] - t0 * u[0], c[1] - t0 * u[1], c[2] - t0 * u[2]};
    double dist = hypot(hypot(e[0], e[1]), e[2]);
    double r = p->radius;
    if (!(dist < r)) return 0.0;
    double cos_z = -u[2]; /* > 0: ray parameter t reaches depth t * cos_z */
    /* Near plane and opaque surface as ray parameters relative to the closest point, in units
     * of r (see above), clamped to the chord [-w, w]. The half chord is taken in world units,
     * where r - dist is exact near the surface, and then scaled: half_chord(1, dist / r) would
     * carry the rounding of dist / r into 1 - dist / r and lose the grazing rays' precision. */
    double dist_r = dist / r, w = half_chord(r, dist) / r;
    double a = clamp((near / cos_z - t0) / r, -w, w);
    double b = clamp((px->opaque_depth / cos_z - t0) / r, -w, w);
    if (!(b > a)) return 0.0;
    return od_clamp(p->tau * r * profile_integral(dist_r * dist_r, w, a, b));
}

/* ---- public ------------------------------------------------------------------------------ */

double sbfx_ref_soft_fade(double x, double power)
{
    if (!(power > 0.0) || !isfinite(power)) power = 1.0; /* degenerate contrast: linear */
    x = clamp(x, 0.0, 1.0);                                /* NaN -> 0 (fully faded) */
    if (x < 0.5) return 0.5 * pow(2.0 * x, power);
    return 1.0 - 0.5 * pow(2.0 * (1.0 - x), power);
}

/* Soft particles: the planar billboard faded by the depth difference to the opaque surface
 * instead of the hard depth test; the near-plane clip (popping) stays. */
static double alpha_soft(const sbfx_ref_particle *p, const sbfx_ref_pixel *px, double near)
{
    double zc = -p->center[2];
    if (zc < near) return 0.0;
    sbfx_ref_pixel unclipped = *px;
    unclipped.opaque_depth = INFINITY; /* the fade replaces the depth test */
    double od = od_planar(p, &unclipped, near);
    double scale = px->soft_scale > 0.0 ? px->soft_scale : p->radius;
    double fade = sbfx_ref_soft_fade((px->opaque_depth - zc) / scale, 2.0);
    return -expm1(-od) * fade;
}

double sbfx_ref_optical_depth(sbfx_opacity_mode mode, const sbfx_ref_particle *p,
                              const sbfx_ref_pixel *px)
{
    if (!inputs_valid(p, px)) return 0.0;
    double near = px->near > 0.0 ? px->near : 0.0;
    switch (mode) {
    case SBFX_OPACITY_PLANAR: return od_planar(p, px, near);
    case SBFX_OPACITY_SOFT: {
        /* The soft fade multiplies alpha, not the exponent: report the equivalent exponent. */
        double alpha = alpha_soft(p, px, near);
        return alpha < 1.0 ? od_clamp(-log1p(-alpha)) : OD_MAX;
    }
    case SBFX_OPACITY_DEFAULT: /* the module's default */
    case SBFX_OPACITY_EXACT: return od_exact(p, px, near);
    case SBFX_OPACITY_SPHERICAL:
    default: return od_spherical(p, px, near);
    }
}

double sbfx_ref_chord(sbfx_opacity_mode mode, const sbfx_ref_particle *p, const sbfx_ref_pixel *px)
{
    if (!inputs_valid(p, px)) return 0.0;
    double near = px->near > 0.0 ? px->near : 0.0;
    if (mode == SBFX_OPACITY_EXACT || mode == SBFX_OPACITY_DEFAULT) { /* od_exact's chord */
        const double *c = p->center;
        double u[3];
        unit_ray(px->ray, u);
        double t0 = c[0] * u[0] + c[1] * u[1] + c[2] * u[2];
        double e[3] = {c[0] - t0 * u[0], c[1] - t0 * u[1], c[2] - t0 * u[2]};
        double dist = hypot(hypot(e[0], e[1]), e[2]), r = p->radius;
        if (!(dist < r)) return 0.0;
        double cos_z = -u[2], w = half_chord(r, dist) / r;
        double a = clamp((near / cos_z - t0) / r, -w, w);
        double b = clamp((px->opaque_depth / cos_z - t0) / r, -w, w);
        return b > a ? (b - a) * r : 0.0;
    }
    double zc, d, w;
    if (!parallel_geometry(p, px, &zc, &d, &w)) return 0.0;
    if (mode == SBFX_OPACITY_PLANAR || mode == SBFX_OPACITY_SOFT) {
        if (zc < near || (mode == SBFX_OPACITY_PLANAR && px->opaque_depth < zc)) return 0.0;
        return 2.0 * w;
    }
    double ds = clamp(px->opaque_depth - zc, -w, w) - clamp(near - zc, -w, w);
    return ds > 0.0 ? ds : 0.0;
}

double sbfx_ref_opacity(sbfx_opacity_mode mode, const sbfx_ref_particle *p, const sbfx_ref_pixel *px)
{
    if (!inputs_valid(p, px)) return 0.0;
    double alpha;
    if (mode == SBFX_OPACITY_SOFT) {
        alpha = alpha_soft(p, px, px->near > 0.0 ? px->near : 0.0);
    } else {
        /* -expm1(-od): accurate for thin particles, exactly 1 once od > ~37. */
        alpha = -expm1(-sbfx_ref_optical_depth(mode, p, px));
    }
    return clamp(alpha, 0.0, 1.0);
}

/* h * asinh(|u| / sqrt(h)), which tends to 0 as h -> 0 and must not overflow on the way. */
static double h_asinh_term(double h, double abs_u)
{
    if (!(h > 0.0)) return 0.0;
    double x = abs_u / sqrt(h);
    if (isfinite(x)) return h * asinh(x); /* asinh is accurate for small and large x alike */
    /* |u| / sqrt(h) overflowed: asinh(x) = log(2x) there, taken apart in logarithms. */
    return h * (log(abs_u) + LN2 - 0.5 * log(h));
}

/* ∫_0^u sqrt(h + s^2) ds = ½(u sqrt(h + u^2) + h asinh(u / sqrt h)), odd in u. */
static double chord_antiderivative(double h, double u)
{
    double abs_u = fabs(u);
    double q = hypot(sqrt(h), abs_u); /* sqrt(h + u^2) without overflow */
    double value = 0.5 * (abs_u * q + h_asinh_term(h, abs_u));
    return u < 0.0 ? -value : value;
}

double sbfx_ref_chord_integral(double h, double a, double b)
{
    /* Outside the contract (NaN, infinite bounds or h, or a result beyond the double range,
     * |a|, |b| > 1e154): 0 rather than NaN/inf. */
    if (!isfinite(h) || !isfinite(a) || !isfinite(b)) return 0.0;
    if (h < 0.0) h = 0.0;
    double value = chord_antiderivative(h, b) - chord_antiderivative(h, a);
    return isfinite(value) ? value : 0.0;
}
