/* The element's arithmetic without GStreamer (integrations/gstreamer/): the clock it takes from
 * the buffers' running times (stream_clock.c) and where a tap's ray meets the ground
 * (ground_tap.c), against cases worked by hand and against sbfx's own matrices. */
#include <math.h>
#include <stdint.h>

#include "check.h"
#include "ground_tap.h"
#include "sbfx.h"
#include "stream_clock.h"

#define MS UINT64_C(1000000)
#define NONE STREAM_CLOCK_NONE

CHECK_TEST(clock_follows_the_running_time_from_the_first_buffer)
{
    struct stream_clock c = {0};
    stream_clock_set_rate(&c, 30, 1);
    CHECK(stream_clock_advance(&c, 500 * MS, NONE) == 0, "the first buffer is the module's zero");
    CHECK(stream_clock_advance(&c, 533 * MS, NONE) == 33 * MS);
    CHECK(stream_clock_advance(&c, 700 * MS, NONE) == 167 * MS, "a variable step is taken as it comes");
    CHECK_NEAR(stream_clock_seconds(&c), 0.2, 1e-12);
    CHECK(stream_clock_advance(&c, 700 * MS, NONE) == 0 && stream_clock_advance(&c, 650 * MS, NONE) == 0,
          "a repeated or earlier running time advances nothing");
    CHECK(stream_clock_advance(&c, 710 * MS, NONE) == 10 * MS, "... and leaves the last one where it was");
}

CHECK_TEST(buffers_without_a_running_time_advance_by_a_frame)
{
    struct stream_clock c = {0};
    stream_clock_set_rate(&c, 25, 1);
    CHECK(stream_clock_advance(&c, NONE, NONE) == 0);
    CHECK(stream_clock_advance(&c, NONE, 20 * MS) == 20 * MS, "its duration first");
    CHECK(stream_clock_advance(&c, NONE, NONE) == 40 * MS, "then the caps' frame");
    stream_clock_set_rate(&c, 0, 1);
    CHECK(stream_clock_advance(&c, NONE, NONE) == STREAM_CLOCK_FALLBACK_NS, "then 1/30 s");
    CHECK(c.untimed == 4, "%llu untimed", (unsigned long long)c.untimed);
    stream_clock_reset(&c);
    CHECK(!c.started && c.untimed == 4, "a reset forgets the stream, not the counts");
}

CHECK_TEST(a_jump_advances_ten_seconds_at_most)
{
    struct stream_clock c = {0};
    stream_clock_advance(&c, 0, NONE);
    CHECK(stream_clock_advance(&c, 3600000 * MS, NONE) == STREAM_CLOCK_MAX_STEP_NS);
    CHECK(c.clamped == 1);
    CHECK_NEAR(stream_clock_seconds(&c), 10.0, 1e-12);
    CHECK(stream_clock_advance(&c, 3600040 * MS, NONE) == 40 * MS, "the steps after it go on as they come");
    CHECK_NEAR(stream_clock_seconds(&c), 10.04, 1e-12);
}

/* A world point into pixels (top-left origin) through view and projection. */
static void to_pixel(const float view[16], const float p[16], const float w[3], int width, int height, double *x,
                     double *y)
{
    double v[4], c[4];
    for (int r = 0; r < 4; r++) v[r] = view[r] * w[0] + view[4 + r] * w[1] + view[8 + r] * w[2] + view[12 + r];
    for (int r = 0; r < 4; r++) c[r] = p[r] * v[0] + p[4 + r] * v[1] + p[8 + r] * v[2] + p[12 + r] * v[3];
    *x = (c[0] / c[3] + 1.0) * 0.5 * width;
    *y = (1.0 - c[1] / c[3]) * 0.5 * height;
}

static void check_round_trip(const float view[16], const float projection[16], const float ground[3])
{
    double x, y;
    to_pixel(view, projection, ground, 640, 360, &x, &y);
    float hit[3];
    CHECK(ground_tap(x, y, 640, 360, view, projection, hit), "(%g, %g, %g) at pixel (%.2f, %.2f) missed", ground[0],
          ground[1], ground[2], x, y);
    CHECK(fabs(hit[0] - ground[0]) < 1e-3 && hit[1] == 0.0f && fabs(hit[2] - ground[2]) < 1e-3,
          "(%g, %g, %g) came back as (%g, %g, %g)", ground[0], ground[1], ground[2], hit[0], hit[1], hit[2]);
}

CHECK_TEST(tap_comes_back_to_the_ground_point_under_it)
{
    const float eye[3] = {3.0f, 2.4f, 6.0f}, target[3] = {0.0f, 1.6f, 0.0f}, up[3] = {0.0f, 1.0f, 0.0f};
    float view[16], projection[16], off_axis[16];
    sbfx_look_at(view, eye, target, up);
    sbfx_perspective(projection, 50.0f * 3.14159265f / 180.0f, 16.0f / 9.0f, 0.1f, INFINITY);
    sbfx_frustum(off_axis, -0.02f, 0.08f, -0.05f, 0.01f, 0.1f, INFINITY);
    const float points[][3] = {{0.0f, 0.0f, 0.0f}, {1.5f, 0.0f, -2.0f}, {-2.0f, 0.0f, 1.0f}};
    for (int i = 0; i < 3; i++) {
        check_round_trip(view, projection, points[i]);
        check_round_trip(view, off_axis, points[i]);
    }
}

CHECK_TEST(tap_on_the_sky_meets_no_ground)
{
    const float eye[3] = {0.0f, 2.0f, 8.0f}, target[3] = {0.0f, 2.0f, 0.0f}, up[3] = {0.0f, 1.0f, 0.0f};
    float view[16], projection[16], hit[3];
    sbfx_look_at(view, eye, target, up);
    sbfx_perspective(projection, 1.0f, 1.0f, 0.1f, INFINITY);
    CHECK(!ground_tap(50, 10, 100, 100, view, projection, hit), "above the horizon");
    CHECK(!ground_tap(50, 50, 100, 100, view, projection, hit), "on the horizon: a level ray");
    CHECK(ground_tap(50, 90, 100, 100, view, projection, hit) && hit[2] < 8.0f, "below it: in front of the eye");
    CHECK(!ground_tap(50, 90, 0, 100, view, projection, hit), "a picture of no size");
    const float below[3] = {0.0f, -1.0f, 8.0f};
    sbfx_look_at(view, below, target, up);
    CHECK(!ground_tap(50, 90, 100, 100, view, projection, hit), "an eye under the ground");
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
