/* A scene whose detail source is a video clip (docs/detail-clips.md): the clip, made here by
 * the ffmpeg command, is found beside the scene, decoded into the module's detail volume (read
 * back from the GPU slice by slice: the decoded, looped luma to the half float), and the scene
 * renders finite pixels that differ from the procedural detail's. */
#include <errno.h>
#include <unistd.h>

#include "video/clip_detail.h"
#include "gl_fixture.h"
#include "module.h"

#define CLIP_FRAMES 40

static char dir[64];

static const char *scene_text =
    "render = { target_scale = 1; max_particles = 512; };\n"
    "media = { smoke = { albedo = 0.35; density = 0.8; color = [0.9, 0.9, 0.92];\n"
    "  detail = { source = \"%s\"; strength = 1.0; window = 0.3; }; }; };\n"
    "effects = { plume = { steps = ( { type = \"emitter\"; medium = \"smoke\"; count = 40;\n"
    "  spawn_radius = 0.4; speed = [0.3, 0.8]; upward = 0.9; lifetime = [3.0, 4.0];\n"
    "  radius = [0.6, 1.4]; drag = 0.6; buoyancy = 0.7; intensity = [1.0, 0.0]; } ); }; };\n";

static void make_clip(void)
{
    if (system("command -v ffmpeg >/dev/null 2>&1") != 0)
        CHECK_SKIP("the ffmpeg command is not installed (tools/deps.sh test)");
    snprintf(dir, sizeof(dir), "/tmp/sbfx-glclip-XXXXXX");
    if (!mkdtemp(dir)) CHECK_SKIP("cannot make a scratch folder: %s", strerror(errno));
    char cmd[512];
    snprintf(cmd, sizeof(cmd), "ffmpeg -hide_banner -loglevel error -nostdin -y -f lavfi -i "
             "'mandelbrot=size=96x96:rate=25' -frames:v %d -c:v ffv1 '%s/clip.mkv'", CLIP_FRAMES, dir);
    CHECK(system(cmd) == 0, "%s", cmd);
}

static void remove_dir(void)
{
    char cmd[128];
    snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
    if (system(cmd) != 0) printf("# could not remove %s\n", dir);
}

/* The scene as if read from dir/scene.cfg, its detail source `source`. */
static sbfx *clip_module(gl_fixture *f, const char *source)
{
    char text[2048], name[128], err[512];
    snprintf(text, sizeof(text), scene_text, source);
    snprintf(name, sizeof(name), "%s/scene.cfg", dir);
    sbfx_scene *scene = NULL;
    CHECK(sbfx_scene_parse(text, name, &scene, err, sizeof(err)) == SBFX_OK, "%s", err);
    if (!scene) exit(1);
    sbfx *fx = fixture_module(f, (sbfx_desc){.scene = scene, .ignore_timeline = true});
    sbfx_scene_free(scene);
    return fx;
}

/* Slice `layer` of the detail volume as floats (R of an RGBA read). */
static bool read_layer(GLuint texture, int layer, int size, float *out)
{
    static float rgba[4 * 512 * 512];
    GLuint fbo;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, texture, 0, layer);
    bool ok = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    if (ok) glReadPixels(0, 0, size, size, GL_RGBA, GL_FLOAT, rgba);
    ok = ok && glGetError() == GL_NO_ERROR;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    for (int i = 0; ok && i < size * size; i++) out[i] = rgba[4 * i];
    return ok;
}

static float half_value(uint16_t bits)
{
    _Float16 h;
    memcpy(&h, &bits, sizeof(h));
    return (float)h;
}

/* What clip_detail_load should have written: decode, loop, normalise (tests/platform checks
 * the decode against the ffmpeg command's luma and the loop's seam). */
static uint16_t *expected_volume(const char *path, int size, int slices)
{
    size_t texels = (size_t)size * size;
    int max_frames = slices + slices / 4, frames = 0;
    float *decoded = malloc((size_t)max_frames * texels * sizeof(float));
    float *loop = malloc((size_t)slices * texels * sizeof(float));
    uint16_t *halves = malloc((size_t)slices * texels * sizeof(uint16_t));
    char err[512];
    CHECK(clip_decode(path, size, max_frames, decoded, &frames, NULL, err, sizeof(err)) == 0, "%s", err);
    CHECK(clip_loop(decoded, frames, size, slices, loop, NULL, NULL) == 0);
    clip_normalise(loop, (size_t)slices * texels, halves);
    free(decoded);
    free(loop);
    return halves;
}

CHECK_TEST(clip_fills_the_detail_volume)
{
    make_clip();
    gl_fixture f;
    fixture_open(&f, 64, 64);
    sbfx *fx = clip_module(&f, "clip.mkv");
    char path[128];
    snprintf(path, sizeof(path), "%s/clip.mkv", dir);
    const char *named = sbfx_detail_clip(fx);
    CHECK(named && strcmp(named, path) == 0, "sbfx_detail_clip: %s, want %s", named ? named : "NULL", path);
    CHECK(!sbfx_wants_live_detail(fx));
    struct clip_info info;
    char err[512];
    CHECK(clip_detail_load(fx, path, &info, err, sizeof(err)) == 0, "%s", err);
    char line[512];
    clip_describe(path, &info, line, sizeof(line));
    printf("# %s\n", line);
    int size, slices;
    sbfx_detail_dimensions(fx, &size, &slices);
    uint16_t *want = expected_volume(path, size, slices);
    float *got = malloc((size_t)size * size * sizeof(float));
    int mismatches = 0;
    double spread = 0.0;
    for (int k = 0; k < slices; k++) {
        if (!read_layer(fx->gl->detail_texture, k, size, got))
            CHECK_SKIP("an R16F volume slice cannot be read back here (no EXT_color_buffer_float)");
        for (int i = 0; i < size * size; i++) {
            float w = half_value(want[(size_t)k * size * size + i]);
            if (got[i] != w && mismatches++ < 3) printf("# slice %d texel %d: %g, want %g\n", k, i, got[i], w);
            spread += fabs(w - 0.5);
        }
    }
    CHECK(mismatches == 0, "%d texels differ from the decoded luma", mismatches);
    CHECK(spread / ((double)slices * size * size) > 0.05, "the volume is flat");
    free(got);
    free(want);
    sbfx_destroy(fx);
    fixture_close(&f);
    remove_dir();
}

/* The particle target after the plume has risen a second, seen from 8 m. */
static float *render_plume(gl_fixture *f, sbfx *fx, int *w, int *h)
{
    const float at[3] = {0.0f, -2.0f, -8.0f};
    CHECK(sbfx_trigger(fx, "plume", at) == SBFX_OK, "%s", sbfx_last_error(fx));
    for (int i = 0; i < 10; i++) CHECK(sbfx_update(fx, 0.1) == SBFX_OK);
    CHECK(sbfx_render(fx, &f->frame) == SBFX_OK, "%s", sbfx_last_error(fx));
    return fixture_read_target(fx, w, h);
}

CHECK_TEST(clip_scene_renders_finite_pixels_of_its_own)
{
    make_clip();
    gl_fixture f;
    fixture_open_far(&f, 160, 120);
    char path[128], err[512];
    snprintf(path, sizeof(path), "%s/clip.mkv", dir);
    sbfx *clip = clip_module(&f, "clip.mkv");
    CHECK(clip_detail_load(clip, path, NULL, err, sizeof(err)) == 0, "%s", err);
    sbfx *procedural = clip_module(&f, "procedural");
    CHECK(sbfx_detail_clip(procedural) == NULL);
    int w, h, w2, h2;
    float *a = render_plume(&f, clip, &w, &h);
    float *b = render_plume(&f, procedural, &w2, &h2);
    size_t n = (size_t)w * h * 4;
    CHECK(w == w2 && h == h2);
    CHECK(all_finite(a, n), "non-finite pixels with clip detail");
    double covered = 0.0, differ = 0.0;
    for (size_t i = 3; i < n; i += 4) {
        covered += a[i] < 0.95f; /* alpha: transmittance */
        differ += fabsf(a[i] - b[i]) + fabsf(a[i - 1] - b[i - 1]) > 0.02f;
    }
    printf("# %.0f of %zu pixels covered; %.0f differ from procedural detail by > 0.02 (alpha + blue)\n", covered,
           n / 4, differ);
    CHECK(covered > 0.05 * (double)(n / 4), "the plume covers %.0f pixels", covered);
    CHECK(differ > 0.2 * covered, "clip and procedural detail render alike (%.0f of %.0f)", differ, covered);
    free(a);
    free(b);
    sbfx_destroy(clip);
    sbfx_destroy(procedural);
    fixture_close(&f);
    remove_dir();
}

CHECK_TEST(missing_clip_is_an_error_and_the_volume_stays)
{
    make_clip();
    gl_fixture f;
    fixture_open(&f, 64, 64);
    sbfx *fx = clip_module(&f, "nowhere/none.mp4");
    char path[128], err[512] = "";
    snprintf(path, sizeof(path), "%s/nowhere/none.mp4", dir);
    CHECK(strcmp(sbfx_detail_clip(fx), path) == 0, "%s", sbfx_detail_clip(fx));
    CHECK(clip_detail_load(fx, sbfx_detail_clip(fx), NULL, err, sizeof(err)) < 0);
    printf("# %s\n", err);
    CHECK(strstr(err, path) != NULL, "%s", err);
    CHECK(glGetError() == GL_NO_ERROR);
    sbfx_destroy(fx);
    fixture_close(&f);
    remove_dir();
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
