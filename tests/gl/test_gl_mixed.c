/* Mixed resolution (SBFX_UPSAMPLE_MIXED, src/render/refine.c): the particles shaded again at full
 * resolution where the quarter-resolution target fails, at an occluder's edges inside the cloud
 * and along the fire's silhouette against the sky. Against the same frame at full resolution
 * (RGBA32F, the target the refinement approximates) it must be closer than nearest-depth
 * upsampling where the coarse target fails and no worse anywhere else; it refines a minority of
 * the pixels the particles cover, with finite values, three passes more and no allocation. */
#include "gl_fixture.h"
#include "host/host_depth.h"

#define W 192
#define H 112
#define CLOUD_DISTANCE 8.0 /* the explosion's centre, metres along -z */
#define BAR_DISTANCE (CLOUD_DISTANCE - 0.5)

typedef struct depth_layout {
    double background, bar; /* opaque distances (INFINITY: none) */
} depth_layout;

/* A horizontal bar through the cloud's middle in front of its centre, the background elsewhere. */
static bool in_bar(int y) { return y >= H / 2 - 7 && y < H / 2 + 7; }

static double layout_distance(int x, int y, void *user)
{
    (void)x;
    const depth_layout *l = user;
    return in_bar(y) ? l->bar : l->background;
}

typedef struct frame_result {
    uint8_t rgba[W * H * 4];
    sbfx_counters counters;
    int refined;      /* pixels the refinement shaded (mixed only) */
    bool finite;      /* the refine target holds no NaN or Inf */
} frame_result;

static void refine_stats(sbfx *fx, frame_result *out)
{
    static float target[W * H * 4];
    int w = 0, h = 0;
    CHECK(sbfx_read_refine_target(fx, target, ARRAY_SIZE(target), &w, &h) == SBFX_OK, "%s", sbfx_last_error(fx));
    CHECK(w == W && h == H, "refine target %dx%d", w, h);
    out->finite = all_finite(target, (size_t)w * h * 4);
    out->refined = 0;
    for (int i = 0; i < w * h; i++) out->refined += target[4 * i + 3] >= 0.0f;
}

static void clear_output(gl_fixture *f)
{
    glBindFramebuffer(GL_FRAMEBUFFER, f->out_fbo);
    glClearColor(0.4f, 0.5f, 0.7f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

/* The built-in explosion at `t` s, at `divisor` with `upsample` and `format`, over the sky colour. */
static void render(gl_fixture *f, double t, int divisor, sbfx_upsample upsample, sbfx_target_format format,
                   frame_result *out)
{
    sbfx *fx = fixture_module(f, (sbfx_desc){.target_divisor = divisor, .upsample = upsample, .target_format = format,
                                             .ignore_timeline = true});
    CHECK(sbfx_trigger(fx, "explosion", (const float[3]){0.0f, 0.0f, (float)-CLOUD_DISTANCE}) == SBFX_OK, "%s",
          sbfx_last_error(fx));
    while (sbfx_time(fx) < t - 1e-9) sbfx_update(fx, 1.0 / 60.0);
    clear_output(f);
    CHECK(sbfx_render(fx, &f->frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    sbfx_stats(fx, &out->counters);
    if (upsample == SBFX_UPSAMPLE_MIXED) {
        refine_stats(fx, out);
        /* a second frame allocates nothing more (the targets exist); the output cleared again,
         * since the composite blends over it */
        clear_output(f);
        CHECK(sbfx_render(fx, &f->frame) == SBFX_OK, "%s", sbfx_last_error(fx));
        sbfx_counters again;
        sbfx_stats(fx, &again);
        CHECK(again.heap_allocs_after_load == out->counters.heap_allocs_after_load,
              "a mixed-resolution frame allocated %llu times",
              (unsigned long long)(again.heap_allocs_after_load - out->counters.heap_allocs_after_load));
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, f->out_fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, out->rgba);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    sbfx_destroy(fx);
}

/* The fixture at W x H with its projection, over `layout`'s depths; false where there is no
 * colour-renderable RGBA16F target, which mixed resolution needs. */
static bool open_over(gl_fixture *f, depth_layout layout)
{
    fixture_open(f, W, H);
    if (!fixture_has_extension("GL_EXT_color_buffer_half_float") && !fixture_has_extension("GL_EXT_color_buffer_float"))
        return false;
    fixture_projection(f, 1.0f, 0.1f, 1000.0f);
    fixture_depth(f, layout_distance, &layout);
    return true;
}

typedef struct errors {
    double edge, elsewhere; /* mean |error| in 8-bit levels near the edges, and over the rest of the cloud */
    int edge_pixels, other_pixels;
} errors;

/* Against the full-resolution frame, over the pixels the cloud covers there (differs from the sky
 * colour): near an edge (`near_edge`) and elsewhere. */
static errors compare(const frame_result *a, const frame_result *full, bool (*near_edge)(const frame_result *, int, int))
{
    errors e = {0};
    double edge = 0.0, other = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *p = &a->rgba[4 * (y * W + x)], *q = &full->rgba[4 * (y * W + x)];
            if (abs(q[0] - 102) + abs(q[1] - 128) + abs(q[2] - 179) <= 3) continue; /* sky in both */
            double d = (abs(p[0] - q[0]) + abs(p[1] - q[1]) + abs(p[2] - q[2])) / 3.0;
            if (near_edge(full, x, y)) edge += d, e.edge_pixels++;
            else other += d, e.other_pixels++;
        }
    e.edge = e.edge_pixels ? edge / e.edge_pixels : 0.0;
    e.elsewhere = e.other_pixels ? other / e.other_pixels : 0.0;
    return e;
}

/* Within a coarse texel of the bar's edges. */
static bool near_bar(const frame_result *full, int x, int y)
{
    (void)full, (void)x;
    return abs(y - (H / 2 - 7)) <= 4 || abs(y - (H / 2 + 7)) <= 4;
}

/* Within a coarse texel of the cloud's silhouette against the sky in the full-resolution frame. */
static bool near_silhouette(const frame_result *full, int x, int y)
{
    for (int j = -4; j <= 4; j++)
        for (int i = -4; i <= 4; i++) {
            int u = x + i, v = y + j;
            if (u < 0 || v < 0 || u >= W || v >= H) continue;
            const uint8_t *q = &full->rgba[4 * (v * W + u)];
            if (abs(q[0] - 102) + abs(q[1] - 128) + abs(q[2] - 179) <= 3) return true;
        }
    return false;
}

static int covered(const frame_result *r)
{
    int n = 0;
    for (int i = 0; i < W * H; i++)
        n += abs(r->rgba[4 * i] - 102) + abs(r->rgba[4 * i + 1] - 128) + abs(r->rgba[4 * i + 2] - 179) > 3;
    return n;
}

/* Nearest-depth, mixed and full resolution of one frame over `layout`; returns the errors. */
static void three(gl_fixture *f, double t, frame_result *nd, frame_result *mx, frame_result *full)
{
    render(f, t, 4, SBFX_UPSAMPLE_NEAREST_DEPTH, SBFX_FORMAT_DEFAULT, nd);
    render(f, t, 4, SBFX_UPSAMPLE_MIXED, SBFX_FORMAT_DEFAULT, mx);
    render(f, t, 1, SBFX_UPSAMPLE_NEAREST_DEPTH, SBFX_FORMAT_RGBA32F, full);
}

/* The passes and draws a mixed frame adds to a nearest-depth one: the full-resolution depth and
 * the mark (one tiled draw each) and the particles again (as many draws as the coarse pass). */
static void check_counters(const frame_result *nd, const frame_result *mx)
{
    CHECK(mx->counters.passes == nd->counters.passes + 3, "passes: nearest-depth %d, mixed %d",
          nd->counters.passes, mx->counters.passes);
    /* nearest-depth: depth, corners, composite (one draw each) and the particle runs */
    int runs = nd->counters.draw_calls - 3;
    CHECK(runs > 0 && mx->counters.draw_calls == nd->counters.draw_calls + 2 + runs,
          "draw calls: nearest-depth %d, mixed %d", nd->counters.draw_calls, mx->counters.draw_calls);
}

CHECK_TEST(an_occluder_inside_the_cloud_is_refined)
{
    gl_fixture f;
    if (!open_over(&f, (depth_layout){INFINITY, BAR_DISTANCE}))
        CHECK_SKIP("mixed resolution needs a colour-renderable RGBA16F target");
    static frame_result nd, mx, full;
    three(&f, 0.6, &nd, &mx, &full);
    errors end = compare(&nd, &full, near_bar), emx = compare(&mx, &full, near_bar);
    int cover = covered(&full);
    printf("# a bar at %.1f m inside the cloud at 0.6 s: %d pixels covered, %d refined; against full resolution, "
           "near the bar's edges (%d px) nearest-depth %.2f, mixed %.2f levels; elsewhere (%d px) %.2f, %.2f\n",
           BAR_DISTANCE, cover, mx.refined, end.edge_pixels, end.edge, emx.edge, end.other_pixels, end.elsewhere,
           emx.elsewhere);
    CHECK(mx.finite, "the refine target holds NaN or Inf");
    CHECK(cover > 2000, "the cloud covers only %d pixels", cover);
    CHECK(mx.refined > 0 && mx.refined < cover, "%d pixels refined of %d covered", mx.refined, cover);
    /* the refinement's point: at most half the error where the coarse target fails... */
    CHECK(emx.edge <= 0.5 * end.edge, "near the bar's edges: mixed %.2f, nearest-depth %.2f levels", emx.edge,
          end.edge);
    /* ...and no worse elsewhere (a refined pixel is the full-resolution one; up to one level's
     * rounding where the two meet) */
    CHECK(emx.elsewhere <= end.elsewhere + 0.05, "away from the edges: mixed %.2f, nearest-depth %.2f levels",
          emx.elsewhere, end.elsewhere);
    check_counters(&nd, &mx);
    fixture_close(&f);
}

/* A young fireball against the sky, no surface anywhere: only the contrast of the coarse image
 * marks pixels, along the dense fire's silhouette. */
CHECK_TEST(the_fire_silhouette_against_the_sky_is_refined)
{
    gl_fixture f;
    if (!open_over(&f, (depth_layout){INFINITY, INFINITY}))
        CHECK_SKIP("mixed resolution needs a colour-renderable RGBA16F target");
    static frame_result nd, mx, full;
    three(&f, 0.3, &nd, &mx, &full);
    errors end = compare(&nd, &full, near_silhouette), emx = compare(&mx, &full, near_silhouette);
    int cover = covered(&full);
    printf("# the fireball at 0.3 s against the sky: %d pixels covered, %d refined; against full resolution, "
           "on the silhouette band (%d px) nearest-depth %.2f, mixed %.2f levels; inside (%d px) %.2f, %.2f\n",
           cover, mx.refined, end.edge_pixels, end.edge, emx.edge, end.other_pixels, end.elsewhere, emx.elsewhere);
    CHECK(mx.finite, "the refine target holds NaN or Inf");
    CHECK(mx.refined > 0 && mx.refined < cover, "%d pixels refined of %d covered", mx.refined, cover);
    CHECK(emx.edge <= 0.5 * end.edge, "on the silhouette: mixed %.2f, nearest-depth %.2f levels", emx.edge, end.edge);
    CHECK(emx.elsewhere <= end.elsewhere + 0.05, "inside: mixed %.2f, nearest-depth %.2f levels", emx.elsewhere,
          end.elsewhere);
    check_counters(&nd, &mx);
    fixture_close(&f);
}

#define GL_LOWER_LEFT_EXT 0x8CA1
#define GL_NEGATIVE_ONE_TO_ONE_EXT 0x935E
#define GL_ZERO_TO_ONE_EXT 0x935F

/* The refinement's mask is a depth test against the particles' window depth, which the host's
 * clip control and depth range place: a reversed-Z host (GL_ZERO_TO_ONE, range [0, 1]) put it
 * on the old mark's 0 and nothing was refined. Under each host set-up the frame must be the
 * default one's, byte for byte, with the same pixels marked (the frame itself unchanged: the
 * clip control is GL state here, not frame.clip_depth_mode). */
CHECK_TEST(the_refinement_ignores_the_hosts_clip_control_and_depth_range)
{
    gl_fixture f;
    if (!open_over(&f, (depth_layout){INFINITY, BAR_DISTANCE}))
        CHECK_SKIP("mixed resolution needs a colour-renderable RGBA16F target");
    void (*clip_control)(GLenum, GLenum) = host_depth_clip_control();
    static frame_result base, other;
    render(&f, 0.6, 4, SBFX_UPSAMPLE_MIXED, SBFX_FORMAT_DEFAULT, &base);
    CHECK(base.refined > 0, "nothing refined under GL's defaults");
    static const struct {
        const char *name;
        bool zero_to_one;
        float near, far;
    } hosts[] = {
        {"reversed-Z: ZERO_TO_ONE, depth range [0, 1]", true, 0.0f, 1.0f},
        {"ZERO_TO_ONE, depth range [1, 0]", true, 1.0f, 0.0f},
        {"NEGATIVE_ONE_TO_ONE, depth range [0, 0]", false, 0.0f, 0.0f},
        {"NEGATIVE_ONE_TO_ONE, depth range [1, 1]", false, 1.0f, 1.0f},
    };
    int checked = 0;
    for (size_t i = 0; i < ARRAY_SIZE(hosts); i++) {
        if (hosts[i].zero_to_one && !clip_control) continue;
        if (hosts[i].zero_to_one) clip_control(GL_LOWER_LEFT_EXT, GL_ZERO_TO_ONE_EXT);
        glDepthRangef(hosts[i].near, hosts[i].far);
        render(&f, 0.6, 4, SBFX_UPSAMPLE_MIXED, SBFX_FORMAT_DEFAULT, &other);
        GLfloat range[2];
        glGetFloatv(GL_DEPTH_RANGE, range);
        CHECK(range[0] == hosts[i].near && range[1] == hosts[i].far, "%s: the depth range came back as [%g, %g]",
              hosts[i].name, range[0], range[1]);
        glDepthRangef(0.0f, 1.0f);
        if (hosts[i].zero_to_one) clip_control(GL_LOWER_LEFT_EXT, GL_NEGATIVE_ONE_TO_ONE_EXT);
        int differ = 0;
        for (size_t b = 0; b < sizeof(base.rgba); b++) differ += base.rgba[b] != other.rgba[b];
        printf("# %s: %d pixels marked (GL's defaults: %d), %d bytes differ\n", hosts[i].name, other.refined,
               base.refined, differ);
        CHECK(other.refined == base.refined && differ == 0, "%s: %d pixels marked (defaults %d), %d bytes differ",
              hosts[i].name, other.refined, base.refined, differ);
        checked++;
    }
    if (!clip_control) printf("# clip control not offered: the ZERO_TO_ONE hosts not checked\n");
    CHECK(checked >= 2);
    fixture_close(&f);
}

/* A rung of the governor's ladder like any other: a budget nothing meets starts on the mixed
 * level (the top) and walks down, off it, to the ladder's last rung. */
CHECK_TEST(the_governor_walks_down_from_a_mixed_rung)
{
    gl_fixture f;
    if (!open_over(&f, (depth_layout){INFINITY, BAR_DISTANCE}))
        CHECK_SKIP("mixed resolution needs a colour-renderable RGBA16F target");
    static const char *const ladder[] = {"exact/4/mx", "exact/4/nd", "exact/8/bl"};
    sbfx *fx = fixture_module(&f, (sbfx_desc){.target_divisor = 4, .upsample = SBFX_UPSAMPLE_MIXED,
                                              .ignore_timeline = true, .frame_budget_ms = 0.001f,
                                              .ladder = ladder, .ladder_count = 3});
    CHECK(sbfx_trigger(fx, "explosion", (const float[3]){0.0f, 0.0f, (float)-CLOUD_DISTANCE}) == SBFX_OK, "%s",
          sbfx_last_error(fx));
    sbfx_counters c;
    sbfx_stats(fx, &c);
    CHECK(strcmp(c.quality, "exact/4/mx") == 0, "the top: %s", c.quality);
    for (int i = 0; i < 40; i++) {
        CHECK(sbfx_update(fx, 1.0 / 30.0) == SBFX_OK);
        clear_output(&f);
        CHECK(sbfx_render(fx, &f.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
        sbfx_report_frame_time(fx, 5.0); /* where the module has no timer of its own */
        glFinish();
    }
    sbfx_stats(fx, &c);
    printf("# budget 0.001 ms from exact/4/mx: level %s after 40 frames, %d changes\n", c.quality, c.quality_changes);
    CHECK(strcmp(c.quality, "exact/8/bl") == 0 && c.quality_changes >= 1, "level %s, %d changes", c.quality,
          c.quality_changes);
    sbfx_destroy(fx);
    fixture_close(&f);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
