/* WGS-84 conversions (geodesy.h). Geodetic to ECEF is closed form; ECEF to geodetic iterates
 * Bowring's latitude with the height written so that it holds at the poles too
 * (h = p cos(lat) + z sin(lat) - a^2 / N). */
#include "net/common/geodesy.h"

#include <math.h>

#define E2 (WGS84_F * (2.0 - WGS84_F)) /* first eccentricity squared */
#define DEG (M_PI / 180.0)

/* Prime vertical radius of curvature at a latitude whose sine is s. */
static double prime_radius(double s)
{
    return WGS84_A / sqrt(1.0 - E2 * s * s);
}

void geodetic_to_ecef(double lat_deg, double lon_deg, double alt_m, double out[3])
{
    double sl = sin(lat_deg * DEG), cl = cos(lat_deg * DEG);
    double n = prime_radius(sl);
    out[0] = (n + alt_m) * cl * cos(lon_deg * DEG);
    out[1] = (n + alt_m) * cl * sin(lon_deg * DEG);
    out[2] = (n * (1.0 - E2) + alt_m) * sl;
}

void ecef_to_geodetic(const double p[3], double *lat_deg, double *lon_deg, double *alt_m)
{
    double r = hypot(p[0], p[1]);
    double lat = atan2(p[2], r * (1.0 - E2)), h = 0.0;
    for (int i = 0; i < 6; i++) { /* converges quadratically: 6 is ample at any height */
        double sl = sin(lat), cl = cos(lat), n = prime_radius(sl);
        h = r * cl + p[2] * sl - WGS84_A * WGS84_A / n;
        lat = atan2(p[2], r * (1.0 - E2 * n / (n + h)));
    }
    double sl = sin(lat), cl = cos(lat);
    *lat_deg = lat / DEG;
    *lon_deg = atan2(p[1], p[0]) / DEG;
    *alt_m = r * cl + p[2] * sl - WGS84_A * WGS84_A / prime_radius(sl);
}

void geo_frame_init(struct geo_frame *f, double lat_deg, double lon_deg, double alt_m)
{
    double sl = sin(lat_deg * DEG), cl = cos(lat_deg * DEG);
    double so = sin(lon_deg * DEG), co = cos(lon_deg * DEG);
    geodetic_to_ecef(lat_deg, lon_deg, alt_m, f->origin);
    const double east[3] = {-so, co, 0.0}, north[3] = {-sl * co, -sl * so, cl}, up[3] = {cl * co, cl * so, sl};
    for (int k = 0; k < 3; k++) f->east[k] = east[k], f->north[k] = north[k], f->up[k] = up[k];
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void geo_frame_enu(const struct geo_frame *f, const double ecef[3], double enu[3])
{
    const double d[3] = {ecef[0] - f->origin[0], ecef[1] - f->origin[1], ecef[2] - f->origin[2]};
    enu[0] = dot(f->east, d);
    enu[1] = dot(f->north, d);
    enu[2] = dot(f->up, d);
}

void geo_frame_scene(const struct geo_frame *f, const double ecef[3], double scene[3])
{
    double enu[3];
    geo_frame_enu(f, ecef, enu);
    scene[0] = enu[0];
    scene[1] = enu[2];
    scene[2] = -enu[1];
}

double geo_frame_distance(const struct geo_frame *f, const double ecef[3])
{
    return sqrt((ecef[0] - f->origin[0]) * (ecef[0] - f->origin[0]) +
                (ecef[1] - f->origin[1]) * (ecef[1] - f->origin[1]) +
                (ecef[2] - f->origin[2]) * (ecef[2] - f->origin[2]));
}
