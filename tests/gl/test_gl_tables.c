/* The lookup tables on the GPU against their double-precision functions (docs/design.md §4: within 1e-3
 * relative over the range the scene can produce; the phase function for every |g| <= 0.95).
 * Values come from particle.frag's own blackbody() and phase() (sbfx_fetch_luts), at both ends
 * of every table, at its steepest point and densely in between; ranges come from the scene.
 * At GPU precision (tests/precision.sh: SBFX_MEDIUMP=native SBFX_FILTER_BITS=8): no table is
 * read through the texture filter (both are interpolated in the shader, texelFetch and mix in
 * highp), and blackbody() is highp; phase() returns mediump, one half rounding, at most 2^-11 =
 * 4.9e-4 relative on a GPU that runs it at half precision, which with the tables' own worst
 * (4.4e-4 at g = -0.95, printed below) stays under the 1e-3. Mesa 22.3's llvmpipe gives the same
 * values to the digit with mediump honoured: the rounding is bounded here, not observed. */
#include "gl_fixture.h"

#define TOLERANCE 1e-3

static sbfx_cmf cmf;

static void load_cmf(void)
{
    cmf = sbfx_cie1931_2deg;
}

static sbfx_scene *parse(const char *text)
{
    char err[512];
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_parse(text, "tables.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (!scene) exit(1);
    return scene;
}

/* A module over the built-in explosion whose fire reaches [lo, hi] and whose smoke has g (the
 * range rule of src/scene/scene_tables.c: the emitters' lo .. (t0 + t1) * 1.25 with cooling off). */
static sbfx *module_for(gl_fixture *f, double lo, double hi, double g)
{
    /* the phase's table asked for: the analytic form is the default (issue 43) */
    sbfx *fx = fixture_module(f, (sbfx_desc){.ignore_timeline = true, .max_particles = 16, .table_phase = true});
    sbfx_medium_params *m = sbfx_media(fx);
    m[SBFX_FIRE].t0 = (float)lo;
    m[SBFX_FIRE].t1 = (float)(hi / SBFX_BLACKBODY_MARGIN - lo);
    m[SBFX_FIRE].cooling = 0.0f;
    m[SBFX_SMOKE].phase_g = (float)g;
    CHECK(sbfx_reload(fx) == SBFX_OK, "%s", sbfx_last_error(fx));
    return fx;
}

/* ---- ranges from the scene ------------------------------------------------------------------ */

static const char fire_scene[] =
    "media = { fire = { temperature = [%.1f, %.1f]; cooling = %g; }; };\n"
    "effects = { e = { steps = ( { type = \"emitter\"; medium = \"fire\"; intensity = [%.3f, %.3f]; fade_in = %g; } ); }; };\n";

static void range_of(gl_fixture *f, double t0, double t1, double cooling, double i0, double i1, double fade,
                     double *lo, double *hi)
{
    char text[512];
    snprintf(text, sizeof(text), fire_scene, t0, t1, cooling, i0, i1, fade);
    sbfx_scene *scene = parse(text);
    sbfx *fx = fixture_module(f, (sbfx_desc){.scene = scene});
    sbfx_scene_free(scene);
    const sbfx_tables *t = sbfx_get_tables(fx);
    *lo = t->blackbody_lo, *hi = t->blackbody_hi;
    printf("# fire T = (%g + %g d)(1 - %g (1 - I)), I in [%g, %g], fade-in %g: table %.1f .. %.1f K\n", t0, t1,
           cooling, i0, i1, fade, *lo, *hi);
    sbfx_destroy(fx);
}

CHECK_TEST(blackbody_range_follows_the_scene)
{
    gl_fixture f;
    fixture_open(&f, 4, 4);
    double lo, hi;
    range_of(&f, 1500, 2000, 0.45, 1, 0, 0.06, &lo, &hi); /* the seed's explosion */
    CHECK_NEAR(hi, 3500 * 1.25, 1e-3);
    CHECK_NEAR(lo, 1500 * 0.55 / 1.25, 1e-3); /* float cooling: 0.55 to 7 digits */
    range_of(&f, 3000, 5000, 0.0, 1, 1, 0, &lo, &hi); /* the hot scene: not clamped at 6000 */
    CHECK_NEAR(hi, 8000 * 1.25, 1e-3);
    CHECK_NEAR(lo, 3000 / 1.25, 1e-3);
    range_of(&f, 1500, 2000, 0.45, 3, 0.5, 0, &lo, &hi); /* intensity above 1 heats the fire */
    CHECK_NEAR(hi, 3500 * (1 - 0.45 * (1 - 3)) * 1.25, 1e-3);
    CHECK_NEAR(lo, 1500 * (1 - 0.45 * 0.5) / 1.25, 1e-3);
    range_of(&f, 300, 100, 1.0, 1, 0, 0.1, &lo, &hi); /* cold: nothing below 500 K */
    CHECK_NEAR(lo, SBFX_BLACKBODY_MIN_KELVIN, 1e-9);
    CHECK_NEAR(hi, 2 * SBFX_BLACKBODY_MIN_KELVIN, 1e-9);
    fixture_close(&f);
}

/* ---- black body ----------------------------------------------------------------------------- */

/* Error of the GPU's colour at T against Planck x CIE: relative to the largest channel, and
 * per channel for channels above 1 % of it. */
static void blackbody_error(sbfx *fx, double t, double *by_max, double *by_channel)
{
    const sbfx_tables *tab = sbfx_get_tables(fx);
    double want[3];
    float got[3], phase;
    sbfx_blackbody_rgb(&cmf, t, tab->blackbody_norm, want);
    CHECK(sbfx_fetch_luts(fx, SBFX_SMOKE, (float)t, 0.0f, got, &phase) == SBFX_OK, "%s", sbfx_last_error(fx));
    double top = fmax(want[0], fmax(want[1], want[2]));
    *by_max = *by_channel = 0.0;
    for (int k = 0; k < 3; k++) {
        double e = fabs(got[k] - want[k]);
        *by_max = fmax(*by_max, e / top);
        if (want[k] > 0.01 * top) *by_channel = fmax(*by_channel, e / want[k]);
    }
}

/* The entry where the table changes most from one entry to the next (relative luminance and
 * chromaticity), probed half-way to the next: the steepest point for linear interpolation. */
static double steepest_kelvin(const sbfx_tables *t)
{
    const float *e = t->blackbody;
    double worst = -1.0, at = t->blackbody_lo;
    for (int i = 0; i + 1 < SBFX_BLACKBODY_SIZE; i++) {
        double step = fabs(e[4 * i + 7] - e[4 * i + 3]);
        for (int k = 0; k < 3; k++) step += fabs(e[4 * i + 4 + k] - e[4 * i + k]);
        if (step <= worst) continue;
        worst = step;
        double w = 1.0 / t->blackbody_hi + (1.0 / t->blackbody_lo - 1.0 / t->blackbody_hi) * (i + 0.5) /
                                               (SBFX_BLACKBODY_SIZE - 1);
        at = 1.0 / w;
    }
    return at;
}

static void check_blackbody(gl_fixture *f, double lo, double hi)
{
    sbfx *fx = module_for(f, lo, hi, 0.0);
    const sbfx_tables *t = sbfx_get_tables(fx);
    CHECK(!t->blackbody_analytic, "the table over %g..%g K fell back to the analytic path", lo, hi);
    double ends[3] = {t->blackbody_lo, t->blackbody_hi, steepest_kelvin(t)};
    const char *names[3] = {"cool end", "hot end", "steepest point"};
    for (int i = 0; i < 3; i++) {
        double by_max, by_channel;
        blackbody_error(fx, ends[i], &by_max, &by_channel);
        printf("# black body %.0f..%.0f K, %s %.1f K: %.2e of the largest channel, %.2e per channel\n", lo, hi,
               names[i], ends[i], by_max, by_channel);
        CHECK(by_max <= TOLERANCE && by_channel <= TOLERANCE, "%s %g K: %g, %g", names[i], ends[i], by_max,
              by_channel);
    }
    double worst = 0.0, worst_channel = 0.0, worst_t = 0.0;
    for (int i = 0; i <= 2000; i++) { /* uniform in 1/T, 4 points per table cell */
        double w = 1.0 / t->blackbody_hi + (1.0 / t->blackbody_lo - 1.0 / t->blackbody_hi) * i / 2000.0;
        double by_max, by_channel;
        blackbody_error(fx, 1.0 / w, &by_max, &by_channel);
        if (by_max > worst) worst = by_max, worst_t = 1.0 / w;
        worst_channel = fmax(worst_channel, by_channel);
    }
    printf("# black body %.0f..%.0f K (%d entries): GPU worst %.2e of the largest channel (at %.0f K), %.2e per "
           "channel; the CPU lookup's %.2e\n", t->blackbody_lo, t->blackbody_hi, SBFX_BLACKBODY_SIZE, worst, worst_t,
           worst_channel, t->blackbody_error);
    CHECK(worst <= TOLERANCE && worst_channel <= TOLERANCE, "worst %g (at %g K), per channel %g", worst, worst_t,
          worst_channel);
    sbfx_destroy(fx);
}

CHECK_TEST(gpu_blackbody_within_tolerance)
{
    load_cmf();
    gl_fixture f;
    fixture_open(&f, 4, 4);
    check_blackbody(&f, 500.0, 20000.0);     /* the probe's range */
    check_blackbody(&f, 825.0, 3500.0);      /* the seed's explosion */
    check_blackbody(&f, 2400.0, 1.25e5);     /* a flash of 1e5 K */
    fixture_close(&f);
}

/* The range covers what the scene makes; outside it (media changed without sbfx_reload, fire
 * under 500 K) the lookup carries on along the end cells instead of clamping: Wien's law for
 * the luminance below the table, down to exactly 0 at T = 0; a drifting but changing colour
 * above it. */
CHECK_TEST(blackbody_outside_the_table)
{
    load_cmf();
    gl_fixture f;
    fixture_open(&f, 4, 4);
    sbfx *fx = module_for(&f, 1500.0, 3500.0, 0.0);
    const sbfx_tables *t = sbfx_get_tables(fx);
    float got[3], phase;
    for (double k = 0.0; k <= 1.0; k += 0.5) {
        CHECK(sbfx_fetch_luts(fx, SBFX_SMOKE, (float)k, 0.0f, got, &phase) == SBFX_OK);
        CHECK(got[0] == 0.0f && got[1] == 0.0f && got[2] == 0.0f, "T = %g K glows: %g %g %g", k, got[0], got[1],
              got[2]);
    }
    double below = 0.9 * t->blackbody_lo, above = 1.5 * t->blackbody_hi, by_max, by_channel;
    blackbody_error(fx, below, &by_max, &by_channel);
    printf("# %.0f K, 10 %% below the table: %.2e of the largest channel\n", below, by_max);
    CHECK(by_max < 0.01, "Wien's law below the table: %g", by_max);
    blackbody_error(fx, above, &by_max, &by_channel);
    printf("# %.0f K, 50 %% above the table: %.2e of the largest channel\n", above, by_max);
    CHECK(by_max < 0.1, "above the table: %g", by_max);
    float top[3];
    CHECK(sbfx_fetch_luts(fx, SBFX_SMOKE, (float)t->blackbody_hi, 0.0f, top, &phase) == SBFX_OK);
    CHECK(sbfx_fetch_luts(fx, SBFX_SMOKE, (float)above, 0.0f, got, &phase) == SBFX_OK);
    CHECK(got[2] / got[0] > 1.2 * top[2] / top[0] && got[1] > 1.5 * top[1], "clamped at the top: %g %g %g vs %g %g %g",
          got[0], got[1], got[2], top[0], top[1], top[2]);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* ---- phase function ------------------------------------------------------------------------- */

static double phase_error(sbfx *fx, double c, double g)
{
    float rgb[3], got;
    CHECK(sbfx_fetch_luts(fx, SBFX_SMOKE, 0.0f, (float)c, rgb, &got) == SBFX_OK, "%s", sbfx_last_error(fx));
    double want = sbfx_phase((double)(float)c, g);
    return fabs(got - want) / want;
}

/* cos of the table's coordinate t (the inverse of sbfx_phase_coordinate, by bisection). */
static double cos_at(double t, double g)
{
    double lo = -1.0, hi = 1.0;
    for (int i = 0; i < 60; i++) {
        double mid = 0.5 * (lo + hi);
        if ((sbfx_phase_coordinate(mid, g) < t) == (g >= 0.0)) lo = mid;
        else hi = mid;
    }
    return 0.5 * (lo + hi);
}

CHECK_TEST(gpu_phase_within_tolerance_for_every_g)
{
    gl_fixture f;
    fixture_open(&f, 4, 4);
    const double gs[] = {-0.95, -0.9, -0.7, -0.4, -0.019, 0.0, 0.02, 0.2, 0.5, 0.8, 0.9, 0.95};
    double worst_all = 0.0;
    for (size_t j = 0; j < ARRAY_SIZE(gs); j++) {
        sbfx *fx = module_for(&f, 1000.0, 4000.0, gs[j]);
        double g = (double)(float)gs[j];
        CHECK(sbfx_get_tables(fx)->phase_table[SBFX_SMOKE], "g = %g: no table", g);
        /* the back, the peak (the steepest point: the function's largest relative slope), then
         * a uniform cos grid and 4 points in every cell of the table's coordinate */
        double back = phase_error(fx, g < 0 ? 1.0 : -1.0, g), peak = phase_error(fx, g < 0 ? -1.0 : 1.0, g);
        double worst = fmax(back, peak), worst_c = 0.0;
        for (int i = 0; i <= 4 * (SBFX_PHASE_SIZE - 1); i++) {
            double cs[2] = {-1.0 + 2.0 * i / (4.0 * (SBFX_PHASE_SIZE - 1)), cos_at(i / (4.0 * (SBFX_PHASE_SIZE - 1)), g)};
            for (int k = 0; k < 2; k++) {
                double e = phase_error(fx, cs[k], g);
                if (e > worst) worst = e, worst_c = cs[k];
            }
        }
        printf("# phase g = %+.3f: back %.2e, peak %.2e, worst %.2e at cos %.6f; the CPU lookup's %.2e\n", g, back,
               peak, worst, worst_c, sbfx_get_tables(fx)->phase_error[SBFX_SMOKE]);
        CHECK(worst <= TOLERANCE, "g = %g: %g at cos %g", g, worst, worst_c);
        worst_all = fmax(worst_all, worst);
        sbfx_destroy(fx);
    }
    printf("# phase table (%d entries per medium), |g| <= 0.95: GPU worst %.2e\n", SBFX_PHASE_SIZE, worst_all);
    fixture_close(&f);
}

/* A g whose table would miss: that medium evaluates the function, the log says so once, the
 * others keep their tables. */
CHECK_TEST(phase_table_that_would_miss_falls_back_once)
{
    gl_fixture f;
    fixture_open(&f, 4, 4);
    sbfx_scene *scene = parse("media = { dust = { phase_g = 0.99; }; smoke = { phase_g = 0.5; }; };\n"
                              "effects = { e = { steps = ( { type = \"emitter\"; medium = \"dust\"; },\n"
                              "                            { type = \"emitter\"; medium = \"smoke\"; } ); }; };\n");
    sbfx *fx = fixture_module(&f, (sbfx_desc){.scene = scene, .table_phase = true});
    sbfx_scene_free(scene);
    const sbfx_tables *t = sbfx_get_tables(fx);
    printf("# g = 0.99: the table's CPU lookup is %.2e off; g = 0.5: %.2e\n", t->phase_error[SBFX_DUST],
           t->phase_error[SBFX_SMOKE]);
    CHECK(t->phase_analytic[SBFX_DUST] && !t->phase_table[SBFX_DUST], "dust keeps a table that misses");
    CHECK(t->phase_table[SBFX_SMOKE] && !t->phase_analytic[SBFX_SMOKE], "smoke lost its table");
    CHECK(f.warnings == 1, "%d warnings, want 1", f.warnings);
    CHECK(strstr(f.last_warning, "media.dust") && strstr(f.last_warning, "per fragment"), "log: %s",
          f.last_warning);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* The default since issue 43: the analytic phase, no phase table; the black body's table. */
CHECK_TEST(default_phase_is_analytic)
{
    gl_fixture f;
    fixture_open(&f, 4, 4);
    sbfx *fx = fixture_module(&f, (sbfx_desc){0});
    const sbfx_tables *t = sbfx_get_tables(fx);
    CHECK(t->phase_analytic[SBFX_DUST] && t->phase_analytic[SBFX_SMOKE], "the phase is not analytic by default");
    CHECK(!t->phase_table[SBFX_DUST] && !t->phase_table[SBFX_SMOKE], "a phase table by default");
    CHECK(!t->blackbody_analytic, "the black body's table is the default");
    sbfx_quality q;
    CHECK(sbfx_get_quality(fx, &q) == SBFX_OK && q.analytic_phase && !q.table_phase);
    sbfx_destroy(fx);
    /* desc.analytic_phase wins over table_phase (the analytic form asked for by name) */
    fx = fixture_module(&f, (sbfx_desc){.analytic_phase = true, .table_phase = true});
    CHECK(sbfx_get_tables(fx)->phase_analytic[SBFX_SMOKE], "table_phase won over analytic_phase");
    sbfx_destroy(fx);
    CHECK(f.warnings == 0, "%s", f.last_warning);
    fixture_close(&f);
}

/* desc.analytic_*: no table texture at all. */
CHECK_TEST(analytic_desc_uploads_no_tables)
{
    gl_fixture f;
    fixture_open(&f, 4, 4);
    sbfx *fx = fixture_module(&f, (sbfx_desc){.analytic_blackbody = true, .analytic_phase = true});
    sbfx_counters c;
    sbfx_stats(fx, &c);
    const sbfx_tables *t = sbfx_get_tables(fx);
    CHECK(t->blackbody_analytic && t->phase_analytic[SBFX_DUST] && t->phase_analytic[SBFX_SMOKE]);
    CHECK(c.textures == 1, "%d textures, want the detail volume only", c.textures);
    CHECK(f.warnings == 0, "asked for, not a fallback: %s", f.last_warning);
    sbfx_destroy(fx);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
