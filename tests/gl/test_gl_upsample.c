/* Nearest-depth upsampling (composite.frag, docs/accuracy-and-benchmarks.md): it picks one
 * low-res texel only at a depth edge that can hide particles. Where every opaque surface around
 * a pixel lies beyond every particle (a far floor meeting the sky at the horizon) the texels hold
 * the same particles, and it must blend them like bilinear upsampling instead of drawing 4 x 4
 * blocks; an occluder inside the cloud must still be treated as an edge. */
#include "gl_fixture.h"

#define W 160
#define H 96
#define CLOUD_DISTANCE 8.0 /* the explosion's centre, metres along -z */

typedef struct depth_layout {
    double left, right, band; /* opaque distances (INFINITY: none) of the halves and a middle band */
} depth_layout;

static double layout_distance(int x, int y, void *user)
{
    const depth_layout *l = user;
    if (y >= H / 2 - 6 && y < H / 2 + 6) return l->band;
    return x < W / 2 ? l->left : l->right;
}

/* The built-in explosion at 0.6 s, at `divisor` with `upsample`, into out (RGBA8). */
static void render(gl_fixture *f, int divisor, sbfx_upsample upsample, uint8_t *out)
{
    sbfx *fx = fixture_module(f, (sbfx_desc){.target_divisor = divisor, .upsample = upsample, .ignore_timeline = true});
    CHECK(sbfx_trigger(fx, "explosion", (const float[3]){0.0f, 0.0f, (float)-CLOUD_DISTANCE}) == SBFX_OK, "%s",
          sbfx_last_error(fx));
    while (sbfx_time(fx) < 0.6 - 1e-9) sbfx_update(fx, 1.0 / 60.0);
    glBindFramebuffer(GL_FRAMEBUFFER, f->out_fbo);
    glClearColor(0.4f, 0.5f, 0.7f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    CHECK(sbfx_render(fx, &f->frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, f->out_fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, out);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    sbfx_destroy(fx);
}

static int covered_pixels(const uint8_t *img)
{
    int n = 0;
    for (int i = 0; i < W * H; i++) n += abs(img[4 * i] - 102) + abs(img[4 * i + 2] - 179) > 8;
    return n;
}

CHECK_TEST(depth_edges_behind_every_particle_blend_like_bilinear)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    fixture_projection(&f, 1.0f, 0.1f, 1000.0f);
    depth_layout far = {40.0, INFINITY, 25.0}; /* floor, sky, a far wall: all beyond the cloud */
    fixture_depth(&f, layout_distance, &far);
    static uint8_t nd[W * H * 4], bl[W * H * 4];
    render(&f, 4, SBFX_UPSAMPLE_NEAREST_DEPTH, nd);
    render(&f, 4, SBFX_UPSAMPLE_BILINEAR, bl);
    int differing = 0, worst = 0;
    for (int i = 0; i < W * H * 4; i++) {
        int d = abs(nd[i] - bl[i]);
        differing += d > 0;
        if (d > worst) worst = d;
    }
    printf("# depth edges at 25, 40 m and the sky behind a cloud at %.0f m: %d covered pixels; nearest-depth "
           "and bilinear differ in %d channels (at most %d levels)\n", CLOUD_DISTANCE, covered_pixels(nd), differing,
           worst);
    CHECK(covered_pixels(nd) > 500, "the explosion covers only %d pixels", covered_pixels(nd));
    CHECK(differing == 0, "nearest-depth treated edges behind the particles as edges: %d channels differ by up "
          "to %d levels", differing, worst);
    fixture_close(&f);
}

/* A bar in front of the cloud's centre hides some of its particles: there nearest-depth must
 * still choose texels by depth, so it differs from bilinear along the bar's edges (and only
 * near them). How much closer to the full-resolution picture that keeps silhouettes is the
 * accuracy bench's "near silhouettes" column, on the example scene. */
CHECK_TEST(an_occluder_inside_the_cloud_is_still_an_edge)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    fixture_projection(&f, 1.0f, 0.1f, 1000.0f);
    depth_layout occluded = {40.0, INFINITY, CLOUD_DISTANCE - 0.5};
    fixture_depth(&f, layout_distance, &occluded);
    static uint8_t nd[W * H * 4], bl[W * H * 4];
    render(&f, 4, SBFX_UPSAMPLE_NEAREST_DEPTH, nd);
    render(&f, 4, SBFX_UPSAMPLE_BILINEAR, bl);
    int near_edges = 0, elsewhere = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            /* within a low-res texel and a half of the bar's edges, or of the halves' seam */
            bool near = abs(y - (H / 2 - 6)) <= 6 || abs(y - (H / 2 + 6)) <= 6 || abs(x - W / 2) <= 6;
            for (int c = 0; c < 3; c++) {
                bool differs = nd[4 * (y * W + x) + c] != bl[4 * (y * W + x) + c];
                near_edges += differs && near;
                elsewhere += differs && !near;
            }
        }
    printf("# a bar at %.1f m inside the cloud: nearest-depth differs from bilinear in %d channels near its "
           "edges, %d elsewhere\n", CLOUD_DISTANCE - 0.5, near_edges, elsewhere);
    CHECK(near_edges > 50, "nearest-depth no longer treats an occluder inside the cloud as an edge (%d channels)",
          near_edges);
    CHECK(elsewhere == 0, "nearest-depth differs from bilinear away from every edge (%d channels)", elsewhere);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
