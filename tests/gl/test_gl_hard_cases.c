/* Every hard case of docs/design.md §2.2 through the CPU reference (ref/reference_frame.c) and the GPU
 * (sbfx_render_view_particles, particle target read back at full resolution), in every opacity
 * mode: both must be finite, agree within the tolerances below, and show what the case is about
 * (alpha 0 where nothing may be seen, alpha -> 1 where everything is, ...). Then a scan of
 * rendered explosion frames (all modes and formats, tables and analytic) for NaN/Inf.
 *
 * The CPU side is given what the GPU has: the float particles, the window depth as the host
 * depth texture stores it (float), the detail volume rounded to half (R16F), and — for the
 * table paths — the module's own float tables (sbfx_get_tables), looked up the way the GPU
 * does; for the analytic paths (desc.analytic_blackbody / analytic_phase (the phase's default; its
 * table is desc.table_phase), or a table that
 * would miss) the analytic functions.
 *
 * Tolerances (GPU float32 against double, RGBA32F target unless said):
 *   alpha: 1e-4 absolute (the opacity tests' 5e-5 per particle, a few particles deep);
 *   light: 2e-3 relative + 1e-5 absolute (half-float detail fetched with the filter's
 *          weights; float tables, float exp/log in the shader);
 *   RGBA16F target: the float tolerances plus, per pixel and channel, the reference's bound on
 *          what the target's roundings can do (ref/reference_frame.h, target_rounding): each
 *          blend may round its source, factor, product and sum, each to either neighbouring
 *          half (relative error 2^-10), and the bound carries that through "over" with the
 *          values the blends pass through. It grows where the light did: 200 fire particles at
 *          the radiance ceiling (16384) pass through values far above what their pixel ends with
 *          once the glow share lets some of them add less, and the light there can differ by
 *          more than a fixed share of the final value (a 1 % tolerance measured 0.98 of itself).
 * At GPU precision (tests/precision.sh, docs/testing.md "Precision diagnostics"):
 *   SBFX_MEDIUMP=native: the light is mediump from the phase function on; it passes at most 4
 *          half roundings (phase, each light's term into the sum, the sum into the medium's
 *          light; emission: its return and the sum), gamma(4) = 4 2^-11 / (1 - 4 2^-11) =
 *          1.96e-3, inside the 2e-3 relative; alpha and geometry stay highp.
 *   SBFX_FILTER_BITS=N: the detail volume's trilinear weights are rounded to N bits, each off
 *          by at most e = 2^-(N+1) (a GPU's own filter: e = 2^-8, filter_weight_error() below);
 *          the lookup is multilinear in them, so it moves by at most e x (the cell's largest
 *          texel difference along each axis, summed over the axes). The reference shades each particle at the detail -+ that (each step after
 *          the lookup is monotone in it) and carries the spread through "over" (ref/
 *          reference_frame.c, filter_bound): that bound, per pixel and channel, is added to the
 *          tolerance. Without the variable it is 0. */
#include "base/float16.h"
#include "gl_fixture.h"
#include "reference_frame.h"
#include "scene/scene.h"

#define SIZE 32
#define MAX_P 256
#define ALPHA_TOL 1e-4
#define RGB_REL 2e-3
#define RGB_ABS 1e-5
#define HALF_ROUNDING 0x1p-10 /* one rounding to either neighbouring half float */
#define STOP_ALLOWANCE (0.25 / 255.0) /* terminate.c's STOP_LEVELS of an 8-bit level */
#define HALF_FLOOR 0x1p-24    /* ...and near 0: a subnormal half's spacing (ref/reference_frame.h) */

static const sbfx_opacity_mode modes[] = {SBFX_OPACITY_PLANAR, SBFX_OPACITY_SOFT, SBFX_OPACITY_SPHERICAL,
                                          SBFX_OPACITY_EXACT};
static const char *const mode_names[] = {"", "planar", "soft", "spherical", "exact", "floor"};

/* ---- one case: set-up, GPU, CPU, comparison --------------------------------------------- */

typedef struct hc_setup {
    sbfx_view_particle p[MAX_P];
    int count;
    float fov, near, far;
    double wall;                 /* opaque distance everywhere; INFINITY: the clear value */
    double wall_left;            /* if > 0: opaque only on the left half, at this distance */
    void (*media)(sbfx_medium_params *m);
    float light_dir[3], light_color[3], ambient[3];
    sbfx_target_format format;
    bool analytic_bb, analytic_phase;
    /* host depth drawn by GL as a plane at `wall` (not written texel by texel): reversed-Z
     * (infinite far, clip control ZERO_TO_ONE, GREATER) or standard, into `depth_format` */
    bool reversed_z;
    GLenum depth_format;
    bool cpu_true_depth;         /* the CPU reference gets `wall` itself, not what the buffer holds */
    double tolerance;            /* > 0: one absolute tolerance for every channel instead */
    bool report_only;            /* print how far GPU and CPU are apart, do not require agreement */
    bool early_termination;      /* the module's early termination on: drawn nearest first */
} hc_setup;

typedef struct hc_result {
    int w, h;
    float *gpu;
    double *cpu;
    int gpu_skipped, cpu_skipped, passes;
    double alpha_err, rgb_err;   /* worst |GPU - CPU|, rgb relative to the tolerance */
    double rgb_err_float;        /* rgb relative to the float tolerance alone (no filter bound) */
    double abs_err;              /* worst |GPU - CPU| of any channel */
    int nonfinite_gpu, nonfinite_cpu, over;
    double *bound;               /* per value: how far the filter's rounded weights can move it */
    double *rounding;            /* per value: how far the target's roundings can move it */
    double filter_share;         /* worst |GPU - CPU| minus the float tolerance, where the bound allowed it */
} hc_result;

static hc_setup base_setup(void)
{
    hc_setup s;
    memset(&s, 0, sizeof(s));
    s.fov = 1.0f, s.near = 0.1f, s.far = 100.0f;
    s.wall = INFINITY;
    s.light_dir[2] = -1.0f, s.light_dir[1] = -0.3f;
    s.light_color[0] = 1.6f, s.light_color[1] = 1.5f, s.light_color[2] = 1.35f;
    s.ambient[0] = 0.28f, s.ambient[1] = 0.32f, s.ambient[2] = 0.4f;
    s.format = SBFX_FORMAT_RGBA32F;
    return s;
}

static sbfx_view_particle particle(float x, float y, float z, float r, sbfx_medium m)
{
    return (sbfx_view_particle){.center = {x, y, z}, .radius = r, .detail = {0.3f, 0.6f, 0.1f},
                                .intensity = 1.0f, .medium = m};
}

static double setup_depth(int x, int y, void *user)
{
    const hc_setup *s = user;
    (void)y;
    if (s->wall_left > 0) return x < SIZE / 2 ? s->wall_left : INFINITY;
    return s->wall;
}

/* The tables and programs follow the media: the module is created with the built-in scene's
 * media as the case changes them, so they are made once, for those media. (Creating it with the
 * built-in scene and sbfx_reload after changing sbfx_media made every program twice: the reload
 * runs the same load_gl on the same state.) */
static sbfx *hc_module(gl_fixture *f, const hc_setup *s, sbfx_opacity_mode mode, bool has_detail[])
{
    static sbfx_scene scene;
    sbfx_scene_builtin(&scene);
    scene.early_termination = s->early_termination;
    if (s->media) s->media(scene.media);
    sbfx *fx = fixture_module(f, (sbfx_desc){.target_divisor = 1, .target_format = s->format, .opacity = mode,
                                             .max_particles = MAX_P, .analytic_blackbody = s->analytic_bb,
                                             .analytic_phase = s->analytic_phase, .table_phase = !s->analytic_phase,
                                             .scene = &scene});
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) has_detail[m] = sbfx_media(fx)[m].detail_strength > 0;
    sbfx_set_light(fx, s->light_dir, s->light_color, s->ambient);
    return fx;
}

static void gpu_render(gl_fixture *f, sbfx *fx, const hc_setup *s, hc_result *r)
{
    if (s->depth_format)
        CHECK(fixture_draw_depth_plane(f, s->wall, s->depth_format), "drawing the host's depth plane failed");
    else
        fixture_depth(f, setup_depth, (void *)s);
    CHECK(sbfx_render_view_particles(fx, &f->frame, s->p, s->count) == SBFX_OK, "%s", sbfx_last_error(fx));
    sbfx_counters c;
    sbfx_stats(fx, &c);
    r->gpu_skipped = c.particles_skipped;
    r->passes = c.passes;
    r->w = r->h = SIZE;
    if (c.passes == 0) { /* nothing drawn: the target holds an earlier frame; nothing was added */
        r->gpu = calloc(SIZE * SIZE * 4, sizeof(float));
        for (int i = 0; i < SIZE * SIZE; i++) r->gpu[4 * i + 3] = 1.0f;
        return;
    }
    r->gpu = fixture_read_target(fx, &r->w, &r->h);
}

/* ---- the reference, given what the GPU has ---------------------------------------------- */

static sbfx_cmf cmf;

/* How far a trilinear weight of the detail volume may be off, and why:
 *   SBFX_FILTER_BITS=N (src/gl/precision.c): the shader rounds it to N bits, at most 2^-(N+1);
 *   llvmpipe, softpipe: the texture unit filters in float, 0;
 *   any other renderer (a GPU): its texture unit, in fixed point with 8 fractional bits
 *   (DESIGN §9), and NVIDIA's snaps the coordinate down to them (docs/gpus.md, root causes):
 *   at most 2^-8. Read at the first case, with the context current. */
static double filter_weight_error(void)
{
    const char *v = getenv("SBFX_FILTER_BITS");
    if (v) return ldexp(1.0, -(atoi(v) + 1));
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    bool software = renderer && (strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe"));
    return software ? 0.0 : ldexp(1.0, -8);
}
static float *half_detail;

static double to_half(double v) { return (double)(sbfx_float16)v; }

static void load_tables(void)
{
    if (half_detail) return;
    cmf = sbfx_cie1931_2deg;
    size_t n = 128 * 128 * 32; /* the module's default volume */
    half_detail = malloc(n * sizeof(float));
    sbfx_detail_generate(128, 32, 1, half_detail);
    for (size_t i = 0; i < n; i++) half_detail[i] = (float)to_half(half_detail[i]);
}

static void rf_media(sbfx *fx, const bool has_detail[], sbfx_rf_frame *f)
{
    const sbfx_medium_params *m = sbfx_media(fx);
    for (int i = 0; i < SBFX_MEDIUM_COUNT; i++)
        f->media[i] = (sbfx_rf_medium){
            .albedo = m[i].albedo, .tau = m[i].tau, .phase_g = m[i].phase_g,
            .color = {m[i].color[0], m[i].color[1], m[i].color[2]}, .detail_strength = m[i].detail_strength,
            .detail_window = m[i].detail_window, .t0 = m[i].t0, .t1 = m[i].t1, .cooling = m[i].cooling,
            .soot = m[i].soot, .emission_scale = m[i].emission_scale, .has_detail = has_detail[i]};
}

static int rf_lights(sbfx *fx, const float view[16], sbfx_rf_light *out, double ambient[3])
{
    sbfx_view_light l[SBFX_RF_MAX_LIGHTS];
    int n = sbfx_frame_lights(fx, view, l, SBFX_RF_MAX_LIGHTS);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 4; k++) {
            out[i].vector[k] = l[i].vector[k];
            if (k < 3) out[i].color[k] = l[i].color[k];
        }
    float a[3];
    sbfx_frame_ambient(fx, a);
    for (int k = 0; k < 3; k++) ambient[k] = a[k];
    return n;
}

static void cpu_render(gl_fixture *f, sbfx *fx, const hc_setup *s, sbfx_opacity_mode mode,
                       const bool has_detail[], hc_result *r)
{
    const float *p = f->frame.projection;
    static double distance[SIZE * SIZE];
    for (int y = 0; y < SIZE; y++)
        for (int x = 0; x < SIZE; x++)
            distance[y * SIZE + x] = s->cpu_true_depth ? setup_depth(x, y, (void *)s)
                                                       : fixture_stored_distance(&f->frame, setup_depth(x, y, (void *)s));
    sbfx_rf_light lights[SBFX_RF_MAX_LIGHTS];
    sbfx_rf_frame rf = {.width = SIZE, .height = SIZE, .projection = {p[0], p[5], p[8], p[9]},
                        .near = fixture_near(&f->frame), .opaque_distance = distance, .opacity = mode,
                        .lights = lights, .detail = half_detail, .detail_size = 128, .detail_frames = 32,
                        .detail_time = sbfx_detail_time(fx), .cmf = &cmf,
                        .blackbody_norm = sbfx_blackbody_norm(&cmf, SBFX_DEFAULT_MAX_KELVIN)};
    const sbfx_tables *t = sbfx_get_tables(fx);
    if (t->blackbody && !t->blackbody_analytic) {
        rf.blackbody_table = t->blackbody, rf.blackbody_table_size = SBFX_BLACKBODY_SIZE;
        rf.blackbody_lo = t->blackbody_lo, rf.blackbody_hi = t->blackbody_hi;
    }
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (t->phase_table[m]) rf.phase_tables[m] = t->phase + (size_t)m * SBFX_PHASE_SIZE;
    rf.phase_table_size = SBFX_PHASE_SIZE;
    r->bound = calloc(SIZE * SIZE * 4, sizeof(double));
    rf.filter_weight_error = filter_weight_error(), rf.filter_bound = r->bound;
    r->rounding = calloc(SIZE * SIZE * 4, sizeof(double));
    rf.target_rounding = s->format == SBFX_FORMAT_RGBA16F ? HALF_ROUNDING : 0.0, rf.rounding_bound = r->rounding;
    rf.target_floor = s->format == SBFX_FORMAT_RGBA16F ? HALF_FLOOR : 0.0;
    rf.front_to_back = s->early_termination; /* the module draws nearest first then */
    rf_media(fx, has_detail, &rf);
    rf.fire_light = sbfx_fire_lit(fx);
    rf.light_count = rf_lights(fx, f->frame.view, lights, rf.ambient);
    sbfx_rf_particle *v = calloc(MAX_P, sizeof(*v));
    for (int i = 0; i < s->count; i++) {
        const sbfx_view_particle *q = &s->p[i];
        v[i] = (sbfx_rf_particle){.radius = q->radius, .intensity = q->intensity, .medium = q->medium};
        for (int k = 0; k < 3; k++) v[i].center[k] = q->center[k], v[i].detail[k] = q->detail[k];
    }
    r->cpu = calloc(SIZE * SIZE * 4, sizeof(double));
    r->cpu_skipped = sbfx_rf_render_layer(&rf, v, s->count, r->cpu, NULL);
    free(v);
}

static void compare(const hc_setup *s, hc_result *r)
{
    double rel = RGB_REL, abs_tol = RGB_ABS, alpha_tol = ALPHA_TOL;
    if (s->tolerance > 0) rel = 0.0, abs_tol = alpha_tol = s->tolerance;
    /* early termination leaves behind a texel at most T L < STOP_LEVELS / 255 of light and T of
     * its transmittance (src/render/terminate.c: T < epsilon = STOP_LEVELS / (255 (L + 1))) */
    if (s->early_termination) abs_tol += STOP_ALLOWANCE, alpha_tol += STOP_ALLOWANCE;
    for (int i = 0; i < SIZE * SIZE; i++)
        for (int k = 0; k < 4; k++) {
            double g = r->gpu[4 * i + k], c = r->cpu[4 * i + k];
            if (!isfinite(g)) r->nonfinite_gpu++;
            if (!isfinite(c)) r->nonfinite_cpu++;
            double err = fabs(g - c), filter = r->bound[4 * i + k];
            r->abs_err = fmax(r->abs_err, err);
            double tol = (k == 3 ? alpha_tol : rel * fabs(c) + abs_tol) + r->rounding[4 * i + k];
            r->filter_share = fmax(r->filter_share, fmin(err - tol, filter));
            if (k == 3) {
                r->alpha_err = fmax(r->alpha_err, err);
                if (!(err <= tol + filter)) r->over++;
            } else {
                r->rgb_err_float = fmax(r->rgb_err_float, err / tol);
                r->rgb_err = fmax(r->rgb_err, err / (tol + filter));
                if (!(err <= tol + filter)) r->over++;
            }
        }
}

static void hc_free(hc_result *r)
{
    free(r->gpu);
    free(r->cpu);
    free(r->bound);
    free(r->rounding);
    memset(r, 0, sizeof(*r));
}

/* Runs the case in one mode: GPU and CPU agree, both finite. */
static void hc_run(gl_fixture *f, const hc_setup *s, sbfx_opacity_mode mode, hc_result *r)
{
    load_tables();
    memset(r, 0, sizeof(*r));
    fixture_projection(f, s->fov, s->near, s->reversed_z ? INFINITY : s->far);
    if (s->reversed_z) sbfx_reverse_z(f->frame.projection, s->near, INFINITY);
    f->frame.clip_depth_mode = s->reversed_z ? SBFX_CLIP_DEPTH_ZERO_TO_ONE : SBFX_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE;
    bool has_detail[SBFX_MEDIUM_COUNT];
    sbfx *fx = hc_module(f, s, mode, has_detail);
    gpu_render(f, fx, s, r);
    cpu_render(f, fx, s, mode, has_detail, r);
    sbfx_destroy(fx);
    compare(s, r);
    printf("#   %-9s max |alpha diff| %.2e, max light diff %.2f of tolerance, max |diff| %.2e", mode_names[mode],
           r->alpha_err, r->rgb_err, r->abs_err);
    if (filter_weight_error() > 0)
        printf("; light %.2f of the float tolerance alone, %.2e past it (within the filter's bound)", r->rgb_err_float,
               fmax(r->filter_share, 0.0));
    printf("\n");
    if (s->report_only) return;
    CHECK(r->nonfinite_gpu == 0, "%s: %d non-finite GPU values", mode_names[mode], r->nonfinite_gpu);
    CHECK(r->nonfinite_cpu == 0, "%s: %d non-finite CPU values", mode_names[mode], r->nonfinite_cpu);
    CHECK(r->over == 0, "%s: %d values differ beyond tolerance (alpha %.3g, light %.3g x tol)",
          mode_names[mode], r->over, r->alpha_err, r->rgb_err);
    CHECK(r->gpu_skipped == r->cpu_skipped, "%s: GPU skipped %d, CPU %d", mode_names[mode], r->gpu_skipped,
          r->cpu_skipped);
}

static double alpha_at(const hc_result *r, int x, int y) { return 1.0 - r->gpu[4 * (y * r->w + x) + 3]; }

static double max_alpha(const hc_result *r)
{
    double a = 0.0;
    for (int i = 0; i < r->w * r->h; i++) a = fmax(a, 1.0 - r->gpu[4 * i + 3]);
    return a;
}

static double max_light(const hc_result *r)
{
    double l = 0.0;
    for (int i = 0; i < r->w * r->h; i++)
        for (int k = 0; k < 3; k++) l = fmax(l, r->gpu[4 * i + k]);
    return l;
}

/* Opens the context and runs the case in every mode, calling expect() on each result. */
static void hc_all_modes(const char *what, hc_setup *s,
                         void (*expect)(const hc_setup *, sbfx_opacity_mode, const hc_result *))
{
    gl_fixture f;
    fixture_open(&f, SIZE, SIZE);
    printf("# %s\n", what);
    for (size_t i = 0; i < ARRAY_SIZE(modes); i++) {
        hc_result r;
        hc_run(&f, s, modes[i], &r);
        if (expect) expect(s, modes[i], &r);
        hc_free(&r);
    }
    fixture_close(&f);
}

/* The view ray (z = -1) through the centre of target pixel (x, y) under the setup's projection. */
static void pixel_slope(const hc_setup *s, int x, int y, double out[2])
{
    double t = 1.0 / tan(s->fov * 0.5);
    out[0] = ((x + 0.5) / SIZE * 2.0 - 1.0) / t;
    out[1] = ((y + 0.5) / SIZE * 2.0 - 1.0) / t;
}

/* ---- media overrides ---------------------------------------------------------------------- */

/* Opacity without the detail perturbation (strength 0: the programs are made without
 * HAS_DETAIL), so the geometry is what is compared. */
static void no_detail(sbfx_medium_params *m)
{
    m[SBFX_DUST].detail_strength = m[SBFX_SMOKE].detail_strength = 0.0f;
}

static void tau_zero(sbfx_medium_params *m)
{
    for (int i = 0; i < SBFX_MEDIUM_COUNT; i++) m[i].tau = 0.0f;
}

static void tau_huge(sbfx_medium_params *m)
{
    for (int i = 0; i < SBFX_MEDIUM_COUNT; i++) m[i].tau = 1e6f;
}

/* ---- d -> r and d > r --------------------------------------------------------------------- */

static void expect_d_near_r(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    /* pixel (10, 16): the billboard point sits exactly at d = r of the first particle */
    CHECK(alpha_at(r, 10, 16) < 1e-2, "%s: alpha %g at d = r", mode_names[mode], alpha_at(r, 10, 16));
    CHECK(alpha_at(r, 7, 16) == 0.0, "%s: alpha %g at d = 1.5 r", mode_names[mode], alpha_at(r, 7, 16));
    CHECK(max_alpha(r) > 0.05, "%s: the particles are not drawn at all", mode_names[mode]);
}

CHECK_TEST(d_near_r_and_beyond)
{
    hc_setup s = base_setup();
    s.media = no_detail;
    double q[2];
    pixel_slope(&s, 10, 16, q);
    s.p[s.count++] = particle((float)(q[0] * 5.0 + 1.0), (float)(q[1] * 5.0), -5.0f, 1.0f, SBFX_SMOKE);
    pixel_slope(&s, 22, 8, q); /* d = r (1 - 1e-6): the last sliver inside */
    s.p[s.count++] = particle((float)(q[0] * 6.0 - 0.5 * (1.0 - 1e-6)), (float)(q[1] * 6.0), -6.0f, 0.5f, SBFX_DUST);
    pixel_slope(&s, 26, 26, q); /* d = r (1 + 1e-6): the first miss */
    s.p[s.count++] = particle((float)(q[0] * 4.0), (float)(q[1] * 4.0 + 0.7 * (1.0 + 1e-6)), -4.0f, 0.7f, SBFX_FIRE);
    hc_all_modes("rays at d = r, just inside and just outside", &s, expect_d_near_r);
}

/* ---- r -> 0 ------------------------------------------------------------------------------- */

static void expect_tiny(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    /* optical depth <= 2 tau r with r <= 1e-3 and tau = 0.4 */
    CHECK(max_alpha(r) <= 2 * 0.4 * 1e-3 * 1.01 + ALPHA_TOL, "%s: alpha %g", mode_names[mode], max_alpha(r));
}

CHECK_TEST(radius_to_zero)
{
    hc_setup s = base_setup();
    s.media = no_detail;
    const float radii[] = {1e-3f, 1e-6f, 1e-12f, 1e-30f, 1.2e-38f, 1e-44f /* subnormal */};
    for (size_t i = 0; i < ARRAY_SIZE(radii); i++) {
        double q[2];
        pixel_slope(&s, 4 + 5 * (int)i, 16, q);
        s.p[s.count++] = particle((float)(q[0] * 2.0), (float)(q[1] * 2.0), -2.0f, radii[i], (sbfx_medium)(i % 3));
    }
    hc_all_modes("radii 1e-3 down to a subnormal", &s, expect_tiny);
}

/* ---- camera inside the sphere ------------------------------------------------------------- */

static void expect_inside(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    if (mode == SBFX_OPACITY_PLANAR || mode == SBFX_OPACITY_SOFT)
        CHECK(max_alpha(r) == 0.0, "%s: the flat billboard behind the near plane drew alpha %g", mode_names[mode],
              max_alpha(r));
    else
        CHECK(alpha_at(r, 16, 16) > 0.2, "%s: alpha %g looking through the sphere from inside", mode_names[mode],
              alpha_at(r, 16, 16));
}

CHECK_TEST(camera_inside_sphere)
{
    hc_setup s = base_setup();
    s.media = no_detail;
    s.p[s.count++] = particle(0.1f, -0.05f, -0.05f, 1.5f, SBFX_SMOKE); /* F < n: centre before the near plane */
    hc_all_modes("camera inside the sphere, centre closer than the near plane", &s, expect_inside);
    s.early_termination = true;
    hc_all_modes("the same with early termination", &s, expect_inside);
}

/* ---- opaque surface inside or in front of the sphere ------------------------------------- */

static void expect_wall_inside(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    double left = alpha_at(r, 15, 16), right = alpha_at(r, 16, 16); /* mirror pixels */
    if (mode == SBFX_OPACITY_PLANAR)
        CHECK(fabs(left - right) < 1e-4, "planar: a wall behind the centre must not clip (%g vs %g)", left, right);
    else
        CHECK(left < right - 0.01, "%s: wall inside the sphere clips nothing (%g vs %g)", mode_names[mode], left, right);
}

CHECK_TEST(opaque_surface_inside_sphere)
{
    hc_setup s = base_setup();
    s.media = no_detail;
    s.wall_left = 5.3; /* between the centre (5) and the back (6), left half only */
    s.p[s.count++] = particle(0.0f, 0.0f, -5.0f, 1.0f, SBFX_SMOKE);
    hc_all_modes("opaque surface through the sphere, behind its centre, on the left half", &s, expect_wall_inside);
}

static void expect_nothing(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    CHECK(max_alpha(r) == 0.0 && max_light(r) == 0.0, "%s: alpha %g, light %g where nothing may show",
          mode_names[mode], max_alpha(r), max_light(r));
}

CHECK_TEST(opaque_surface_in_front_of_sphere)
{
    hc_setup s = base_setup();
    s.wall = 3.5; /* Zs < F = 4: delta s = 0 */
    s.p[s.count++] = particle(0.0f, 0.0f, -5.0f, 1.0f, SBFX_SMOKE);
    s.p[s.count++] = particle(0.3f, 0.2f, -5.5f, 1.2f, SBFX_FIRE);
    s.p[s.count++] = particle(-0.4f, 0.1f, -6.0f, 1.5f, SBFX_DUST);
    hc_all_modes("opaque surface in front of every sphere", &s, expect_nothing);
}

/* ---- sphere behind the camera -------------------------------------------------------------- */

CHECK_TEST(sphere_behind_camera)
{
    hc_setup s = base_setup();
    s.p[s.count++] = particle(0.0f, 0.0f, 5.0f, 1.0f, SBFX_SMOKE);
    s.p[s.count++] = particle(0.5f, -0.2f, 3.0f, 2.5f, SBFX_FIRE);
    s.p[s.count++] = particle(0.0f, 0.0f, 1.0f, 1.1f, SBFX_DUST); /* back reaches exactly 0.1 */
    hc_all_modes("spheres wholly behind the camera", &s, expect_nothing);
    s.count = 0;
    s.media = no_detail;
    s.p[s.count++] = particle(0.3f, 0.0f, 0.5f, 1.0f, SBFX_SMOKE); /* centre behind, camera inside */
    hc_all_modes("centre behind the camera, the sphere reaching in front", &s, NULL);
}

/* ---- z_c = 1e4, r = 0.05 -------------------------------------------------------------------- */

static void expect_far_small(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    /* through the centre: optical depth 2 tau r (planar, soft, spherical) or tau r (exact) */
    double od = (mode == SBFX_OPACITY_EXACT ? 1.0 : 2.0) * 0.4 * 0.05, peak = -expm1(-od);
    CHECK(fabs(max_alpha(r) - peak) < 0.05 * peak, "%s: peak alpha %g, expected about %g", mode_names[mode],
          max_alpha(r), peak);
}

/* The particle is 1e4 m away and 0.1 m across: a 1.6e-5 rad field of view makes it span a third
 * of the 32-pixel target. Nothing opaque is near it: the depth stays at its clear value (no
 * surface). A surface next to a far particle: far_field_particle_in_front_of_surface. */
CHECK_TEST(small_particle_far_away)
{
    hc_setup s = base_setup();
    s.media = no_detail;
    s.fov = 1.6e-5f, s.near = 0.1f, s.far = 1e5f;
    double q[2];
    pixel_slope(&s, 16, 16, q); /* centred on a pixel's ray: the peak is sampled */
    s.p[s.count++] = particle((float)(q[0] * 1e4), (float)(q[1] * 1e4), -1e4f, 0.05f, SBFX_SMOKE);
    hc_all_modes("z_c = 1e4, r = 0.05, opaque depth at the clear value", &s, expect_far_small);
}

/* ---- far field: a small particle just in front of a surface 3 km away ----------------------
 * r = 5 cm at 3000 m, the surface 1 cm behind its centre, near 0.1: the opaque depth decides
 * how much of the chord is seen. Reversed-Z float depth (GL_EXT_clip_control, DEPTH_COMPONENT32F)
 * resolves about z 2^-24 = 0.2 mm there: sbfx must agree with the CPU reference given the true
 * surface distance within 4e-3. A standard 24-bit buffer resolves z^2 / (n 2^24) = 5.4 m: the
 * surface reads metres off and the result is wrong by the particle's whole alpha — reported. */
static hc_setup far_field_setup(void)
{
    hc_setup s = base_setup();
    s.media = no_detail;
    s.fov = 5.3e-5f, s.near = 0.1f, s.far = 1e5f;
    s.wall = 3000.01;
    s.cpu_true_depth = true;
    s.tolerance = 4e-3;
    double q[2];
    pixel_slope(&s, 16, 16, q);
    s.p[s.count++] = particle((float)(q[0] * 3000.0), (float)(q[1] * 3000.0), -3000.0f, 0.05f, SBFX_SMOKE);
    return s;
}

static void expect_clipped(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    /* the surface cuts the chord: the centre pixel shows less than the unclipped peak */
    double od = (mode == SBFX_OPACITY_EXACT ? 1.0 : 2.0) * 0.4 * 0.05, peak = -expm1(-od);
    if (mode != SBFX_OPACITY_PLANAR && mode != SBFX_OPACITY_SOFT)
        CHECK(max_alpha(r) < 0.8 * peak && max_alpha(r) > 0.2 * peak, "%s: peak alpha %g of an unclipped %g",
              mode_names[mode], max_alpha(r), peak);
}

CHECK_TEST(far_field_particle_in_front_of_surface)
{
    gl_fixture probe;
    fixture_open(&probe, 1, 1);
    bool reversed = host_depth_has_clip_control();
    fixture_close(&probe);
    hc_setup s = far_field_setup();
    if (reversed) {
        s.reversed_z = true;
        s.depth_format = GL_DEPTH_COMPONENT32F;
        hc_all_modes("far field, host depth: reversed-Z DEPTH_COMPONENT32F (GL_EXT_clip_control), within 4e-3", &s,
                     expect_clipped);
    }
    s = far_field_setup();
    s.depth_format = GL_DEPTH_COMPONENT24;
    s.report_only = true;
    hc_all_modes("far field, host depth: standard DEPTH_COMPONENT24 (reported: the buffer cannot resolve it)", &s, NULL);
    if (!reversed)
        CHECK_SKIP("far field: GL_EXT_clip_control missing, no reversed-Z float depth to check (24-bit reported)");
}

/* ---- tau = 0 and tau = 1e6 ------------------------------------------------------------------ */

static void add_mixed_particles(hc_setup *s)
{
    s->p[s->count++] = particle(0.0f, 0.0f, -5.0f, 1.2f, SBFX_SMOKE);
    s->p[s->count++] = particle(0.6f, 0.3f, -4.0f, 0.8f, SBFX_FIRE);
    s->p[s->count++] = particle(-0.7f, -0.2f, -6.0f, 1.5f, SBFX_DUST);
}

static void expect_saturated(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    CHECK(max_alpha(r) >= 1.0 - 1e-6, "%s: tau = 1e6 leaves alpha at %g", mode_names[mode], max_alpha(r));
}

CHECK_TEST(tau_zero_and_huge)
{
    hc_setup s = base_setup();
    add_mixed_particles(&s);
    s.media = tau_zero;
    hc_all_modes("tau = 0: nothing", &s, expect_nothing);
    s.media = tau_huge;
    hc_all_modes("tau = 1e6: alpha -> 1", &s, expect_saturated);
    s.early_termination = true; /* the opaque front stops what is behind it */
    hc_all_modes("the same with early termination", &s, expect_saturated);
}

/* ---- depth at its far clear value ------------------------------------------------------------ */

CHECK_TEST(depth_at_far_clear_value)
{
    hc_setup s = base_setup();
    s.media = no_detail;
    s.far = 20.0f; /* nothing opaque: depth 1.0 everywhere, read as the far distance */
    s.p[s.count++] = particle(0.0f, 0.0f, -19.5f, 1.0f, SBFX_SMOKE); /* straddles the far plane */
    s.p[s.count++] = particle(1.0f, 0.5f, -10.0f, 2.0f, SBFX_DUST);
    hc_all_modes("depth texture at its clear value, a sphere across the far plane", &s, NULL);
}

/* ---- half-float target near 65504 with fire ------------------------------------------------- */

static void hot_fire(sbfx_medium_params *m)
{
    m[SBFX_FIRE].emission_scale = 1e6f; /* the table's ~1 x 1e6: every fragment hits the ceiling */
    m[SBFX_FIRE].t0 = 5000.0f;
    m[SBFX_FIRE].tau = 3.0f;
}

static void expect_ceiling(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    /* each fragment adds at most ceiling x alpha and keeps (1 - alpha) of what is behind: C <= ceiling */
    double most = max_light(r);
    CHECK(most <= SBFX_RF_RADIANCE_CEILING * (1.0 + 1.0 / 1024.0), "%s: light %g above the ceiling",
          mode_names[mode], most);
    CHECK(most > 1.0, "%s: the fire is not drawn (light %g)", mode_names[mode], most);
}

static void fire_stack(hc_setup *s)
{
    sbfx_rng rng;
    sbfx_rng_seed(&rng, 65504);
    for (s->count = 0; s->count < 200; s->count++) {
        sbfx_view_particle *p = &s->p[s->count];
        *p = particle((float)sbfx_rng_range(&rng, -0.3, 0.3), (float)sbfx_rng_range(&rng, -0.3, 0.3),
                      (float)sbfx_rng_range(&rng, -5.5, -4.5), 1.5f, SBFX_FIRE);
        for (int k = 0; k < 3; k++) p->detail[k] = (float)sbfx_rng_uniform(&rng);
    }
}

CHECK_TEST(half_float_target_with_hot_fire)
{
    hc_setup s = base_setup();
    fire_stack(&s);
    s.media = hot_fire;
    s.format = SBFX_FORMAT_RGBA16F;
    hc_all_modes("200 overlapping fire particles, emission x 1e6, RGBA16F target", &s, expect_ceiling);
    s.analytic_bb = true;
    hc_all_modes("the same with the analytic black body", &s, expect_ceiling);
    s.format = SBFX_FORMAT_RGBA32F;
    hc_all_modes("the same into RGBA32F", &s, expect_ceiling);
    s.format = SBFX_FORMAT_RGBA16F;
    s.analytic_bb = false;
    s.early_termination = true; /* epsilon at its smallest: L at the ceiling */
    hc_all_modes("RGBA16F with early termination", &s, expect_ceiling);
}

/* ---- fire's soot: the cool share's soot covers, and glows not ------------------------------ */

static float fire_soot_value;
static double soot_alpha_sum[3][ARRAY_SIZE(modes)], soot_light_sum[3][ARRAY_SIZE(modes)];
static int soot_run;

static void sooty_fire(sbfx_medium_params *m) { m[SBFX_FIRE].soot = fire_soot_value; }

static void record_soot(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    size_t i = 0;
    while (modes[i] != mode) i++;
    double alpha = 0.0, light = 0.0;
    for (int y = 0; y < r->h; y++)
        for (int x = 0; x < r->w; x++) {
            alpha += alpha_at(r, x, y);
            for (int k = 0; k < 3; k++) light += r->gpu[4 * (y * r->w + x) + k];
        }
    soot_alpha_sum[soot_run][i] = alpha, soot_light_sum[soot_run][i] = light;
}

/* media.fire.soot (docs/look-fire.md "Pink edges"): the share of a young fire's column too cool
 * to glow carries soot times its optical depth on top, which absorbs and emits nothing. Three fire
 * particles side by side (none in front of another, so the light behind is never covered): the
 * GPU agrees with the reference at soot 0, 2 (the default) and 64 (the top of its range); the
 * coverage grows with the soot and the light stays what the glowing share emits. */
CHECK_TEST(fire_soot_covers_and_does_not_glow)
{
    hc_setup s = base_setup();
    s.media = sooty_fire;
    s.p[s.count++] = particle(-0.9f, 0.0f, -5.0f, 0.6f, SBFX_FIRE);
    s.p[s.count++] = particle(0.6f, 0.2f, -5.0f, 0.5f, SBFX_FIRE);
    s.p[s.count++] = particle(-0.1f, -1.0f, -5.0f, 0.4f, SBFX_FIRE);
    s.p[2].intensity = 0.6f; /* a cooling one: more of it is too cool to glow */
    const float soot[] = {0.0f, (float)SBFX_FIRE_SOOT_DEFAULT, 64.0f};
    for (soot_run = 0; soot_run < 3; soot_run++) {
        fire_soot_value = soot[soot_run];
        char what[64];
        snprintf(what, sizeof what, "three fire particles, soot %g", soot[soot_run]);
        hc_all_modes(what, &s, record_soot);
    }
    for (size_t i = 0; i < ARRAY_SIZE(modes); i++) {
        printf("# %-9s summed alpha %.3f / %.3f / %.3f, light %.4f / %.4f / %.4f\n", mode_names[modes[i]],
               soot_alpha_sum[0][i], soot_alpha_sum[1][i], soot_alpha_sum[2][i], soot_light_sum[0][i],
               soot_light_sum[1][i], soot_light_sum[2][i]);
        CHECK(soot_alpha_sum[1][i] > 1.05 * soot_alpha_sum[0][i] && soot_alpha_sum[2][i] > soot_alpha_sum[1][i],
              "%s: the soot does not cover", mode_names[modes[i]]);
        for (int k = 1; k < 3; k++)
            CHECK(fabs(soot_light_sum[k][i] - soot_light_sum[0][i]) <= RGB_REL * soot_light_sum[0][i],
                  "%s: soot %g changes the light (%g against %g)", mode_names[modes[i]], soot[k],
                  soot_light_sum[k][i], soot_light_sum[0][i]);
    }
}

/* ---- black body at T -> 0 and T = 1e5 ------------------------------------------------------ */

static float fire_t0, fire_t1;

static void fixed_temperature(sbfx_medium_params *m)
{
    m[SBFX_FIRE].t0 = fire_t0;
    m[SBFX_FIRE].t1 = fire_t1;
    m[SBFX_FIRE].cooling = 0.0f;
}

static void expect_dark(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    CHECK(max_light(r) == 0.0, "%s: T = %g K glows with %g", mode_names[mode], fire_t0, max_light(r));
    CHECK(max_alpha(r) > 0.05, "%s: the cold fire still absorbs", mode_names[mode]);
}

static void expect_glow(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    CHECK(max_light(r) > 0.1, "%s: T = %g K (clamped to the table's top) does not glow", mode_names[mode], fire_t0);
}

static void blackbody_case(bool analytic)
{
    hc_setup s = base_setup();
    s.analytic_bb = analytic;
    s.media = fixed_temperature;
    s.p[s.count++] = particle(0.0f, 0.0f, -5.0f, 1.5f, SBFX_FIRE);
    s.p[s.count++] = particle(0.5f, 0.4f, -4.0f, 0.8f, SBFX_FIRE);
    const float cold[] = {0.0f, 1e-3f, 1.0f};
    for (size_t i = 0; i < ARRAY_SIZE(cold); i++) {
        fire_t0 = cold[i], fire_t1 = 0.0f;
        hc_all_modes(analytic ? "analytic black body, T -> 0" : "black-body table, T -> 0", &s, expect_dark);
    }
    fire_t0 = 1e5f, fire_t1 = 0.0f;
    hc_all_modes(analytic ? "analytic black body, T = 1e5 K" : "black-body table, T = 1e5 K", &s, expect_glow);
}

CHECK_TEST(blackbody_extremes_table) { blackbody_case(false); }
CHECK_TEST(blackbody_extremes_analytic) { blackbody_case(true); }

/* ---- phase function at g = +-0.99 and 0 ---------------------------------------------------- */

static float phase_g;
static double centre_light[3]; /* green channel at the centre pixel for g = -0.99, 0, 0.99 */

static void set_phase_g(sbfx_medium_params *m)
{
    no_detail(m);
    m[SBFX_SMOKE].phase_g = phase_g;
    m[SBFX_SMOKE].albedo = 0.9f;
}

static void record_centre(const hc_setup *s, sbfx_opacity_mode mode, const hc_result *r)
{
    (void)s;
    if (mode != SBFX_OPACITY_EXACT) return;
    int i = phase_g < -0.5f ? 0 : phase_g > 0.5f ? 2 : 1;
    centre_light[i] = r->gpu[4 * (16 * r->w + 16) + 1];
}

/* The light travels toward the camera (+z, the fixture's view is the identity): straight
 * through the particle into the eye, the forward peak for g > 0. */
static void phase_case(bool analytic)
{
    hc_setup s = base_setup();
    s.analytic_phase = analytic;
    s.media = set_phase_g;
    s.light_dir[0] = 0.0f, s.light_dir[1] = 0.0f, s.light_dir[2] = 1.0f;
    s.p[s.count++] = particle(0.0f, 0.0f, -5.0f, 1.0f, SBFX_SMOKE);
    const float gs[] = {-0.99f, 0.0f, 0.99f};
    for (size_t i = 0; i < ARRAY_SIZE(gs); i++) {
        phase_g = gs[i];
        char what[96];
        snprintf(what, sizeof(what), "%s phase, g = %.2f, back-lit", analytic ? "analytic" : "table", gs[i]);
        hc_all_modes(what, &s, record_centre);
    }
    printf("# centre light (green) for g = -0.99, 0, 0.99: %.5g %.5g %.5g\n", centre_light[0], centre_light[1],
           centre_light[2]);
    CHECK(centre_light[2] > 10.0 * centre_light[1] && centre_light[1] > centre_light[0],
          "g > 0 must peak forward: %g %g %g", centre_light[0], centre_light[1], centre_light[2]);
}

CHECK_TEST(phase_extremes_table) { phase_case(false); }
CHECK_TEST(phase_extremes_analytic) { phase_case(true); }

/* ---- NaN / Inf in every per-particle input ------------------------------------------------- */

#define BAD_FIELDS 8 /* centre x, y, z, radius, detail u, v, t, intensity */

static float *bad_field(sbfx_view_particle *p, int field)
{
    if (field < 3) return &p->center[field];
    if (field == 3) return &p->radius;
    if (field < 7) return &p->detail[field - 4];
    return &p->intensity;
}

/* Every field x {NaN, +Inf, -Inf}, then a zero and a negative radius and an unknown medium. */
static int bad_particles(const sbfx_view_particle *good, int goods, sbfx_view_particle *out)
{
    const float values[] = {NAN, INFINITY, -INFINITY};
    int n = 0;
    for (int field = 0; field < BAD_FIELDS; field++)
        for (size_t v = 0; v < ARRAY_SIZE(values); v++) {
            out[n] = good[n % goods];
            *bad_field(&out[n], field) = values[v];
            n++;
        }
    out[n] = good[0], out[n++].radius = 0.0f;
    out[n] = good[1], out[n++].radius = -1.0f;
    out[n] = good[2], out[n++].medium = (sbfx_medium)77;
    return n;
}

static double *cpu_layer(const sbfx_view_particle *p, int count, int *skipped)
{
    sbfx_rf_particle v[64];
    for (int i = 0; i < count; i++) {
        v[i] = (sbfx_rf_particle){.radius = p[i].radius, .intensity = p[i].intensity, .medium = p[i].medium};
        for (int k = 0; k < 3; k++) v[i].center[k] = p[i].center[k], v[i].detail[k] = p[i].detail[k];
    }
    sbfx_rf_frame f = {.width = SIZE, .height = SIZE, .projection = {1.8, 1.8, 0, 0}, .near = 0.1,
                       .opacity = SBFX_OPACITY_EXACT, .ambient = {0.3, 0.3, 0.3}};
    static double far[SIZE * SIZE];
    for (int i = 0; i < SIZE * SIZE; i++) far[i] = INFINITY;
    f.opaque_distance = far;
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) f.media[m] = (sbfx_rf_medium){.albedo = 0.5, .tau = 0.4, .color = {1, 1, 1}};
    double *layer = calloc(SIZE * SIZE * 4, sizeof(double));
    *skipped = sbfx_rf_render_layer(&f, v, count, layer, NULL);
    return layer;
}

static void bad_inputs_in_mode(gl_fixture *f, sbfx_opacity_mode mode, const sbfx_view_particle *good, int goods,
                               const sbfx_view_particle *all, int count)
{
    sbfx *fx = fixture_module(f, (sbfx_desc){.target_divisor = 1, .target_format = SBFX_FORMAT_RGBA32F,
                                             .opacity = mode, .max_particles = 64});
    int w, h;
    CHECK(sbfx_render_view_particles(fx, &f->frame, good, goods) == SBFX_OK, "%s", sbfx_last_error(fx));
    float *before = fixture_read_target(fx, &w, &h);
    for (int i = goods; i <= count; i++) { /* each bad particle alone, then all of them */
        const sbfx_view_particle *batch = all;
        int n = i < count ? goods + 1 : count;
        sbfx_view_particle one[4];
        if (i < count) {
            memcpy(one, good, sizeof(*good) * (size_t)goods);
            one[goods] = all[i];
            batch = one;
        }
        CHECK(sbfx_render_view_particles(fx, &f->frame, batch, n) == SBFX_OK, "%s", sbfx_last_error(fx));
        sbfx_counters c;
        sbfx_stats(fx, &c);
        float *after = fixture_read_target(fx, &w, &h);
        CHECK(c.particles_skipped == n - goods, "%s: bad particle %d: skipped %d of %d", mode_names[mode], i,
              c.particles_skipped, n - goods);
        CHECK(memcmp(before, after, sizeof(float) * 4 * (size_t)(w * h)) == 0, "%s: bad particle %d changed pixels",
              mode_names[mode], i);
        free(after);
    }
    free(before);
    sbfx_destroy(fx);
}

CHECK_TEST(bad_inputs_skipped_every_field)
{
    gl_fixture f;
    fixture_open_far(&f, SIZE, SIZE);
    const sbfx_view_particle good[3] = {particle(0.0f, 0.0f, -6.0f, 1.5f, SBFX_SMOKE),
                                        particle(1.0f, 0.5f, -7.0f, 1.0f, SBFX_FIRE),
                                        particle(-1.0f, -0.5f, -5.0f, 1.2f, SBFX_DUST)};
    sbfx_view_particle all[64];
    memcpy(all, good, sizeof(good));
    int count = 3 + bad_particles(good, 3, all + 3);
    for (size_t m = 0; m < ARRAY_SIZE(modes); m++) bad_inputs_in_mode(&f, modes[m], good, 3, all, count);
    /* the CPU reference skips the same particles and changes nothing either */
    int skipped_good, skipped_all;
    double *a = cpu_layer(good, 3, &skipped_good), *b = cpu_layer(all, count, &skipped_all);
    CHECK(skipped_good == 0 && skipped_all == count - 3, "CPU skipped %d of %d", skipped_all, count - 3);
    CHECK(memcmp(a, b, sizeof(double) * SIZE * SIZE * 4) == 0, "CPU: bad particles changed pixels");
    free(a);
    free(b);
    fixture_close(&f);
}

/* ---- rendered explosion frames: no NaN or Inf in any float target ------------------------- */

#include "host/test_scene.h"

#define SCAN_W 160
#define SCAN_H 90

/* The configurations one module renders: every quality of `levels` (switched with
 * sbfx_set_quality before each frame), or with none the module's own (the floor opacity, which
 * sbfx_set_quality refuses). A frame rendered after switching to q is bit-identical to the same
 * frame of a module created with q (sbfx.h; test_gl_quality), so one module per target format
 * scans the same programs, targets and frames that one module per configuration did, while
 * the explosion is simulated and the module made once instead of 16 times. */
typedef struct scan_set {
    sbfx_desc desc;
    sbfx_quality levels[16];
    int level_count;
    int bad[16];                 /* frames with NaN/Inf, per level (or [0]: the module's own) */
} scan_set;

static const double scan_times[] = {0.02, 0.2, 0.45, 1.0, 2.0, 2.9};

static void scan_frame(sbfx *fx, sbfx_frame *frame, float *rgba, sbfx_target_format format, int *bad)
{
    CHECK(sbfx_render(fx, frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    sbfx_counters c;
    sbfx_stats(fx, &c);
    CHECK(c.target_format == format, "asked for format %d, got %d", format, c.target_format);
    int w, h;
    if (sbfx_read_particle_target(fx, rgba, 4 * SCAN_W * SCAN_H, &w, &h) != SBFX_OK) return;
    if (!all_finite(rgba, 4u * (size_t)(w * h))) (*bad)++;
}

static void scan_module(struct test_scene *scene, sbfx_frame *frame, scan_set *set)
{
    sbfx *fx = NULL;
    CHECK(sbfx_create(&set->desc, &fx) == SBFX_OK, "sbfx_create");
    if (!fx) return;
    float *rgba = malloc(sizeof(float) * 4 * SCAN_W * SCAN_H);
    for (size_t t = 0; t < ARRAY_SIZE(scan_times); t++) {
        while (sbfx_time(fx) < scan_times[t] - 1e-9) sbfx_update(fx, 1.0 / 120.0);
        test_scene_orbit_camera(scan_times[t], (float)SCAN_W / SCAN_H, frame->view, frame->projection);
        test_scene_draw(scene, frame->view, frame->projection);
        if (set->level_count == 0) scan_frame(fx, frame, rgba, set->desc.target_format, &set->bad[0]);
        for (int q = 0; q < set->level_count; q++) {
            CHECK(sbfx_set_quality(fx, &set->levels[q]) == SBFX_OK, "%s", sbfx_last_error(fx));
            scan_frame(fx, frame, rgba, set->levels[q].target_format, &set->bad[q]);
        }
    }
    free(rgba);
    sbfx_destroy(fx);
}

CHECK_TEST(explosion_frames_have_no_nan_or_inf)
{
    gl_fixture f;
    fixture_open(&f, SCAN_W, SCAN_H);
    struct test_scene scene;
    char err[256];
    CHECK(test_scene_create(&scene, SCAN_W, SCAN_H, err, sizeof(err)) == 0, "%s", err);
    sbfx_frame frame = f.frame;
    frame.scene_color_texture = scene.color_texture;
    frame.scene_depth_texture = scene.depth_texture;
    /* RGBA8 cannot hold a NaN, but its read-back is scanned all the same: "all formats" */
    const sbfx_target_format formats[] = {SBFX_FORMAT_RGBA8, SBFX_FORMAT_RGBA16F, SBFX_FORMAT_RGBA32F};
    int frames = 0, bad = 0;
    for (size_t fm = 0; fm < ARRAY_SIZE(formats); fm++) {
        /* the four modes x 1, 1/4 x tables/analytic through one module; the floor's four alone */
        scan_set all = {.desc = {.target_divisor = 1, .target_format = formats[fm], .opacity = SBFX_OPACITY_EXACT}};
        scan_set floor[4];
        for (int m = SBFX_OPACITY_PLANAR; m <= SBFX_OPACITY_EXACT; m++)
            for (int div = 1; div <= 4; div *= 4)
                for (int analytic = 0; analytic < 2; analytic++)
                    all.levels[all.level_count++] = (sbfx_quality){
                        .opacity = (sbfx_opacity_mode)m, .target_divisor = div, .upsample = SBFX_UPSAMPLE_NEAREST_DEPTH,
                        .target_format = formats[fm], .analytic_blackbody = analytic, .analytic_phase = analytic,
                        .table_phase = !analytic};
        scan_module(&scene, &frame, &all);
        for (int q = 0; q < all.level_count; q++) {
            const sbfx_quality *l = &all.levels[q];
            CHECK(all.bad[q] == 0, "%s, format %d, 1/%d, analytic %d: %d frames with NaN/Inf", mode_names[l->opacity],
                  formats[fm], l->target_divisor, l->analytic_blackbody, all.bad[q]);
            bad += all.bad[q];
            frames += (int)ARRAY_SIZE(scan_times);
        }
        for (int i = 0; i < 4; i++) {
            int div = i < 2 ? 1 : 4, analytic = i % 2;
            floor[i] = (scan_set){.desc = {.target_divisor = div, .target_format = formats[fm],
                                           .opacity = SBFX_OPACITY_FLOOR, .analytic_blackbody = analytic,
                                           .analytic_phase = analytic, .table_phase = !analytic}};
            scan_module(&scene, &frame, &floor[i]);
            CHECK(floor[i].bad[0] == 0, "floor, format %d, 1/%d, analytic %d: %d frames with NaN/Inf", formats[fm], div,
                  analytic, floor[i].bad[0]);
            bad += floor[i].bad[0];
            frames += (int)ARRAY_SIZE(scan_times);
        }
    }
    printf("# %d explosion frames scanned (5 modes incl. floor x RGBA8/16F/32F x 1, 1/4 x tables/analytic), "
           "%d bad\n", frames, bad);
    test_scene_destroy(&scene);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
