/* The look (issue 17 item 1, docs/design.md §8, docs/look.md): the rendered clouds of the example scenes
 * have the fine structure of turbulent smoke, and it is the detail's. Per scene, from its own
 * camera (and one other azimuth), at a time its cloud fills enough sky for the 32 px scale:
 *   - full-resolution target, detail on: beta (tests/look/look_metrics.h) in [2.4, 3.9];
 *   - detail off (every strength 0): beta rises by at least 1.
 * lit-smoke, whose lit smoke textures carry its structure with or without the detail: beta in
 * range only (its first view, 3 s, nearest the lower bound, and 5 s nearest the upper).
 * 960 x 540 (the metric's 32 px scale needs the size), llvmpipe. Not here (docs/look.md says
 * why, with the numbers): barrage and post, whose clouds never fill 129 x 129 px of smooth sky. */
#include <math.h>

#include "check.h"
#include "egl/egl_headless.h"
#include "look_metrics.h"
#include "look_render.h"

#define W 960
#define H 540
#define BETA_LO 2.4
#define BETA_HI 3.9

typedef struct look_case {
    const char *scene;
    double t;
    float azimuth_offset;
} look_case;

static double measure(look_renderer *r, const look_case *c, bool detail_off, const uint8_t *mask, uint8_t *mask_out)
{
    char err[512];
    look_shot shot = {c->scene, c->t, c->azimuth_offset, 1, detail_off, NULL, false, 1, false};
    CHECK(look_render(r, &shot, err, sizeof err) == 0, "%s", err);
    if (mask_out) look_effect_mask(r->out_rgba, r->background_rgba, W, H, mask_out);
    double *y = malloc(sizeof(double) * W * H);
    if (!y) CHECK_SKIP("out of memory");
    look_luminance(r->out_rgba, (size_t)W * H, y);
    look_spectrum s;
    CHECK(look_measure(y, mask ? mask : mask_out, W, H, &s) == 0);
    free(y);
    return s.beta;
}

static void check_case_rise(const look_case *c, bool rise)
{
    struct egl_headless egl;
    char err[512];
    if (egl_headless_open(&egl, err, sizeof err) != 0) CHECK_SKIP("no headless GLES 3.0 context: %s", err);
    look_renderer r;
    CHECK(look_renderer_open(&r, W, H, err, sizeof err) == 0, "%s", err);
    uint8_t *mask = malloc((size_t)W * H);
    if (!mask) CHECK_SKIP("out of memory");
    double on = measure(&r, c, false, NULL, mask);
    double off = rise ? measure(&r, c, true, mask, NULL) : NAN; /* the same pixels */
    printf("# %s t=%.2f azimuth %+.0f: beta %.3f with detail, %.3f without\n", c->scene, c->t, c->azimuth_offset,
           on, off);
    CHECK(on >= BETA_LO && on <= BETA_HI, "%s: beta %g outside [%g, %g]", c->scene, on, BETA_LO, BETA_HI);
    if (rise) CHECK(off - on >= 1.0, "%s: detail off moves beta by %g only", c->scene, off - on);
    free(mask);
    look_renderer_close(&r);
    egl_headless_close(&egl);
}

static void check_case(const look_case *c) { check_case_rise(c, true); }

CHECK_TEST(lit_smoke_default_view) { check_case_rise(&(look_case){"scenes/lit-smoke.cfg", 3.0, 0.0f}, false); }
CHECK_TEST(lit_smoke_later) { check_case_rise(&(look_case){"scenes/lit-smoke.cfg", 5.0, 0.0f}, false); }
CHECK_TEST(smoke_default_view) { check_case(&(look_case){"scenes/smoke.cfg", 3.0, 0.0f}); }
CHECK_TEST(explosion_default_view) { check_case(&(look_case){"scenes/explosion.cfg", 2.2, 0.0f}); }
CHECK_TEST(explosion_other_view) { check_case(&(look_case){"scenes/explosion.cfg", 2.2, 100.0f}); }
CHECK_TEST(dust_storm_default_view) { check_case(&(look_case){"scenes/dust-storm.cfg", 2.5, 0.0f}); }
CHECK_TEST(dust_storm_other_view) { check_case(&(look_case){"scenes/dust-storm.cfg", 2.5, -140.0f}); }
CHECK_TEST(campfire_default_view) { check_case(&(look_case){"scenes/campfire.cfg", 3.5, 0.0f}); }
/* heat shimmer in front of the fire: detail off must take the shimmer's turbulence too */
CHECK_TEST(campfire_through_the_heat) { check_case(&(look_case){"scenes/campfire.cfg", 2.0, -140.0f}); }

int main(int argc, char **argv) { return check_main_args(argc, argv); }
