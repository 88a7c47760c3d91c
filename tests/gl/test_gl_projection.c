/* Every OpenGL perspective (issue 10, docs/design.md §5): the same explosion over the same opaque scene
 * rendered with a finite far plane (1e5, 24-bit depth), an infinite far plane (24-bit depth)
 * and reversed-Z (GL_EXT_clip_control ZERO_TO_ONE, DEPTH_COMPONENT32F cleared to 0, GREATER)
 * gives the same picture within one 8-bit level; an off-axis frustum gives the matching half of
 * a wider symmetric frame; malformed projections are refused with a message naming the fault. */
#include "gl_fixture.h"
#include "host/test_scene.h"
#include "module.h"

#define W 128
#define H 72
#define NEAR 0.1f
#define FOV 0.87f

enum { FINITE, INFINITE, REVERSED, VARIANTS };
static const char *const variant_names[VARIANTS] = {"finite far 1e5", "infinite far", "reversed-Z"};

typedef struct variant_frame {
    struct test_scene scene;
    sbfx_frame frame;
    bool usable;
} variant_frame;

static void variant_projection(int v, float aspect, float p[16])
{
    sbfx_perspective(p, FOV, aspect, NEAR, v == FINITE ? 1e5f : INFINITY);
    if (v == REVERSED) sbfx_reverse_z(p, NEAR, INFINITY);
}

static bool variant_open(variant_frame *vf, int v, int w, int h, const gl_fixture *f)
{
    char err[256];
    memset(vf, 0, sizeof(*vf));
    CHECK(test_scene_create(&vf->scene, w, h, err, sizeof(err)) == 0, "%s", err);
    if (v == REVERSED && test_scene_use_reversed_z(&vf->scene, err, sizeof(err)) != 0) {
        printf("# %s skipped: %s\n", variant_names[v], err);
        return false;
    }
    vf->frame = f->frame;
    vf->frame.width = w, vf->frame.height = h;
    vf->frame.scene_color_texture = vf->scene.color_texture;
    vf->frame.scene_depth_texture = vf->scene.depth_texture;
    vf->frame.clip_depth_mode = v == REVERSED ? SBFX_CLIP_DEPTH_ZERO_TO_ONE : SBFX_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE;
    vf->usable = true;
    return true;
}

static sbfx_opacity_mode module_opacity; /* 0: the default (spherical) */

static sbfx *module_at(gl_fixture *f, const char *scene_path, double t, sbfx_upsample upsample)
{
    sbfx_scene *scene = NULL;
    char err[512];
    if (scene_path) CHECK(sbfx_scene_load(scene_path, &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    sbfx *fx = fixture_module(f, (sbfx_desc){.scene = scene, .ignore_timeline = true, .upsample = upsample,
                                                 .opacity = module_opacity});
    sbfx_scene_free(scene);
    sbfx_trigger(fx, "explosion", (const float[3]){0, 0, 0});
    while (sbfx_time(fx) < t - 1e-9) sbfx_update(fx, 1.0 / 60.0);
    return fx;
}

/* The scene's colour (of `colour_from`) into an output framebuffer, sbfx over it, read back. */
static void render_over(GLuint colour_from, GLuint out_fbo, sbfx *fx, const sbfx_frame *frame, uint8_t *rgba)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, colour_from);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, out_fbo);
    glBlitFramebuffer(0, 0, frame->width, frame->height, 0, 0, frame->width, frame->height, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
    sbfx_frame f = *frame;
    f.out_framebuffer = out_fbo;
    CHECK(sbfx_render(fx, &f) == SBFX_OK, "%s", sbfx_last_error(fx));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, out_fbo);
    glReadPixels(0, 0, frame->width, frame->height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

static int max_level_difference(const uint8_t *a, const uint8_t *b, size_t n, int *pixels_differing)
{
    int worst = 0;
    *pixels_differing = 0;
    for (size_t i = 0; i < n; i++) {
        int d = abs((int)a[i] - (int)b[i]);
        worst = d > worst ? d : worst;
        *pixels_differing += d != 0;
    }
    return worst;
}

/* Each variant draws its own depth; all share the finite variant's colour, so the pictures
 * differ only by what sbfx made of the depth. Bilinear upsampling is continuous in the depths:
 * every value agrees within one level. Nearest-depth upsampling switches where a low-res depth
 * differs from the pixel's by the 5% threshold: a pixel within an ulp of it may switch in one
 * encoding and not the other (a different sample, not a different depth); those pixels are
 * counted and must stay under 1%. */
static void projections_agree(const char *scene_path, const double *times, int count, sbfx_upsample upsample)
{
    gl_fixture f;
    fixture_open(&f, W, H);
    variant_frame vf[VARIANTS];
    for (int v = 0; v < VARIANTS; v++) variant_open(&vf[v], v, W, H, &f);
    static uint8_t image[VARIANTS][W * H * 4];
    for (int k = 0; k < count; k++) {
        for (int v = 0; v < VARIANTS; v++) {
            if (!vf[v].usable) continue;
            float unused[16];
            test_scene_orbit_camera(times[k], (float)W / H, vf[v].frame.view, unused);
            variant_projection(v, (float)W / H, vf[v].frame.projection);
            CHECK(test_scene_draw(&vf[v].scene, vf[v].frame.view, vf[v].frame.projection) == 0);
        }
        for (int v = 0; v < VARIANTS; v++) {
            if (!vf[v].usable) continue;
            sbfx *fx = module_at(&f, scene_path, times[k], upsample);
            render_over(vf[FINITE].scene.framebuffer, f.out_fbo, fx, &vf[v].frame, image[v]);
            sbfx_destroy(fx);
        }
        for (int v = INFINITE; v < VARIANTS; v++) {
            if (!vf[v].usable) continue;
            int differing, switched = 0, worst = max_level_difference(image[FINITE], image[v], sizeof(image[v]), &differing);
            for (int i = 0; i < W * H; i++)
                for (int c = 0; c < 3; c++)
                    if (abs(image[v][4 * i + c] - image[FINITE][4 * i + c]) > 1) {
                        switched++;
                        break;
                    }
            printf("# %s, %s, t = %.2f s: %s vs finite far: max %d levels, %d channel values differ, %d pixels by more "
                   "than 1 level\n", scene_path ? scene_path : "built-in explosion",
                   upsample == SBFX_UPSAMPLE_BILINEAR ? "bilinear" : "nearest-depth", times[k], variant_names[v], worst,
                   differing, switched);
            if (upsample == SBFX_UPSAMPLE_BILINEAR)
                CHECK(worst <= 1, "%s differs from the finite-far picture by %d levels", variant_names[v], worst);
            else
                CHECK(switched * 100 < W * H, "%s: %d pixels switched upsampling", variant_names[v], switched);
        }
        int lit = 0;
        for (size_t i = 0; i < sizeof(image[0]); i += 4) lit += image[FINITE][i] != 0;
        CHECK(lit > 0, "nothing drawn");
    }
    for (int v = 0; v < VARIANTS; v++) test_scene_destroy(&vf[v].scene);
    fixture_close(&f);
    if (!vf[REVERSED].usable) CHECK_SKIP("reversed-Z: GL_EXT_clip_control missing (finite and infinite far agreed)");
}

CHECK_TEST(finite_infinite_and_reversed_z_agree)
{
    const double times[] = {0.3, 1.2};
    projections_agree(NULL, times, 2, SBFX_UPSAMPLE_BILINEAR);
}

CHECK_TEST(nearest_depth_upsampling_across_projections)
{
    const double times[] = {0.3, 1.2};
    projections_agree(NULL, times, 2, SBFX_UPSAMPLE_NEAREST_DEPTH);
}

/* Depth of field, velocity blur (reprojected depth) and shimmer read the host depth too. */
CHECK_TEST(post_effects_agree_across_projections)
{
    const double times[] = {0.6};
    projections_agree("scenes/post.cfg", times, 1, SBFX_UPSAMPLE_BILINEAR);
}

/* ---- off-axis: the top-right quarter of a symmetric frame twice as wide and high ------------- */

/* The spherical billboards and the exact perspective ray both rebuild the ray from [8], [9]. */
static void off_axis(sbfx_opacity_mode opacity)
{
    module_opacity = opacity;
    gl_fixture f;
    fixture_open(&f, 2 * W, 2 * H);
    variant_frame wide, half;
    variant_open(&wide, FINITE, 2 * W, 2 * H, &f);
    variant_open(&half, FINITE, W, H, &f);
    float unused[16];
    test_scene_orbit_camera(0.5, (float)W / H, wide.frame.view, unused);
    memcpy(half.frame.view, wide.frame.view, sizeof(wide.frame.view));
    float top = NEAR * tanf(FOV * 0.5f), right = top * (float)W / H;
    sbfx_frustum(wide.frame.projection, -right, right, -top, top, NEAR, 200.0f);
    sbfx_frustum(half.frame.projection, 0.0f, right, 0.0f, top, NEAR, 200.0f); /* p[8] = p[9] = 1 */
    CHECK(half.frame.projection[8] == 1.0f && half.frame.projection[9] == 1.0f &&
          half.frame.projection[10] == wide.frame.projection[10]);
    CHECK(test_scene_draw(&wide.scene, wide.frame.view, wide.frame.projection) == 0);
    /* the off-axis host's opaque scene is the wide one's quarter (its own raster would round
     * triangle edges differently; what is compared is sbfx) */
    glBindFramebuffer(GL_READ_FRAMEBUFFER, wide.scene.framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, half.scene.framebuffer);
    glBlitFramebuffer(W, H, 2 * W, 2 * H, 0, 0, W, H, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    GLuint half_out_tex, half_out;
    glGenTextures(1, &half_out_tex);
    glBindTexture(GL_TEXTURE_2D, half_out_tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, W, H);
    glGenFramebuffers(1, &half_out);
    glBindFramebuffer(GL_FRAMEBUFFER, half_out);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, half_out_tex, 0);
    static uint8_t wide_image[4 * W * H * 4], half_image[W * H * 4], wide_right[W * H * 4];
    sbfx *fx = module_at(&f, NULL, 0.5, SBFX_UPSAMPLE_NEAREST_DEPTH);
    render_over(wide.scene.framebuffer, f.out_fbo, fx, &wide.frame, wide_image);
    sbfx_destroy(fx);
    fx = module_at(&f, NULL, 0.5, SBFX_UPSAMPLE_NEAREST_DEPTH);
    render_over(half.scene.framebuffer, half_out, fx, &half.frame, half_image);
    sbfx_counters c;
    sbfx_stats(fx, &c);
    /* depth, (the low-res corners where RGBA32F renders), particles, composite */
    CHECK(c.passes == 3 + sbfx_float32_renderable(), "the off-axis frame drew %d passes", c.passes);
    sbfx_destroy(fx);
    /* the first columns and rows upsample from texels beyond the seams in the wide frame; the
     * off-axis frame ends there (clamped): compared where the footprint is inside */
    const int border = 2; /* divisor / 2 */
    for (int y = 0; y < H; y++) {
        memcpy(&wide_right[4 * y * W], &wide_image[4 * ((y + H) * 2 * W + W)], 4 * W);
        for (int x = 0; x < W; x++)
            if (x < border || y < border) memcpy(&half_image[4 * (y * W + x)], &wide_right[4 * (y * W + x)], 4);
    }
    int differing, worst = max_level_difference(wide_right, half_image, sizeof(half_image), &differing);
    static uint8_t scene_only[W * H * 4];
    glBindFramebuffer(GL_READ_FRAMEBUFFER, half.scene.framebuffer);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, scene_only);
    int covered, unused_worst = max_level_difference(scene_only, half_image, sizeof(half_image), &covered);
    (void)unused_worst;
    CHECK(covered > 1000, "the explosion hardly shows in the off-axis frame (%d values)", covered);
    printf("# off-axis (projection[8] = [9] = 1), %s opacity, vs the quarter of the symmetric frame: max %d levels, "
           "%d values differ\n", opacity == SBFX_OPACITY_EXACT ? "exact" : "spherical", worst, differing);
    CHECK(worst <= 1, "off-axis frame differs by %d levels", worst);
    glDeleteFramebuffers(1, &half_out);
    glDeleteTextures(1, &half_out_tex);
    test_scene_destroy(&wide.scene);
    test_scene_destroy(&half.scene);
    fixture_close(&f);
}

CHECK_TEST(off_axis_frustum_matches_wide_frame) { off_axis(SBFX_OPACITY_SPHERICAL); }
CHECK_TEST(off_axis_exact_ray_matches_wide_frame) { off_axis(SBFX_OPACITY_EXACT); }

/* ---- malformed projections ------------------------------------------------------------------ */

typedef struct bad_projection {
    int index;          /* entry to change, -1: see fix() */
    float value;
    const char *message; /* must appear in sbfx_last_error */
} bad_projection;

CHECK_TEST(malformed_projections_refused_with_the_fault_named)
{
    gl_fixture f;
    fixture_open_far(&f, 16, 16);
    sbfx *fx = fixture_module(&f, (sbfx_desc){0});
    sbfx_trigger(fx, "explosion", (const float[3]){0, 0, -5});
    sbfx_update(fx, 0.2);
    const bad_projection cases[] = {
        {10, NAN, "projection[10] is nan"},
        {0, INFINITY, "projection[0] is inf"},
        {11, 0.0f, "orthographic"},          /* with [15] = 1 below */
        {11, -2.0f, "projection[11] must be -1"},
        {4, 0.3f, "projection[4] is 0.3"},   /* skew */
        {2, 0.1f, "projection[2] is 0.1"},   /* oblique near plane */
        {5, 0.0f, "zero scale"},
        {14, 0.0f, "projection[14] is 0"},
        {10, -0.5f, "far plane"},            /* far behind the camera */
        {10, -3.0f, "near plane"},           /* near behind the camera: p14 / (p10 - 1) < 0 ... */
    };
    for (size_t i = 0; i < ARRAY_SIZE(cases); i++) {
        sbfx_frame frame = f.frame;
        frame.projection[cases[i].index] = cases[i].value;
        if (cases[i].value == 0.0f && cases[i].index == 11) frame.projection[15] = 1.0f, frame.projection[14] = 0.0f;
        if (i == ARRAY_SIZE(cases) - 1) frame.projection[14] = 1.0f; /* reversed sign with p10 < -1: near < 0 */
        sbfx_result r = sbfx_render(fx, &frame);
        CHECK(r == SBFX_ERR_INVALID_ARGUMENT && strstr(sbfx_last_error(fx), cases[i].message),
              "case %zu: result %d, message \"%s\" should say \"%s\"", i, r, sbfx_last_error(fx), cases[i].message);
    }
    sbfx_frame frame = f.frame;
    frame.clip_depth_mode = (sbfx_clip_depth_mode)7;
    CHECK(sbfx_render(fx, &frame) == SBFX_ERR_INVALID_ARGUMENT && strstr(sbfx_last_error(fx), "clip_depth_mode"));
    /* and the good ones pass: finite, infinite, off-axis, reversed ([-1, 1] and [0, 1]) */
    float good[5][16];
    sbfx_perspective(good[0], 1.0f, 1.0f, 0.1f, 100.0f);
    sbfx_perspective(good[1], 1.0f, 1.0f, 0.1f, INFINITY);
    sbfx_frustum(good[2], -0.02f, 0.1f, -0.05f, 0.01f, 0.1f, INFINITY);
    sbfx_perspective(good[3], 1.0f, 1.0f, 0.1f, INFINITY);
    sbfx_reverse_z(good[3], 0.1f, INFINITY);
    sbfx_perspective(good[4], 1.0f, 1.0f, 100.0f, 0.1f); /* near and far swapped: reversed in [-1, 1] */
    for (int i = 0; i < 5; i++) {
        memcpy(frame.projection, good[i], sizeof(good[i]));
        frame.clip_depth_mode = i == 3 ? SBFX_CLIP_DEPTH_ZERO_TO_ONE : SBFX_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE;
        CHECK(sbfx_render(fx, &frame) == SBFX_OK, "good projection %d refused: %s", i, sbfx_last_error(fx));
    }
    CHECK(good[1][10] == -1.0f && good[1][14] == -0.2f, "infinite far: p10 %g p14 %g", good[1][10], good[1][14]);
    CHECK(good[3][10] == 0.0f && good[3][14] == 0.1f, "reversed infinite: p10 %g p14 %g", good[3][10], good[3][14]);
    sbfx_destroy(fx);
    fixture_close(&f);
}

/* Window depth <-> distance in double, every convention, including the far-field case. */
CHECK_TEST(window_depth_round_trip)
{
    sbfx_frame frame = {0};
    const double distances[] = {0.1, 1.0, 8.0, 3000.0, 3000.01, 1e5};
    for (int v = 0; v < VARIANTS; v++) {
        variant_projection(v, 1.0f, frame.projection);
        frame.clip_depth_mode = v == REVERSED ? SBFX_CLIP_DEPTH_ZERO_TO_ONE : SBFX_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE;
        for (size_t i = 0; i < ARRAY_SIZE(distances); i++) {
            double z = distances[i], back = sbfx_window_distance(&frame, sbfx_window_depth(&frame, z));
            /* float window depth: standard resolves z^2 / (n 2^24), reversed-Z z 2^-24 */
            double tol = v == REVERSED ? z * 1.2e-7 : z * z / (0.1 * 16777216.0) * 2.0 + 1e-6;
            if (v == FINITE && z >= 1e5) continue; /* at the far plane: the clear value */
            CHECK(fabs(back - z) <= tol, "%s: %g -> %g (tolerance %g)", variant_names[v], z, back, tol);
        }
        CHECK(isinf(sbfx_window_distance(&frame, v == REVERSED ? 0.0f : 1.0f)), "%s: clear value", variant_names[v]);
    }
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
