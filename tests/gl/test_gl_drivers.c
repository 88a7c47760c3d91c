/* Two Mesa implementations agree (issue #4): the same explosion frames, rendered once by
 * llvmpipe and once by softpipe, give the same images within a stated tolerance.
 *
 * Mesa picks its driver when EGL opens, from GALLIUM_DRIVER: each driver renders in a child
 * process of its own (forked before any EGL call), writes its frames to a file under /tmp, and
 * the test compares the files. Skipped, with the reason, where softpipe is not available.
 *
 * What is rendered: the built-in explosion over the test scene at 320x180 from a fixed camera,
 * at t = 0.3, 0.8 and 1.5 s, in two configurations: the defaults (spherical, 1/4 resolution,
 * RGBA16F, nearest-depth upsampling) and the exact model at full resolution into RGBA32F.
 *
 * Tolerance, measured first (Mesa 22.3.6, llvmpipe with LLVM 15 against softpipe, 6 frames):
 *   mean |diff| 0.014 .. 0.113 levels of 255; pixels with a channel more than 2 levels apart
 *   0.014 .. 0.17 %, more than 4 levels 0 .. 0.08 %; the largest single difference 3 .. 60.
 * Where they come from: both drivers run the same GLSL through different back ends (llvmpipe:
 * 8-wide LLVM code with its own exp/log/pow and texture-filtering arithmetic; softpipe: TGSI
 * interpreted with the C library's math). The detail volume's trilinear filtering differs in
 * its low bits, which shows as thin streaks of 1-3 levels inside the fire (they vanish when
 * the detail is switched off); and at a few depth discontinuities the nearest-depth upsampling
 * picks a different neighbouring texel (a decision that one ulp of depth can flip), which moves
 * a handful of pixels by tens of levels. A real disagreement — a lost pass or particle, a
 * format fallback, a wrong upsample — moves whole regions.
 * Since issue 17 the detail carves (erosion of the density, shading, fire temperature:
 * docs/look.md) with about 100 texels across a particle, which amplifies those low-bit filter
 * differences. Measured again on 2026-11-25 (Mesa 22.3.6, Debian 12's, as in CI; llvmpipe
 * against softpipe, 6 frames, the same numbers on every run): more than 2 levels apart
 * 0.16 .. 0.65 % of pixels, more than 4 levels 0.02 .. 0.24 %, mean 0.03 .. 0.15 levels, largest
 * 9 .. 47 (before fire's temperature took half the detail's fluctuation: up to 0.66 %, 0.29 %,
 * 69). The same frames with every medium's detail strength 0: more than 2 levels
 * 0.002 .. 0.021 %, more than 4 levels 0 .. 0.016 %, mean 0.02 .. 0.13 levels. So the detail,
 * not a lost pass, makes the thirtyfold larger fractions: a low-bit difference of the filtered
 * detail is multiplied by the erosion ramp (slope 1.8 x 2.2 on the density) and by the fire's
 * black-body colour (steep in temperature). Issue 27's soot (docs/look-fire.md: old fire absorbs
 * up to 16 times its glowing depth, with the detail strength) multiplies them once more, in the
 * cooling fire: measured on 2026-11-26 (same Mesa, 6 frames, the same numbers on every run) more
 * than 2 levels apart 0.17 .. 1.02 % of pixels, more than 4 levels 0.04 .. 0.47 %, mean
 * 0.03 .. 0.14 levels, largest 24 .. 49; the same code with the soot off: 0.15 .. 0.66 %,
 * 0.02 .. 0.26 %, 0.03 .. 0.15, 9 .. 46. The bound is on fractions, about 1.5 times the largest
 * measured:
 *     >= 98.5 % of pixels within 2/255 and >= 99.25 % within 4/255 in every channel,
 *     mean |diff| <= 0.25/255 (unchanged: the detail hardly moves the mean),
 * and, only as a backstop against garbage, no channel more than 96/255 apart. */
#include <errno.h>
#include <fcntl.h>
#include <sys/stat.h>
#include "gl_fixture.h"
#include "host/test_scene.h"

#define W 320
#define H 180
#define FRAMES 3
#define CONFIGS 2
#define IMAGE_BYTES (W * H * 4)
#define EXIT_NO_DRIVER 3

static const double times[FRAMES] = {0.3, 0.8, 1.5};

static sbfx_desc config_desc(int c)
{
    if (c == 0) return (sbfx_desc){0}; /* the defaults */
    return (sbfx_desc){.target_divisor = 1, .target_format = SBFX_FORMAT_RGBA32F, .opacity = SBFX_OPACITY_EXACT};
}

/* One configuration's frames into out (FRAMES images, bottom row first). */
static int render_frames(struct test_scene *scene, GLuint fbo, sbfx_desc desc, uint8_t *out)
{
    sbfx *fx = NULL;
    if (sbfx_create(&desc, &fx) != SBFX_OK) return -1;
    sbfx_frame frame = {.scene_color_texture = scene->color_texture, .scene_depth_texture = scene->depth_texture,
                        .out_framebuffer = fbo, .width = W, .height = H};
    test_scene_orbit_camera(0.0, (float)W / H, frame.view, frame.projection); /* fixed camera */
    int rc = 0;
    for (int i = 0; i < FRAMES && rc == 0; i++) {
        while (sbfx_time(fx) < times[i] - 1e-9) sbfx_update(fx, 1.0 / 120.0);
        test_scene_draw(scene, frame.view, frame.projection);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, scene->framebuffer);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        if (sbfx_render(fx, &frame) != SBFX_OK) rc = -1;
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, out + (size_t)i * IMAGE_BYTES);
    }
    sbfx_destroy(fx);
    return rc;
}

static int write_file(const char *path, const uint8_t *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    size_t written = fwrite(data, 1, n, f);
    return fclose(f) == 0 && written == n ? 0 : -1;
}

static GLuint output_framebuffer(void)
{
    GLuint rb = 0, fbo = 0;
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, W, H);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE ? fbo : 0;
}

/* The child: GALLIUM_DRIVER set before EGL opens, every configuration's frames to `path`. */
static int child_render(const char *driver, const char *path)
{
    setenv("GALLIUM_DRIVER", driver, 1);
    struct egl_headless egl;
    char err[512];
    if (egl_headless_open(&egl, err, sizeof(err)) != 0) return EXIT_NO_DRIVER;
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    if (!renderer || !strstr(renderer, driver)) return EXIT_NO_DRIVER; /* Mesa fell back to another */
    struct test_scene scene;
    GLuint fbo = output_framebuffer();
    if (!fbo || test_scene_create(&scene, W, H, err, sizeof(err)) != 0) return 1;
    uint8_t *images = calloc(CONFIGS * FRAMES, IMAGE_BYTES);
    int rc = images ? 0 : 1;
    for (int c = 0; c < CONFIGS && rc == 0; c++)
        rc = render_frames(&scene, fbo, config_desc(c), images + (size_t)c * FRAMES * IMAGE_BYTES);
    if (rc == 0) rc = write_file(path, images, (size_t)CONFIGS * FRAMES * IMAGE_BYTES) ? 1 : 0;
    free(images);
    test_scene_destroy(&scene);
    egl_headless_close(&egl);
    return rc;
}

static int run_child(const char *driver, const char *path)
{
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) _exit(child_render(driver, path));
    int status = 0;
    if (pid < 0 || waitpid(pid, &status, 0) < 0) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static uint8_t *read_file(const char *path, size_t n)
{
    uint8_t *data = malloc(n);
    FILE *f = fopen(path, "rb");
    size_t got = f && data ? fread(data, 1, n, f) : 0;
    if (f) fclose(f);
    if (got != n) {
        free(data);
        return NULL;
    }
    return data;
}

typedef struct diff_stats {
    double mean;     /* mean |diff| over every RGB channel, levels */
    int max;         /* largest |diff| of any channel */
    double over_4;   /* fraction of pixels with some channel more than 4 levels apart */
    double over_2;
} diff_stats;

static diff_stats compare_images(const uint8_t *a, const uint8_t *b, size_t pixels)
{
    diff_stats d = {0};
    size_t over4 = 0, over2 = 0;
    double sum = 0;
    for (size_t i = 0; i < pixels; i++) {
        int worst = 0;
        for (int k = 0; k < 3; k++) {
            int e = abs((int)a[4 * i + k] - (int)b[4 * i + k]);
            sum += e;
            worst = e > worst ? e : worst;
        }
        d.max = worst > d.max ? worst : d.max;
        over4 += worst > 4;
        over2 += worst > 2;
    }
    d.mean = sum / (3.0 * pixels);
    d.over_4 = (double)over4 / pixels;
    d.over_2 = (double)over2 / pixels;
    return d;
}

CHECK_TEST(llvmpipe_and_softpipe_agree)
{
    char lp_path[64], sp_path[64];
    snprintf(lp_path, sizeof(lp_path), "/tmp/sbfx-drivers-%d-llvmpipe.rgba", (int)getpid());
    snprintf(sp_path, sizeof(sp_path), "/tmp/sbfx-drivers-%d-softpipe.rgba", (int)getpid());
    int lp = run_child("llvmpipe", lp_path);
    if (lp == EXIT_NO_DRIVER) CHECK_SKIP("llvmpipe is not available (GALLIUM_DRIVER=llvmpipe gave another renderer)");
    int sp = run_child("softpipe", sp_path);
    if (sp == EXIT_NO_DRIVER) {
        unlink(lp_path);
        CHECK_SKIP("softpipe is not available in this Mesa (GALLIUM_DRIVER=softpipe gave another renderer)");
    }
    CHECK(lp == 0 && sp == 0, "rendering failed: llvmpipe %d, softpipe %d", lp, sp);
    size_t n = (size_t)CONFIGS * FRAMES * IMAGE_BYTES;
    uint8_t *a = read_file(lp_path, n), *b = read_file(sp_path, n);
    unlink(lp_path);
    unlink(sp_path);
    if (!a || !b) {
        free(a), free(b);
        CHECK(0, "the children wrote no images");
        return;
    }
    for (int i = 0; i < CONFIGS * FRAMES; i++) {
        diff_stats d = compare_images(a + (size_t)i * IMAGE_BYTES, b + (size_t)i * IMAGE_BYTES, W * H);
        printf("# %s t=%.1f: mean |diff| %.4f levels, max %d, pixels > 2 levels %.4f %%, > 4 levels %.4f %%\n",
               i < FRAMES ? "defaults" : "exact 1/1 RGBA32F", times[i % FRAMES], d.mean, d.max, 100 * d.over_2,
               100 * d.over_4);
        CHECK(d.over_2 <= 0.015, "frame %d: %.3f %% of pixels differ by more than 2 levels", i, 100 * d.over_2);
        CHECK(d.over_4 <= 0.0075, "frame %d: %.3f %% of pixels differ by more than 4 levels", i, 100 * d.over_4);
        CHECK(d.mean <= 0.25, "frame %d: mean difference %.3f levels", i, d.mean);
        CHECK(d.max <= 96, "frame %d: a channel differs by %d levels", i, d.max);
    }
    free(a);
    free(b);
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
