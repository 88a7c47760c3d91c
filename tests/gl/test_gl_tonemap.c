/* The particles' light on the display (sbfx_tone_map): the composite's output against the CPU
 * tone map (ref/reference_frame.c) applied to the particle target the GPU made; `none` is the
 * old composite; the hue-preserving default keeps each pixel's chromaticity and, where it may
 * read the host's scene colour, leaves room for it so that no channel clips; a scene colour
 * texture that is the framebuffer being drawn is not read (a feedback loop); exposure scales. */
#include "gl_fixture.h"
#include "reference_frame.h"

#define SIZE 48

static const float background[3] = {0.35f, 0.5f, 0.7f}; /* a sky: bright blue */
static const float black[3] = {0, 0, 0};

/* What the frame says about the host's scene colour. */
typedef enum scene_colour { SCENE_NOT_GIVEN, SCENE_GIVEN, SCENE_DRAWN_INTO } scene_colour;

typedef struct tone_case {
    sbfx_tone_map op;
    float exposure;
    const float *back;
    scene_colour scene;
    const char *name;
} tone_case;

static void clear_out(gl_fixture *f, const float rgb[3])
{
    glBindFramebuffer(GL_FRAMEBUFFER, f->out_fbo);
    glClearColor(rgb[0], rgb[1], rgb[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

/* An RGBA8 scene colour texture of the background, as a host's scene pass leaves it. */
static GLuint scene_texture(const float rgb[3])
{
    static uint8_t texels[SIZE * SIZE * 4];
    for (int i = 0; i < SIZE * SIZE; i++)
        for (int k = 0; k < 4; k++) texels[4 * i + k] = (uint8_t)lrintf((k < 3 ? rgb[k] : 1.0f) * 255.0f);
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, SIZE, SIZE, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

/* Hot fire in front of dust lit by a strong light: light far above 1 in most covered pixels. */
static void render(gl_fixture *f, const tone_case *c, float **target, uint8_t *out)
{
    sbfx *fx = fixture_module(f, (sbfx_desc){.target_divisor = 1, .target_format = SBFX_FORMAT_RGBA32F,
                                             .ignore_timeline = true, .tone_map = c->op, .exposure = c->exposure});
    const float dir[3] = {0, -0.3f, -1}, color[3] = {6, 5, 4}, ambient[3] = {0.3f, 0.3f, 0.3f};
    sbfx_set_light(fx, dir, color, ambient);
    sbfx_view_particle p[3] = {
        {.center = {0.4f, 0.1f, -5}, .radius = 1.3f, .detail = {0.6f, 0.1f, 0.5f}, .intensity = 1, .medium = SBFX_DUST},
        {.center = {-0.5f, 0, -4}, .radius = 1.0f, .detail = {0.2f, 0.4f, 0.1f}, .intensity = 1, .medium = SBFX_FIRE},
        {.center = {-0.9f, -0.6f, -3.5f}, .radius = 0.5f, .detail = {0.3f, 0.7f, 0.2f}, .intensity = 0.3f,
         .medium = SBFX_FIRE}};
    clear_out(f, c->back);
    sbfx_frame frame = f->frame;
    GLuint scene = c->scene == SCENE_GIVEN ? scene_texture(c->back) : 0;
    frame.scene_color_texture = c->scene == SCENE_DRAWN_INTO ? f->out_texture : scene;
    CHECK(sbfx_render_view_particles(fx, &frame, p, 3) == SBFX_OK, "%s", sbfx_last_error(fx));
    CHECK(glGetError() == GL_NO_ERROR);
    int w, h;
    *target = fixture_read_target(fx, &w, &h);
    glBindFramebuffer(GL_FRAMEBUFFER, f->out_fbo);
    glReadPixels(0, 0, SIZE, SIZE, GL_RGBA, GL_UNSIGNED_BYTE, out);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (scene) glDeleteTextures(1, &scene);
    sbfx_destroy(fx);
}

typedef struct outcome {
    int covered, clipped;     /* pixels the particles touch; of them, a channel at 255 */
    double worst_level;       /* |GPU - CPU tone map| in 8-bit levels */
    double worst_ratio;       /* largest change of a channel ratio (g/r, b/r) over a black picture */
} outcome;

static outcome compare(const tone_case *c, const float *target, const uint8_t *out)
{
    outcome o = {0};
    sbfx_tone_map op = c->op ? c->op : SBFX_TONE_MAP_FILMIC; /* zero in the desc: the defaults */
    double back[3];
    for (int k = 0; k < 3; k++) back[k] = lrint(c->back[k] * 255.0) / 255.0; /* what the picture holds */
    for (int i = 0; i < SIZE * SIZE; i++) {
        const float *px = &target[4 * i];
        double light[3] = {px[0], px[1], px[2]}, mapped[3];
        if (px[3] > 1.0f - 1.0f / 255.0f) continue;
        o.covered++;
        sbfx_rf_tone_map(op, light, px[3], c->scene == SCENE_GIVEN ? back : NULL, mapped);
        bool clipped = false;
        for (int k = 0; k < 3; k++) {
            double want = fmin(fmax(back[k] * px[3] + mapped[k], 0.0), 1.0) * 255.0;
            o.worst_level = fmax(o.worst_level, fabs(out[4 * i + k] - want));
            clipped = clipped || out[4 * i + k] == 255;
        }
        o.clipped += clipped;
        if (c->back[0] == 0.0f && light[0] > 0.05 && out[4 * i] > 60) /* 8-bit rounding: 0.5 / 60 */
            for (int k = 1; k < 3; k++)
                o.worst_ratio = fmax(o.worst_ratio, fabs((double)out[4 * i + k] / out[4 * i] - light[k] / light[0]));
    }
    return o;
}

static outcome run(gl_fixture *f, tone_case c)
{
    static const char *const scene_names[] = {"not given", "given", "drawn into"};
    float *target;
    uint8_t out[SIZE * SIZE * 4];
    render(f, &c, &target, out);
    outcome o = compare(&c, target, out);
    printf("# %-15s exposure %.2f over %.2f %.2f %.2f, scene colour %s: %d of %d covered pixels clipped, "
           "GPU vs CPU %.1f levels, channel ratios moved %.3f\n", c.name, c.exposure, c.back[0], c.back[1], c.back[2],
           scene_names[c.scene], o.clipped, o.covered, o.worst_level, o.worst_ratio);
    free(target);
    CHECK(o.covered > SIZE * SIZE / 8, "%s: the particles cover %d pixels", c.name, o.covered);
    /* 1 level of rounding, 1 of float vs double near a rounding edge */
    CHECK(o.worst_level <= 2.0, "%s: GPU %.1f levels off the CPU tone map", c.name, o.worst_level);
    return o;
}

CHECK_TEST(none_is_the_plain_composite)
{
    gl_fixture f;
    fixture_open_far(&f, SIZE, SIZE);
    outcome o = run(&f, (tone_case){SBFX_TONE_MAP_NONE, 1.0f, background, SCENE_GIVEN, "none"});
    CHECK(o.clipped > o.covered / 10, "the case must clip without tone mapping: %d of %d", o.clipped, o.covered);
    fixture_close(&f);
}

CHECK_TEST(hue_preserving_clips_nothing_over_a_known_scene)
{
    gl_fixture f;
    fixture_open_far(&f, SIZE, SIZE);
    outcome o = run(&f, (tone_case){SBFX_TONE_MAP_DEFAULT, 0.0f, background, SCENE_GIVEN, "default (filmic)"});
    CHECK(o.clipped == 0, "%d of %d pixels clipped", o.clipped, o.covered);
    o = run(&f, (tone_case){SBFX_TONE_MAP_HUE_PRESERVING, 1.0f, background, SCENE_GIVEN, "hue-preserving"});
    CHECK(o.clipped == 0, "%d of %d pixels clipped", o.clipped, o.covered);
    o = run(&f, (tone_case){SBFX_TONE_MAP_PER_CHANNEL, 1.0f, background, SCENE_GIVEN, "per-channel"});
    CHECK(o.clipped == 0, "%d of %d pixels clipped", o.clipped, o.covered);
    o = run(&f, (tone_case){SBFX_TONE_MAP_FILMIC, 1.0f, background, SCENE_GIVEN, "filmic"});
    CHECK(o.clipped == 0, "%d of %d pixels clipped", o.clipped, o.covered);
    /* unknown picture: the light alone is kept below 1, the sky behind it may still clip */
    outcome blind = run(&f, (tone_case){SBFX_TONE_MAP_DEFAULT, 1.0f, background, SCENE_NOT_GIVEN, "default (filmic)"});
    CHECK(blind.clipped > 0, "over a bright sky the blind mapping should clip somewhere");
    fixture_close(&f);
}

CHECK_TEST(hue_preserving_keeps_channel_ratios)
{
    gl_fixture f;
    fixture_open_far(&f, SIZE, SIZE);
    outcome o = run(&f, (tone_case){SBFX_TONE_MAP_HUE_PRESERVING, 1.0f, black, SCENE_GIVEN, "hue-preserving"});
    CHECK(o.clipped == 0, "%d of %d pixels clipped over black", o.clipped, o.covered);
    CHECK(o.worst_ratio < 0.02, "a channel ratio moved by %g", o.worst_ratio); /* 8-bit rounding */
    outcome per_channel = run(&f, (tone_case){SBFX_TONE_MAP_PER_CHANNEL, 1.0f, black, SCENE_GIVEN, "per-channel"});
    CHECK(per_channel.worst_ratio > 0.1, "per channel should bend hues: %g", per_channel.worst_ratio);
    fixture_close(&f);
}

/* A host that composites into the framebuffer holding its scene colour texture: sbfx must not
 * sample what it draws; the mapping is the one for an unknown picture. */
CHECK_TEST(scene_colour_being_drawn_is_not_read)
{
    gl_fixture f;
    fixture_open_far(&f, SIZE, SIZE);
    run(&f, (tone_case){SBFX_TONE_MAP_HUE_PRESERVING, 1.0f, background, SCENE_DRAWN_INTO, "hue-preserving"});
    fixture_close(&f);
}

CHECK_TEST(exposure_scales_the_light)
{
    gl_fixture f;
    fixture_open_far(&f, SIZE, SIZE);
    run(&f, (tone_case){SBFX_TONE_MAP_NONE, 0.25f, black, SCENE_NOT_GIVEN, "none"});
    run(&f, (tone_case){SBFX_TONE_MAP_HUE_PRESERVING, 4.0f, background, SCENE_GIVEN, "hue-preserving"});
    /* pre-exposed (docs/look-fire.md): the particle target itself holds the light times the
     * exposure, scattered and emitted alike; its transmittance does not change */
    float *one, *quarter;
    static uint8_t out[SIZE * SIZE * 4];
    render(&f, &(tone_case){SBFX_TONE_MAP_NONE, 1.0f, black, SCENE_NOT_GIVEN, "none"}, &one, out);
    render(&f, &(tone_case){SBFX_TONE_MAP_NONE, 0.25f, black, SCENE_NOT_GIVEN, "none"}, &quarter, out);
    double worst = 0;
    int lit = 0;
    for (int i = 0; i < SIZE * SIZE; i++) {
        CHECK(quarter[4 * i + 3] == one[4 * i + 3], "transmittance changed at %d", i);
        for (int k = 0; k < 3; k++)
            if (one[4 * i + k] > 1e-3f) {
                lit++;
                worst = fmax(worst, fabs(quarter[4 * i + k] / one[4 * i + k] - 0.25));
            }
    }
    printf("# exposure 0.25: target light / light at exposure 1 within %.2g of 0.25 in %d channels\n", worst, lit);
    CHECK(lit > SIZE * SIZE / 4 && worst < 1e-4, "%d lit channels, ratio off by %g", lit, worst);
    free(one), free(quarter);
    fixture_close(&f);
}

/* The curve: identity to the knee, slope 1 there, 1 at the white point, monotone. */
CHECK_TEST(tone_curve_shape)
{
    sbfx_tone_curve c = sbfx_tone_curve_default();
    CHECK(sbfx_tone_curve_apply(&c, 0.3) == 0.3 && sbfx_tone_curve_apply(&c, c.knee) == c.knee);
    double h = 1e-6, slope = (sbfx_tone_curve_apply(&c, c.knee + h) - c.knee) / h;
    CHECK(fabs(slope - 1.0) < 1e-4, "slope above the knee %g", slope);
    CHECK(fabs(sbfx_tone_curve_apply(&c, c.white) - 1.0) < 1e-12);
    CHECK(sbfx_tone_curve_apply(&c, 1e9) == 1.0 && sbfx_tone_curve_apply(&c, NAN) == 0.0);
    double prev = 0;
    for (double v = 0; v < 100; v += 0.01) {
        double y = sbfx_tone_curve_apply(&c, v);
        CHECK(y >= prev, "not monotone at %g", v);
        prev = y;
    }
    printf("# tone curve: knee %.2f, steepness %.4f; 1 -> %.3f, 2 -> %.3f, 10 -> %.3f, 30 -> %.3f\n", c.knee,
           c.steepness, sbfx_tone_curve_apply(&c, 1), sbfx_tone_curve_apply(&c, 2), sbfx_tone_curve_apply(&c, 10),
           sbfx_tone_curve_apply(&c, 30));
}

static void srgb_to_uv(const double rgb[3], double uv[2])
{
    double x = 0.4124 * rgb[0] + 0.3576 * rgb[1] + 0.1805 * rgb[2], y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    double z = 0.0193 * rgb[0] + 0.1192 * rgb[1] + 0.9505 * rgb[2], d = x + 15 * y + 3 * z;
    uv[0] = 4 * x / d, uv[1] = 9 * y / d;
}

/* filmic (docs/look-fire.md): black-body mid-tones (light a display could show as it is: every
 * channel at most 1, luminance from 0.05) keep its chromaticity within 0.005 in u'v' (round 2's Planckian-locus bound), and
 * brighter light goes to white: luminance rising with the light, all channels 1 at the end. */
CHECK_TEST(filmic_keeps_mid_tone_hue_and_goes_to_white)
{
    const sbfx_cmf *cmf = &sbfx_cie1931_2deg;
    sbfx_tone_curve c = sbfx_tone_curve_for(SBFX_TONE_MAP_FILMIC);
    double worst = 0;
    for (double kelvin = 1200; kelvin <= 6500; kelvin += 100) {
        double bb[3], before = -1, in_uv[2];
        sbfx_blackbody_rgb(cmf, kelvin, sbfx_blackbody_norm(cmf, kelvin), bb); /* luminance 1 */
        srgb_to_uv(bb, in_uv);
        for (double scale = 0.01; scale < 1e5; scale *= 1.05) {
            double q[3] = {bb[0] * scale, bb[1] * scale, bb[2] * scale}, x[3], uv[2];
            sbfx_tone_filmic(&c, q, x);
            double y = 0.2126 * x[0] + 0.7152 * x[1] + 0.0722 * x[2];
            CHECK(y >= before - 1e-12, "%g K: luminance falls at scale %g", kelvin, scale);
            before = y;
            if (y < 0.05 || fmax(q[0], fmax(q[1], q[2])) > 1.0) continue; /* mid-tones: displayable as they are */
            srgb_to_uv(x, uv);
            worst = fmax(worst, hypot(uv[0] - in_uv[0], uv[1] - in_uv[1]));
        }
        double q[3] = {bb[0] * 1e6, bb[1] * 1e6, bb[2] * 1e6}, x[3];
        sbfx_tone_filmic(&c, q, x);
        CHECK(x[0] == 1.0 && x[1] == 1.0 && x[2] == 1.0, "%g K far above white: %g %g %g", kelvin, x[0], x[1], x[2]);
    }
    printf("# filmic: mid-tone black-body light (channels <= 1, luminance >= 0.05, 1200 .. 6500 K) moves at most "
           "%.4f in u'v'\n", worst);
    CHECK(worst <= 0.005, "mid-tones moved %.4f in u'v'", worst);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
