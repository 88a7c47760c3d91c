/* The loaded scene's lookup tables (scene/scene.h says what the room is for; docs/design.md §2.3,
 * §4): ranges from what the scene can produce, built in double by the tables' math
 * (tables/tables.h) and stored as float, checked against their functions at load. A medium
 * whose table would miss the tolerance is evaluated analytically instead (logged once). The
 * GPU copies are the gl room's (gl/luts.c uploads and binds them). */
#ifndef SBFX_SCENE_TABLES_H
#define SBFX_SCENE_TABLES_H

#include "scene/plan.h"

/* Lookup tables (reference.h has their coordinates; docs/accuracy-and-benchmarks.md the sizes'
 * measured error). Float32 entries fetched with texelFetch and interpolated in the shader:
 * half floats would spend half the error budget on rounding (2^-11), float textures are not
 * filterable in core ES 3.0, and the filter's fixed-point weights would add their own error. */
#define SBFX_BLACKBODY_SIZE 512           /* RGBA32F entries, uniform in 1/T */
#define SBFX_PHASE_SIZE 256               /* R32F entries per medium, warped cos θ */
#define SBFX_DEFAULT_MAX_KELVIN 6000.0    /* blackbody_max_kelvin: luminance 1 at this T */
#define SBFX_DEFAULT_WHITE_LUMINANCE 1e4  /* desc.white_luminance, cd/m^2 */
#define SBFX_BLACKBODY_MIN_KELVIN 500.0   /* cooler fire: under 1e-19 of the unit's light */
#define SBFX_BLACKBODY_MARGIN 1.25        /* the range reaches this factor beyond the scene's */
#define SBFX_TABLE_TOLERANCE 1e-3         /* docs/design.md §4: relative to the double function */
#define SBFX_TABLE_GPU_ALLOWANCE 1e-4     /* of it, what the shader's float arithmetic may use
                                             (llvmpipe: 6e-6 black body, 5e-7 phase) */
#define SBFX_ANALYTIC_MAX_BANDS 96        /* MAX_BANDS in particle.frag */

/* The tables made at load (fx->tables), with the CPU copy of what is uploaded (tests mirror the
 * GPU with it) and what was decided. */
typedef struct sbfx_tables {
    float *blackbody;              /* SBFX_BLACKBODY_SIZE x 4; NULL without fire */
    double blackbody_lo, blackbody_hi;  /* kelvin, from the scene's fire (scene_tables.c) */
    double blackbody_norm;         /* 1 / Y(desc.blackbody_max_kelvin) */
    double blackbody_error;        /* the CPU lookup's largest error over the range */
    bool blackbody_missed;         /* the table misses the tolerance: always analytic */
    bool blackbody_analytic;       /* the current level's analytic_blackbody, or the table missed */
    float *phase;                  /* SBFX_MEDIUM_COUNT rows of SBFX_PHASE_SIZE; row m: medium m */
    double phase_error[SBFX_MEDIUM_COUNT];
    bool phase_table[SBFX_MEDIUM_COUNT];    /* the medium samples its row */
    bool phase_analytic[SBFX_MEDIUM_COUNT]; /* the medium evaluates the function per fragment */
    bool phase_missed[SBFX_MEDIUM_COUNT];   /* its table misses the tolerance: always analytic */
    /* analytic black body: per band, sRGB weight (matrix x CMF x trapezoid x norm) and the
     * band's wavelength in micrometres; made with the first level that uses it */
    int cmf_bands;
    float *cmf_rgb, *cmf_band;
} sbfx_tables;

/* The black-body and phase tables of the loaded scene from its media and effects; the analytic
 * black body's constants where a declared level uses them; fire's photometric emission (once,
 * at create). CPU only. */
sbfx_result sbfx_scene_tables_create(sbfx *fx);
void sbfx_scene_tables_destroy(sbfx *fx);
/* The analytic black body's per-band constants (when a level that uses it is chosen later). */
sbfx_result sbfx_blackbody_constants_load(sbfx *fx);
/* Scatters light through the phase function: uses the medium, has albedo, is not lit the
 * lit-smoke way. */
bool sbfx_medium_uses_phase(const sbfx *fx, sbfx_medium m);
/* What a level uses of the loaded scene's tables. */
bool sbfx_quality_uses_blackbody_table(const sbfx *fx, const sbfx_quality *q);
bool sbfx_quality_uses_blackbody_analytic(const sbfx *fx, const sbfx_quality *q);
bool sbfx_quality_uses_phase_table(const sbfx *fx, const sbfx_quality *q);
/* The tables of the loaded scene (tests, the CPU reference). */
const sbfx_tables *sbfx_get_tables(const sbfx *fx);

#endif
