/* Post effects against what they must do on small synthetic images: zero motion is the
 * identity, a pan blurs by its velocity, the focus plane stays sharp while the far field
 * blurs by the expected radius, shimmer of zero strength is the identity and follows the detail
 * strength, history blur does
 * not depend on the frame rate, and nothing turns NaN at edges or at the depth clear value. */
#include "gl_fixture.h"
#include "module.h"

#define W 128
#define H 64

#define HEAT_MEDIA(strength)                                                                  \
    "media = { heat = { density = 2.0; strength = " strength "; }; };\n"                       \
    "effects = { haze = { steps = ( { type = \"emitter\"; medium = \"heat\"; count = 20;"        \
    " spawn_radius = 1.0; speed = [0.0, 0.1]; lifetime = [10.0, 10.0]; radius = [1.5, 1.5]; } ); }; };\n"
#define SMOKE_MEDIA                                                                            \
    "media = { smoke = { density = 0.4; }; };\n"                                               \
    "effects = { puff = { steps = ( { type = \"emitter\"; medium = \"smoke\"; count = 1; } ); }; };\n"

typedef struct post_fixture {
    gl_fixture gl;
    GLuint color_texture, out_float, out_float_fbo;
    uint8_t color[W * H * 4];
} post_fixture;

static sbfx *post_module(post_fixture *p, const char *text)
{
    char err[512];
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_parse(text, "post.cfg", &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (!scene) exit(1);
    sbfx *fx = fixture_module(&p->gl, (sbfx_desc){.scene = scene, .target_divisor = 1, .ignore_timeline = true});
    sbfx_scene_free(scene);
    return fx;
}

static void upload_color(post_fixture *p)
{
    glBindTexture(GL_TEXTURE_2D, p->color_texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, W, H, 0, GL_RGBA, GL_UNSIGNED_BYTE, p->color);
}

static double depth_plane_10(int x, int y, void *u) { (void)x, (void)y, (void)u; return 10.0; }

static void post_open(post_fixture *p)
{
    memset(p, 0, sizeof(*p));
    fixture_open(&p->gl, W, H);
    fixture_projection(&p->gl, 0.8f, 0.1f, 200.0f);
    fixture_depth(&p->gl, depth_plane_10, NULL);
    glGenTextures(1, &p->color_texture);
    glBindTexture(GL_TEXTURE_2D, p->color_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    p->gl.frame.scene_color_texture = p->color_texture;
    /* a float output too, so a NaN would show */
    glGenTextures(1, &p->out_float);
    glBindTexture(GL_TEXTURE_2D, p->out_float);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, W, H, 0, GL_RGBA, GL_HALF_FLOAT, NULL);
    glGenFramebuffers(1, &p->out_float_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, p->out_float_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, p->out_float, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

static void read_out(post_fixture *p, uint8_t *rgba)
{
    glBindFramebuffer(GL_FRAMEBUFFER, p->gl.out_fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

static void vertical_line(post_fixture *p, int column)
{
    memset(p->color, 0, sizeof(p->color));
    for (int y = 0; y < H; y++) {
        uint8_t *px = &p->color[4 * (y * W + column)];
        px[0] = px[1] = px[2] = px[3] = 255;
    }
    upload_color(p);
}

/* How many pixels of row y are lit above `threshold`, and the first and last of them. */
static int lit_span(const uint8_t *rgba, int y, int threshold, int *first, int *last)
{
    int n = 0;
    *first = -1, *last = -1;
    for (int x = 0; x < W; x++)
        if (rgba[4 * (y * W + x)] > threshold) {
            if (*first < 0) *first = x;
            *last = x;
            n++;
        }
    return n;
}

CHECK_TEST(zero_motion_is_identity)
{
    post_fixture p;
    post_open(&p);
    for (int i = 0; i < W * H * 4; i++) p.color[i] = (uint8_t)(i * 37 % 251);
    upload_color(&p);
    sbfx *fx = post_module(&p, SMOKE_MEDIA "post = { motion_blur = { mode = \"velocity\"; shutter = 1.0; }; };\n");
    uint8_t out[W * H * 4];
    for (int frame = 0; frame < 3; frame++) {
        CHECK(sbfx_update(fx, 1.0 / 30) == SBFX_OK);
        CHECK(sbfx_render(fx, &p.gl.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    }
    read_out(&p, out);
    int differ = 0;
    for (int i = 0; i < W * H * 4; i++) differ += (i % 4 != 3) && out[i] != p.color[i];
    CHECK(differ == 0, "%d channels changed without motion", differ);
    sbfx_destroy(fx);
}

/* The camera pans sideways so the depth-10 plane moves 12 px per frame; with the shutter open
 * the whole frame a one-pixel line smears over 12 px (the tile, 8, bounds the half-extent). */
CHECK_TEST(horizontal_pan_blurs_by_the_velocity)
{
    post_fixture p;
    post_open(&p);
    vertical_line(&p, W / 2);
    sbfx *fx = post_module(&p, SMOKE_MEDIA "post = { motion_blur = { mode = \"velocity\"; shutter = 1.0; tile = 8; samples = 31; }; };\n");
    const double shift_px = 12.0;
    /* NDC per pixel = 2/W; at depth 10 one NDC unit is 10/P0 metres */
    double metres = shift_px * 2.0 / W * 10.0 / p.gl.frame.projection[0];
    CHECK(sbfx_render(fx, &p.gl.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    p.gl.frame.view[12] = (float)-metres; /* camera moves +x: the scene moves left on screen */
    CHECK(sbfx_render(fx, &p.gl.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    uint8_t out[W * H * 4];
    read_out(&p, out);
    if (getenv("SBFX_TEST_VERBOSE")) {
        float v[4 * W * H];
        glBindFramebuffer(GL_FRAMEBUFFER, fx->render->post.velocity.framebuffer);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, v);
        printf("# velocity at centre %g %g\n", v[4 * (H / 2 * W + W / 2)], v[4 * (H / 2 * W + W / 2) + 1]);
        glBindFramebuffer(GL_FRAMEBUFFER, fx->render->post.neighbors.framebuffer);
        glReadPixels(0, 0, 1, 1, GL_RGBA, GL_FLOAT, v);
        printf("# neighbour max %g %g\n", v[0], v[1]);
    }
    int first, last, n = lit_span(out, H / 2, 2, &first, &last);
    printf("# line smeared over %d px (x %d..%d), velocity %.1f px per frame\n", n, first, last, shift_px);
    CHECK(fabs((last - first + 1) - shift_px) <= 2.0, "blur length %d, want %.0f +- 2", last - first + 1, shift_px);
    CHECK(first <= W / 2 && last >= W / 2, "the blur must cover the line's position");
    sbfx_destroy(fx);
}

static double focus_left_far_right(int x, int y, void *u)
{
    (void)y, (void)u;
    return x < W / 2 ? 5.0 : 150.0;
}

CHECK_TEST(focus_plane_sharp_far_field_blurred_by_its_radius)
{
    post_fixture p;
    post_open(&p);
    fixture_depth(&p.gl, focus_left_far_right, NULL);
    memset(p.color, 0, sizeof(p.color));
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            uint8_t v = (x == W / 4 || x == 3 * W / 4) ? 255 : 0; /* a line in each field */
            uint8_t *px = &p.color[4 * (y * W + x)];
            px[0] = px[1] = px[2] = v, px[3] = 255;
        }
    upload_color(&p);
    sbfx *fx = post_module(&p, SMOKE_MEDIA "post = { depth_of_field = { near = [0.5, 2.0]; far = [20.0, 100.0];"
                               " max_radius = 6.0; scale = 1; }; };\n");
    CHECK(sbfx_render(fx, &p.gl.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    uint8_t out[W * H * 4];
    read_out(&p, out);
    int sharp_first, sharp_last, blur_first, blur_last;
    int y = H / 2;
    lit_span(out, y, 0, &sharp_first, &sharp_last);
    int sharp = 0;
    for (int x = 0; x < W / 2 - 8; x++) sharp += out[4 * (y * W + x)] != p.color[4 * (y * W + x)];
    int n = 0;
    blur_first = blur_last = -1;
    for (int x = W / 2 + 8; x < W; x++)
        if (out[4 * (y * W + x)] > 0) {
            if (blur_first < 0) blur_first = x;
            blur_last = x, n++;
        }
    int radius = (blur_last - blur_first) / 2;
    printf("# in-focus field: %d pixels changed; far line spread to x %d..%d (radius %d, want 6)\n", sharp,
           blur_first, blur_last, radius);
    CHECK(sharp == 0, "%d in-focus pixels changed", sharp);
    CHECK(abs(radius - 6) <= 1, "far blur radius %d, want 6 +- 1", radius);
    sbfx_destroy(fx);
}

/* A detailed smoke cloud 6 m away over a flat sky (no surface: the depth's clear value), through
 * depth of field with the far range `far` at the post scene's blur scale 2, into out; without
 * `far`, no post effect: the particles composited over the sky's colour in the output. */
static double sky(int x, int y, void *u) { (void)x, (void)y, (void)u; return INFINITY; }

static void render_cloud(post_fixture *p, const char *far, uint8_t *out)
{
    char text[1536], post[256] = "";
    if (far)
        snprintf(post, sizeof(post), "post = { depth_of_field = { near = [0.5, 1.0]; far = %s; max_radius = 6.0;"
                 " scale = 2; }; };\n", far);
    snprintf(text, sizeof(text),
             "media = { smoke = { density = 0.6; detail = { source = \"procedural\"; strength = 0.8; window = 0.8; }; }; };\n"
             "effects = { cloud = { steps = ( { type = \"emitter\"; medium = \"smoke\"; count = 8; spawn_radius = 0.6;"
             " speed = [0.0, 0.05]; lifetime = [10.0, 10.0]; radius = [1.0, 1.4]; } ); }; };\n%s", post);
    glBindFramebuffer(GL_FRAMEBUFFER, p->gl.out_fbo);
    glClearColor(p->color[0] / 255.0f, p->color[1] / 255.0f, p->color[2] / 255.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    sbfx *fx = post_module(p, text);
    const float at[3] = {0, 0, -6};
    CHECK(sbfx_trigger(fx, "cloud", at) == SBFX_OK, "%s", sbfx_last_error(fx));
    CHECK(sbfx_update(fx, 0.1) == SBFX_OK);
    CHECK(sbfx_render(fx, &p->gl.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    read_out(p, out);
    sbfx_destroy(fx);
}

/* Over the pixels the cloud covers (more than 4 levels from the sky): the largest and the mean
 * difference between two renders, in levels. */
static int cloud_difference(const post_fixture *p, const uint8_t *a, const uint8_t *b, double *mean, int *covered)
{
    int worst = 0, n = 0;
    double sum = 0;
    for (int i = 0; i < W * H; i++) {
        bool cloud = false;
        for (int c = 0; c < 3; c++) cloud = cloud || abs(b[4 * i + c] - p->color[4 * i + c]) > 4;
        if (!cloud) continue;
        n++;
        for (int c = 0; c < 3; c++) {
            int d = abs(a[4 * i + c] - b[4 * i + c]);
            worst = d > worst ? d : worst;
            sum += d / 3.0;
        }
    }
    *mean = n ? sum / n : 0;
    *covered = n;
    return worst;
}

/* Particles in focus over a far sky stay the full-resolution picture: the CoC where they cover
 * the sky is theirs (by their coverage), at full resolution, so the blurred half-resolution
 * field does not replace them (it did: the composite took the sky's CoC, 1, and the cloud's
 * detail went through the blur scale's box and a bilinear upsample). The same cloud in the far
 * field is blurred. The reference: the cloud without post effects over the sky's colour. */
CHECK_TEST(particles_in_focus_stay_sharp_over_a_far_sky)
{
    post_fixture p;
    post_open(&p);
    fixture_depth(&p.gl, sky, NULL);
    for (int i = 0; i < W * H; i++) {
        uint8_t *px = &p.color[4 * i];
        px[0] = 110, px[1] = 150, px[2] = 205, px[3] = 255;
    }
    upload_color(&p);
    static uint8_t focused[W * H * 4], all_sharp[W * H * 4], far_cloud[W * H * 4];
    render_cloud(&p, "[20.0, 100.0]", focused);   /* the cloud in focus, the sky far */
    render_cloud(&p, "[2.0, 4.0]", far_cloud);    /* the cloud far too */
    render_cloud(&p, NULL, all_sharp);
    double mean, far_mean;
    int covered, far_covered;
    int worst = cloud_difference(&p, focused, all_sharp, &mean, &covered);
    int far_worst = cloud_difference(&p, far_cloud, all_sharp, &far_mean, &far_covered);
    printf("# in focus: %d cloud pixels, differ from no depth of field by at most %d levels (mean %.2f); "
           "in the far field: %d pixels, at most %d (mean %.2f)\n",
           covered, worst, mean, far_covered, far_worst, far_mean);
    CHECK(covered > 400, "the cloud covers only %d pixels", covered);
    CHECK(worst <= 3 && mean <= 0.5, "the in-focus cloud changed by up to %d levels (mean %.2f)", worst, mean);
    CHECK(far_covered > 20 && far_mean > 2.0, "the far cloud is not blurred (mean change %.2f)", far_mean);
}

static int run_heat(post_fixture *p, const char *strength, uint8_t *out)
{
    char text[1024];
    snprintf(text, sizeof(text), HEAT_MEDIA("%s"), strength);
    sbfx *fx = post_module(p, text);
    const float at[3] = {0, 0, -10};
    CHECK(sbfx_trigger(fx, "haze", at) == SBFX_OK, "%s", sbfx_last_error(fx));
    CHECK(sbfx_update(fx, 0.1) == SBFX_OK);
    CHECK(sbfx_render(fx, &p->gl.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    sbfx_counters c;
    sbfx_stats(fx, &c);
    read_out(p, out);
    sbfx_destroy(fx);
    return c.passes;
}

CHECK_TEST(shimmer_of_zero_strength_is_identity)
{
    post_fixture p;
    post_open(&p);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            uint8_t *px = &p.color[4 * (y * W + x)];
            px[0] = (uint8_t)((x / 4 + y / 4) % 2 ? 230 : 20), px[1] = (uint8_t)(x * 2), px[2] = (uint8_t)(y * 4), px[3] = 255;
        }
    upload_color(&p);
    uint8_t still[W * H * 4], moved[W * H * 4];
    int passes = run_heat(&p, "0.0", still);
    run_heat(&p, "0.03", moved);
    int changed_still = 0, changed_moved = 0;
    for (int i = 0; i < W * H * 4; i++) {
        if (i % 4 == 3) continue;
        changed_still += still[i] != p.color[i];
        changed_moved += moved[i] != p.color[i];
    }
    printf("# shimmer: strength 0 changed %d channels, strength 0.03 changed %d (passes %d)\n", changed_still,
           changed_moved, passes);
    CHECK(passes >= 3, "heat particles were not drawn");
    CHECK(changed_still == 0, "zero shimmer changed %d channels", changed_still);
    CHECK(changed_moved > 100, "shimmer did not move the image (%d)", changed_moved);
}

/* With a detail volume the shimmer is the volume's turbulence scaled by the heat medium's
 * detail strength (docs/look.md): half the strength moves the picture about half as far, and
 * the strength set to 0 after load (the detail switched off, programs kept) moves nothing. */
#define HEAT_DETAIL_MEDIA(detail)                                                              \
    "media = { heat = { density = 2.0; strength = 0.03; detail = { source = \"procedural\"; strength = " detail \
    "; window = 0.3; }; }; };\n"                                                                \
    "effects = { haze = { steps = ( { type = \"emitter\"; medium = \"heat\"; count = 20;"        \
    " spawn_radius = 1.0; speed = [0.0, 0.1]; lifetime = [10.0, 10.0]; radius = [1.5, 1.5]; } ); }; };\n"

static double heat_detail_shift(post_fixture *p, const char *detail, bool switched_off)
{
    char text[1024];
    snprintf(text, sizeof(text), HEAT_DETAIL_MEDIA("%s"), detail);
    sbfx *fx = post_module(p, text);
    if (switched_off) sbfx_media(fx)[SBFX_HEAT].detail_strength = 0.0f;
    const float at[3] = {0, 0, -10};
    CHECK(sbfx_trigger(fx, "haze", at) == SBFX_OK, "%s", sbfx_last_error(fx));
    CHECK(sbfx_update(fx, 0.1) == SBFX_OK);
    CHECK(sbfx_render(fx, &p->gl.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    static uint8_t out[W * H * 4];
    read_out(p, out);
    sbfx_destroy(fx);
    double sum = 0.0;
    for (int i = 0; i < W * H * 4; i++)
        if (i % 4 != 3) sum += abs((int)out[i] - (int)p->color[i]);
    return sum / (W * H * 3);
}

CHECK_TEST(shimmer_follows_the_detail_strength)
{
    post_fixture p;
    post_open(&p);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) { /* smooth ramps: a shift changes a pixel in proportion */
            uint8_t *px = &p.color[4 * (y * W + x)];
            px[0] = (uint8_t)(x * 2), px[1] = (uint8_t)(y * 4), px[2] = (uint8_t)(255 - x), px[3] = 255;
        }
    upload_color(&p);
    double full = heat_detail_shift(&p, "1.0", false), half = heat_detail_shift(&p, "0.5", false);
    double off = heat_detail_shift(&p, "1.0", true);
    printf("# shimmer with the detail volume: mean change %.3f levels at detail strength 1, %.3f at 0.5, %.3f "
           "switched off\n", full, half, off);
    CHECK(full > 0.1, "the shimmer did not move the picture (%.3f levels)", full);
    CHECK(half > 0.3 * full && half < 0.7 * full, "half the detail strength moved it %.3f of the full", half / full);
    CHECK(off == 0.0, "with the detail switched off the shimmer still moved it (%.3f levels)", off);
}

/* The history blend fades by time, not by frames: after the same 0.2 s, 60 fps and 15 fps
 * leave the same amount of the old image. */
static double history_after(post_fixture *p, double fps, double *elapsed)
{
    sbfx *fx = post_module(p, SMOKE_MEDIA "post = { motion_blur = { mode = \"history\"; persistence = 0.1; }; };\n");
    memset(p->color, 255, sizeof(p->color));
    upload_color(p);
    CHECK(sbfx_render(fx, &p->gl.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    memset(p->color, 0, sizeof(p->color));
    upload_color(p);
    for (int i = 0; i < (int)(0.2 * fps + 0.5); i++) {
        sbfx_update(fx, 1.0 / fps);
        CHECK(sbfx_render(fx, &p->gl.frame) == SBFX_OK);
    }
    uint8_t out[W * H * 4];
    read_out(p, out);
    *elapsed = sbfx_time(fx);
    sbfx_destroy(fx);
    return out[4 * (H / 2 * W + W / 2)] / 255.0;
}

CHECK_TEST(history_blur_is_frame_rate_independent)
{
    post_fixture p;
    post_open(&p);
    double t_fast, t_slow;
    double fast = history_after(&p, 60.0, &t_fast), slow = history_after(&p, 15.0, &t_slow);
    double want = exp(-t_fast / 0.1);
    printf("# old image left: %.3f after %.4f s at 60 fps, %.3f after %.4f s at 15 fps (exp(-t/0.1) = %.3f)\n",
           fast, t_fast, slow, t_slow, want);
    CHECK(fabs(t_fast - t_slow) < 1e-6, "the runs simulated different times");
    CHECK(fabs(fast - slow) <= 2.0 / 255, "%.3f vs %.3f", fast, slow);
    CHECK(fabs(fast - want) <= 1.5 / 255, "%.3f, want %.3f", fast, want);
}

/* Every post effect at once, depth at its clear value on half the screen, particles at the
 * screen edge: the float output has no NaN or Inf. */
static double half_cleared(int x, int y, void *u) { (void)y, (void)u; return x < W / 2 ? 4.0 : INFINITY; }

CHECK_TEST(no_nan_at_screen_edges_or_clear_depth)
{
    post_fixture p;
    post_open(&p);
    fixture_depth(&p.gl, half_cleared, NULL);
    memset(p.color, 128, sizeof(p.color));
    upload_color(&p);
    char text[2048];
    snprintf(text, sizeof(text),
             "media = { heat = { strength = 0.05; }; smoke = { density = 0.4; }; };\n"
             "effects = { e = { steps = ( { type = \"emitter\"; medium = \"heat\"; count = 8; spawn_radius = 6.0;"
             " speed = [1.0, 3.0]; lifetime = [5.0, 5.0]; radius = [2.0, 2.0]; },"
             " { type = \"emitter\"; medium = \"smoke\"; count = 8; spawn_radius = 6.0; speed = [1.0, 3.0];"
             " lifetime = [5.0, 5.0]; radius = [1.0, 1.0]; } ); }; };\n"
             "post = { motion_blur = { mode = \"velocity\"; }; depth_of_field = { near = [1.0, 3.0];"
             " far = [5.0, 20.0]; }; };\n");
    sbfx *fx = post_module(&p, text);
    const float at[3] = {4, 0, -6};
    CHECK(sbfx_trigger(fx, "e", at) == SBFX_OK);
    p.gl.frame.out_framebuffer = p.out_float_fbo;
    float *out = malloc(sizeof(float) * 4 * W * H);
    bool finite = true;
    for (int i = 0; i < 10; i++) {
        sbfx_update(fx, 1.0 / 30);
        p.gl.frame.view[12] = 0.3f * i; /* a moving camera */
        CHECK(sbfx_render(fx, &p.gl.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
        glBindFramebuffer(GL_FRAMEBUFFER, p.out_float_fbo);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, out);
        finite = finite && all_finite(out, 4u * W * H);
    }
    CHECK(finite, "NaN or Inf in the output");
    free(out);
    sbfx_destroy(fx);
}

/* The velocity blur's blocks (tile_class.frag) of a class (1 the gather, 0.5 its fast path, 0
 * still), read back. */
static int blocks_of(sbfx *fx, float class, int *total)
{
    const sbfx_rt *c = &fx->render->post.classes;
    float v[4 * 16 * 16];
    CHECK(c->width * c->height <= 16 * 16, "%dx%d blocks", c->width, c->height);
    glBindFramebuffer(GL_FRAMEBUFFER, c->framebuffer);
    glReadPixels(0, 0, c->width, c->height, GL_RGBA, GL_FLOAT, v);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    int n = 0;
    for (int i = 0; i < c->width * c->height; i++) n += v[4 * i] == class;
    *total = c->width * c->height;
    return n;
}

/* A still camera: every block is still, drawn by the copy, and the picture is the input. */
CHECK_TEST(a_still_camera_copies_every_block)
{
    post_fixture p;
    post_open(&p);
    for (int i = 0; i < W * H * 4; i++) p.color[i] = (uint8_t)(i * 37 % 251);
    upload_color(&p);
    sbfx *fx = post_module(&p, SMOKE_MEDIA "post = { motion_blur = { mode = \"velocity\"; shutter = 1.0; }; };\n");
    for (int frame = 0; frame < 2; frame++)
        CHECK(sbfx_render(fx, &p.gl.frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    int total, moving = blocks_of(fx, 1.0f, &total) + blocks_of(fx, 0.5f, &total);
    uint8_t out[W * H * 4];
    read_out(&p, out);
    int differ = 0;
    for (int i = 0; i < W * H * 4; i++) differ += (i % 4 != 3) && out[i] != p.color[i];
    printf("# still camera: %d of %d blocks moving, %d channels changed\n", moving, total, differ);
    CHECK(total == 4 * 2 && moving == 0, "%d of %d blocks moving, want 0 of 8", moving, total);
    CHECK(differ == 0, "%d channels changed without motion", differ);
    sbfx_destroy(fx);
}

/* A sideways pan over a near wall (left half, 4 m) and the sky (right half): the wall moves 12 px,
 * the sky not at all. The gather runs over the wall's blocks and the block its tiles' neighbours
 * reach (three columns of 32 px), the copy over the last column: byte for byte the gather's over
 * every block (the tiles' full_screen) there. The first column's neighbourhoods all move as one
 * (the wall's 6 px of blur): its blocks take the fast path, which for one velocity at one depth
 * is the full gather's weights (within a level: the order of the arithmetic). */
static double wall_and_sky(int x, int y, void *u) { (void)y, (void)u; return x < W / 2 ? 4.0 : INFINITY; }

CHECK_TEST(only_moving_blocks_get_the_gather)
{
    post_fixture p;
    post_open(&p);
    fixture_depth(&p.gl, wall_and_sky, NULL);
    for (int i = 0; i < W * H * 4; i++) p.color[i] = (uint8_t)(i * 37 % 251);
    upload_color(&p);
    const char *text = SMOKE_MEDIA "post = { motion_blur = { mode = \"velocity\"; shutter = 1.0; tile = 8; }; };\n";
    sbfx *fx = post_module(&p, text), *control = post_module(&p, text);
    control->render->tiles.full_screen = true;
    double metres = 12.0 * 2.0 / W * 4.0 / p.gl.frame.projection[0];
    uint8_t out[W * H * 4], want[W * H * 4];
    sbfx *both[2] = {fx, control};
    uint8_t *images[2] = {out, want};
    int total = 0, full = 0, fast = 0, all_total = 0, all_moving = 0;
    for (int k = 0; k < 2; k++) {
        p.gl.frame.view[12] = 0.0f;
        CHECK(sbfx_render(both[k], &p.gl.frame) == SBFX_OK, "%s", sbfx_last_error(both[k]));
        p.gl.frame.view[12] = (float)-metres;
        CHECK(sbfx_render(both[k], &p.gl.frame) == SBFX_OK, "%s", sbfx_last_error(both[k]));
        read_out(&p, images[k]);
    }
    full = blocks_of(fx, 1.0f, &total);
    fast = blocks_of(fx, 0.5f, &total);
    all_moving = blocks_of(control, 1.0f, &all_total);
    int differ = 0, copied = 0, changed = 0, fast_worst = 0;
    for (int i = 0; i < W * H * 4; i++) {
        bool fast_column = (i / 4) % W < 32;
        if (fast_column) fast_worst = abs(out[i] - want[i]) > fast_worst ? abs(out[i] - want[i]) : fast_worst;
        else differ += out[i] != want[i];
        if (i % 4 == 3) continue;
        if ((i / 4) % W >= 96) copied += out[i] != p.color[i];
        else changed += out[i] != p.color[i];
    }
    printf("# pan over a wall and the sky: of %d blocks %d the gather's, %d its fast path's (control: %d the "
           "gather's); %d channels differ from the gather everywhere outside the fast column, at most %d levels "
           "in it; %d changed in the moving blocks, %d in the still column\n",
           total, full, fast, all_moving, differ, fast_worst, changed, copied);
    CHECK(full == 2 * 2 && fast == 2, "%d full and %d fast blocks of %d, want 4 and 2 (columns 2-3, 1)", full, fast, total);
    CHECK(fast_worst <= 1, "the fast path differs from the gather by %d levels", fast_worst);
    CHECK(all_moving == all_total, "the control drew the copy over %d blocks", all_total - all_moving);
    CHECK(changed > 1000, "the wall was not blurred (%d channels changed)", changed);
    CHECK(copied == 0, "the still column changed (%d channels)", copied);
    CHECK(differ == 0, "%d channels differ from the gather over every block", differ);
    sbfx_destroy(fx);
    sbfx_destroy(control);
}

/* Each post effect exists in the plan only when asked for. */
CHECK_TEST(post_effects_only_when_asked)
{
    post_fixture p;
    post_open(&p);
    struct { const char *post; int programs; } cases[] = {
        {"", 3},
        {"post = { motion_blur = { mode = \"history\"; }; };\n", 3 + 2},
        {"post = { motion_blur = { mode = \"velocity\"; }; };\n", 3 + 8}, /* + the blocks' classes, fast path, copy */
        {"post = { depth_of_field = { near = [1.0, 2.0]; far = [10.0, 20.0]; }; };\n", 3 + 6}, /* + the setup and composite outside the tiles */
    };
    for (size_t i = 0; i < ARRAY_SIZE(cases); i++) {
        char text[1024];
        snprintf(text, sizeof(text), SMOKE_MEDIA "%s", cases[i].post);
        sbfx *fx = post_module(&p, text);
        sbfx_counters c;
        sbfx_stats(fx, &c);
        /* + the low-res corners (passes.c); with post effects the scene outside the tiles (composite.frag
         * SCENE_ONLY) */
        int want = cases[i].programs + sbfx_float32_renderable() + (i > 0);
        CHECK(c.programs == want, "case %zu: %d programs, want %d", i, c.programs, want);
        CHECK(sbfx_render(fx, &p.gl.frame) == SBFX_OK);
        sbfx_stats(fx, &c);
        /* idle: without post effects nothing at all; with them only the post chain */
        if (i == 0) CHECK(c.passes == 0 && c.framebuffers == 0, "idle without post: %d passes", c.passes);
        else CHECK(c.passes > 0 && c.framebuffers > 0, "case %zu: no post pass", i);
        sbfx_destroy(fx);
    }
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
