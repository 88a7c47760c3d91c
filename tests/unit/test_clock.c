/* The clock's periodic values stay exact however far it is from 0 (issue 13, docs/design.md §7): the
 * detail animation's phase and orbiting lights a year in move as they do at 0. No GL: the
 * module's clock state is set directly. */
#include <stdlib.h>
#include "check.h"
#include "module.h"

#define YEAR 31536000.0

static sbfx *clock_at(double start, double elapsed)
{
    sbfx *fx = sbfx_module_new(); /* the rooms zeroed, as sbfx_create finds them */
    fx->scene->desc.start_time = start;
    fx->sim->time = elapsed;
    return fx;
}

static double detail_at(double start, double elapsed)
{
    sbfx *fx = clock_at(start, elapsed);
    double t = sbfx_detail_time(fx);
    free(fx);
    return t;
}

/* The phase step between two clocks, taken the way the shader sees it: as floats, wrapped. */
static double float_step(double a, double b)
{
    double d = (double)(float)b - (double)(float)a;
    return d - floor(d + 0.5);
}

/* At t0 = a year (a clock started there, or a module up that long) the detail phase moves by
 * dt / 4 for a step dt, to 1e-6 of a loop, as floats. The seed's (float)(time * 0.25) moved by
 * 0 or 0.5 there. */
CHECK_TEST(detail_phase_moves_by_a_quarter_of_dt_a_year_in)
{
    const double steps[] = {1.0 / 120.0, 1.0 / 60.0, 0.1, 1.0, 3.3};
    const double clocks[][2] = {{YEAR, 0.0}, {0.0, YEAR}, {YEAR, YEAR + 0.37}, {1e10, 17.5}};
    for (size_t c = 0; c < ARRAY_SIZE(clocks); c++)
        for (size_t i = 0; i < ARRAY_SIZE(steps); i++) {
            double s = clocks[c][0], e = clocks[c][1], dt = steps[i];
            double a = detail_at(s, e), b = detail_at(s, e + dt);
            CHECK(a >= 0.0 && a < 1.0 && b >= 0.0 && b < 1.0, "phase %.9f, %.9f outside [0, 1)", a, b);
            double want = dt / 4.0 - floor(dt / 4.0 + 0.5);
            CHECK(fabs(float_step(a, b) - want) < 1e-6, "start %.0f + %.2f s: a step of %g s moved the phase "
                  "by %.9f, want %.9f", s, e, dt, float_step(a, b), want);
        }
    double seed = float_step((float)(YEAR * 0.25), (float)((YEAR + 1.0 / 120.0) * 0.25));
    printf("# the seed's float clock a year in: a 1/120 s step moves the phase by %g (want %g)\n", seed,
           1.0 / 480.0);
    CHECK(fabs(seed - 1.0 / 480.0) > 1e-3, "the float clock was exact: the test above shows nothing");
}

/* A year (a whole number of 4 s loops) in, the phase is what it is at the start, bit for bit. */
CHECK_TEST(a_year_in_is_the_start_of_the_loop)
{
    for (double e = 0.0; e < 8.0; e += 0.37)
        CHECK(detail_at(YEAR, e) == detail_at(0.0, e), "%.2f s after a year: %.17g vs %.17g", e,
              detail_at(YEAR, e), detail_at(0.0, e));
    CHECK(fabs(detail_at(YEAR + 1.0, 0.0) - 0.25) < 1e-12, "a year and 1 s: %.17g", detail_at(YEAR + 1.0, 0.0));
}

static void orbit_position(double start, double elapsed, float period, float out[3])
{
    sbfx *fx = clock_at(start, elapsed);
    fx->scene->light_count = 1;
    fx->scene->lights[0] = (sbfx_scene_light){.point = true,
                                       .orbit = {.on = true, .center = {0, 2, 0}, .radius = 3.6f, .period = period}};
    sbfx_orbit_lights(fx);
    memcpy(out, fx->scene->lights[0].vector, 3 * sizeof(float));
    free(fx);
}

/* Periods that divide a year: a clock started a year in puts the light where a clock at 0 does.
 * 3.7 s does not: a module up a year puts it where a clock started at the remainder does. */
CHECK_TEST(orbiting_light_a_year_in_is_where_it_is_at_zero)
{
    const float periods[] = {4.0f, -8.0f, 3.7f};
    for (size_t i = 0; i < ARRAY_SIZE(periods); i++)
        for (double e = 0.0; e < 5.0; e += 0.41) {
            float a[3], b[3];
            double p = periods[i];
            bool divides = fmod(YEAR, fabs(p)) == 0.0;
            orbit_position(divides ? YEAR : 0.0, divides ? e : YEAR + e, periods[i], a);
            orbit_position(divides ? 0.0 : fmod(YEAR, fabs(p)), e, periods[i], b);
            for (int k = 0; k < 3; k++)
                CHECK(fabsf(a[k] - b[k]) < 2e-5f, "period %g, %.2f s: axis %d %.7f vs %.7f", p, e, k,
                      (double)a[k], (double)b[k]);
        }
}

CHECK_TEST(clock_is_start_plus_elapsed)
{
    sbfx *fx = clock_at(YEAR, 2.5);
    CHECK(sbfx_time(fx) == YEAR + 2.5 && sbfx_elapsed(fx) == 2.5, "time %.9f elapsed %.9f", sbfx_time(fx),
          sbfx_elapsed(fx));
    free(fx);
    CHECK(sbfx_time(NULL) == 0.0 && sbfx_elapsed(NULL) == 0.0);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
