/* CPU reference renderer of whole particle frames (docs/design.md §2, §4), in double precision,
 * usable without GL (pure libc + reference.h).
 *
 * It evaluates, per full-resolution pixel, what particle.frag evaluates per particle-target
 * pixel — same ray, same detail lookup, same medium and light model, same emission ceiling —
 * but in double, with the opacity model chosen per frame (EXACT for the benchmark's reference),
 * the black body and the phase function analytic (or, for tests of the GPU tables, through the
 * same tables), and accumulates the particles back to front in the order src/sim/sort.c gives them:
 *     C <- c_i + C (1 - a_i),   T <- T (1 - a_i)      (C = premultiplied light, T = transmittance)
 * or, as the module draws them where it terminates early (front_to_back; render/terminate.c),
 * nearest first: C <- C + T c_i, T <- T (1 - a_i) ("under"; the same in exact arithmetic)
 * then composites over the opaque scene like composite.frag and an RGBA8 framebuffer do, with the
 * same tone mapping of the layer's light (C' = tone_map(C, T)):
 *     out = clamp(scene * T + C', 0, 1) * 255.
 *
 * Modelled: dust, smoke and fire with the phase-function lighting. Not modelled: heat (scene
 * displacement), lit media (lighting = "lit": ref/lit_ref.h is their reference), post effects.
 *
 * Precision can be switched to an emulation of the shader's mediump declarations (IEEE half,
 * _Float16, rounding to nearest even, at exactly the points the shader declares mediump), which
 * is how the tests bound what a Mali-class GPU loses there. */
#ifndef SBFX_REFERENCE_FRAME_H
#define SBFX_REFERENCE_FRAME_H

#include <stdbool.h>
#include <stdint.h>
#include "reference.h"
#include "sim/fire_light.h"

/* particle.frag's per-fragment radiance ceiling (RADIANCE_CEILING). */
#define SBFX_RF_RADIANCE_CEILING 16384.0
/* The detail's perturbation, particle.frag's EROSION_*, FIRE_CORE, FIRE_DETAIL and DETAIL_SHADE
 * (docs/look.md). */
#define SBFX_RF_EROSION_THRESHOLD 0.30
#define SBFX_RF_EROSION_AGE 0.25
#define SBFX_RF_EROSION_SHARPNESS 1.8
#define SBFX_RF_EROSION_GAIN 2.2
#define SBFX_RF_FIRE_CORE SBFX_FIRE_CORE     /* src/sim/fire_light.h: sbfx_fire_coordinate */
#define SBFX_RF_FIRE_DETAIL SBFX_FIRE_DETAIL
#define SBFX_RF_DETAIL_SHADE 1.8
/* The shader's light falloff floor: point lights act no closer than 0.5 m (d² >= 0.25). */
#define SBFX_RF_MIN_LIGHT_D2 0.25

/* A particle in view space, as sbfx_view_particle (internal.h) holds it. */
typedef struct sbfx_rf_particle {
    double center[3];  /* view space, center[2] < 0 in front of the camera */
    double radius;
    double detail[3];  /* detail window origin (u, v) and time offset */
    double intensity;  /* density scale; fire also cools as it falls */
    sbfx_medium medium;
    /* The frame's fire light in-scattered at its centre (sbfx_fire_scatter, src/sim/fire_light.h):
     * filled by sbfx_rf_render_layer when the frame's fire_light is on; zero otherwise. */
    sbfx_fire_scatter fire;
} sbfx_rf_particle;

/* One medium's parameters, as sbfx_medium_params (internal.h) holds them. */
typedef struct sbfx_rf_medium {
    double albedo, tau, phase_g, color[3];
    double detail_strength, detail_window;
    double t0, t1, cooling, emission_scale;
    double soot; /* fire: the cool share's soot (sbfx_fire_cool_soot) */
    /* The GPU program samples the detail volume (it was built with detail_strength > 0); the
     * strength then scales both perturbations (0: none, though the volume is still sampled). */
    bool has_detail;
} sbfx_rf_medium;

/* A light in view space: vector[3] = 0 direction the light travels in, 1 position. */
typedef struct sbfx_rf_light {
    double vector[4];
    double color[3];
} sbfx_rf_light;

typedef enum sbfx_rf_precision {
    SBFX_RF_DOUBLE = 0,  /* the reference */
    SBFX_RF_MEDIUMP,     /* round to IEEE half where particle.frag declares mediump */
} sbfx_rf_precision;

typedef struct sbfx_rf_frame {
    int width, height;             /* pixel grid (full resolution for the reference) */
    double projection[4];          /* P[0], P[5], P[8], P[9] of the GL projection */
    double near;                   /* near-plane distance */
    const double *opaque_distance; /* width*height view distances along -z, row 0 = bottom */
    sbfx_opacity_mode opacity;     /* EXACT for the reference; FLOOR draws nothing here */
    double soft_scale;             /* soft mode's fade range; <= 0: the particle radius */

    sbfx_rf_medium media[SBFX_MEDIUM_COUNT];
    const sbfx_rf_light *lights;
    int light_count;               /* at most SBFX_RF_MAX_LIGHTS are used, like the shader */
    double ambient[3];

    const float *detail;           /* size x size x frames, x fastest; NULL: detail = 0.5 */
    int detail_size, detail_frames;
    double detail_time;            /* sbfx_detail_time(): added to the time coordinate */

    const sbfx_cmf *cmf;           /* black body: analytic Planck x CMF (0 for T <= 0, T capped */
    double blackbody_norm;         /* at 1e7 K like the shader), sbfx_blackbody_norm's scale */
    /* Tables instead of the analytic functions (NULL: analytic). Only tests of the GPU's own
     * tables set these (sbfx_get_tables()); the benchmark's reference is analytic. */
    const float *blackbody_table;  /* see sbfx_blackbody_table */
    int blackbody_table_size;
    double blackbody_lo, blackbody_hi;
    const float *phase_tables[SBFX_MEDIUM_COUNT]; /* per medium (NULL: analytic), its phase_g */
    int phase_table_size;

    sbfx_rf_precision precision;
    /* The detail volume as a GPU's texture unit filters it: each weight off by at most
     * filter_weight_error (2^-(N+1) for N-bit rounding, SBFX_FILTER_BITS; 2^-N for a coordinate
     * snapped down to N bits; 0: in float, like llvmpipe; DESIGN §9). The reference keeps the
     * exact weights; with filter_bound set (width*height*4, like the layer) it also gets, per
     * pixel and channel, how far those weights can move the result: each lookup's value moves by
     * at most filter_weight_error x its cell's largest texel difference along each axis, each
     * particle is shaded at detail -+ that, and the spread is carried through the blending
     * (render_pixel). */
    double filter_weight_error;
    double *filter_bound;
    /* The particle target's storage as the GPU blends into it: every blend's result is stored at
     * that precision. target_rounding is the relative error of one rounding (2^-10 for a half
     * float whose rounding may go to either neighbour; 0: exact, as the reference is). With
     * rounding_bound set (width*height*4) it gets, per pixel and channel, how far those roundings
     * can move the result. A blend C' = rgb + (1 - a) C may round the source, the factor, the
     * product and the sum: it moves by at most e (|rgb| + |C| + |C'|) + (1 - a)(1 + 2e) d_C, and
     * T' = (1 - a) T by e (2 T + T') + (1 - a)(1 + 2e) d_T (blend_over). Front to back,
     * C' = C + T rgb carries the stored T's error into the light behind it: it moves by at most
     * e (2 T |rgb| + |C| + |C'|) + (1 + 3e)(d_C + |rgb| d_T) (blend_under). */
    double target_rounding;
    /* ...and the absolute spacing of its values near 0, which a relative rounding does not cover:
     * 2^-24 for a half float's subnormals (2^-14 on a GPU that flushes them, as ES 3.0 allows);
     * 0: exact. Added to T's bound at every blend. */
    double target_floor;
    double *rounding_bound;
    bool front_to_back;            /* blend nearest first, as early termination draws (above) */
    double exposure;               /* desc.exposure, applied where light is made (0: 1) */
    /* The frame's fire lights its dust and smoke (the module's plan.fire_light: emitting fire and
     * dust or smoke of the phase model in the scene): sbfx_rf_render_layer gathers the frame's
     * fire particles into point lights (sbfx_rf_fire_lights) and in-scatters them. */
    bool fire_light;
} sbfx_rf_frame;

#define SBFX_RF_MAX_LIGHTS 8

/* True when every input is finite, the radius positive and the medium known (the module's
 * sbfx_view_particle_valid: an invalid particle is skipped, never drawn). */
bool sbfx_rf_particle_valid(const sbfx_rf_particle *p);

/* Back-to-front order exactly as src/sim/sort.c computes it: key = sqrtf of the float squared
 * distance of the float centre, descending, ties in input order. order[] gets count indices. */
void sbfx_rf_sort(const sbfx_rf_particle *particles, int count, int *order);

/* The view ray (z = -1) through the centre of pixel (x, y) of the frame's grid. */
void sbfx_rf_pixel_ray(const sbfx_rf_frame *f, int x, int y, double ray[3]);

/* One particle at one pixel, as particle.frag computes it: premultiplied light rgb (light x
 * the emitting alpha; fire's emission times the share of its soot that glows,
 * sbfx_fire_glow_share) and alpha (what it covers: for fire with its soot, sbfx_fire_soot). A
 * particle the ray misses gives alpha 0, rgb 0. */
void sbfx_rf_shade(const sbfx_rf_frame *f, const sbfx_rf_particle *p, const double ray[3],
                   double opaque_distance, double rgb[3], double *alpha);

/* The frame's fire particles gathered into at most max point lights in view space (src/sim/fire_light.h,
 * as the module gathers them): the fire model of f->media[SBFX_FIRE], its black body (f's table or
 * analytic), the detail volume's levels. Returns the count, -1 if out of memory. */
int sbfx_rf_fire_lights(const sbfx_rf_frame *f, const sbfx_rf_particle *particles, int count, sbfx_fire_gathered *out,
                        int max);

/* The particle layer of the whole grid: layer[4 * (y * width + x)] = premultiplied light rgb,
 * transmittance. Invalid particles are skipped; returns how many were. If footprint is not
 * NULL it gets 1 where the pixel's ray passes through at least one valid particle's sphere
 * (depth ignored: where a particle *could* show), else 0. Returns -1 if out of memory. */
int sbfx_rf_render_layer(const sbfx_rf_frame *f, const sbfx_rf_particle *particles, int count,
                         double *layer, uint8_t *footprint);

/* composite.frag's tone mapping of one layer pixel (premultiplied light c, already times the
 * exposure: the layer is pre-exposed like the module's, transmittance t) over the host's pixel
 * dst (NULL: unknown, taken as black): the light is brought within the room the picture leaves,
 * room_k = 1 - t dst_k, through the tone curve (reference.h) of its largest ratio c_k / room_k
 * (the colour scaled: hue kept), of each channel's ratio, or filmic (sbfx_tone_filmic) on the
 * ratios; NONE leaves it as it is. */
void sbfx_rf_tone_map(sbfx_tone_map op, const double c[3], double t, const double dst[3], double out[3]);

/* out[3 * i + k] = clamp(scene_k / 255 * T + C'_k, 0, 1) * 255 for the RGBA8 scene colour
 * (rows in the same order as the layer), C' the light tone-mapped over that scene colour (the
 * GPU reads it too when frame.scene_color_texture is given and not drawn into). */
void sbfx_rf_composite(const double *layer, const uint8_t *scene_rgba8, int width, int height, sbfx_tone_map op,
                       double *out_rgb);

#endif
