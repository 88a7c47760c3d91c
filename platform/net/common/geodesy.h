/* WGS-84 geodetic <-> geocentric (ECEF) <-> local east-north-up, in double precision.
 *
 * ECEF coordinates are metres from the Earth's centre (6.4e6 and more): a float holds them to
 * half a metre. Everything stays in double until the local offset from the origin is taken; only
 * that offset (metres, at most dis.range) becomes a float for the scene (DESIGN §7's rule for
 * time, applied to space).
 *
 * The scene's frame (y up) at an origin on the ellipsoid:
 *     x = east, y = up, z = -north
 * so a camera looking down -z looks north. */
#ifndef SBFX_GEODESY_H
#define SBFX_GEODESY_H

#define WGS84_A 6378137.0                 /* semi-major axis, m */
#define WGS84_F (1.0 / 298.257223563)     /* flattening */

struct geo_frame {
    double origin[3];                     /* ECEF of the origin */
    double east[3], north[3], up[3];      /* unit vectors in ECEF */
};

void geodetic_to_ecef(double lat_deg, double lon_deg, double alt_m, double out[3]);
/* Latitude and longitude in degrees, height above the ellipsoid in metres (iterated to well
 * under a micrometre for points from the deep sea to orbit; the poles included). */
void ecef_to_geodetic(const double p[3], double *lat_deg, double *lon_deg, double *alt_m);

void geo_frame_init(struct geo_frame *f, double lat_deg, double lon_deg, double alt_m);
/* East, north, up of an ECEF point, metres from the origin. */
void geo_frame_enu(const struct geo_frame *f, const double ecef[3], double enu[3]);
/* The scene's x, y, z (east, up, -north) of an ECEF point. */
void geo_frame_scene(const struct geo_frame *f, const double ecef[3], double scene[3]);
/* Straight-line distance of an ECEF point from the origin, m. */
double geo_frame_distance(const struct geo_frame *f, const double ecef[3]);

#endif
