/* Detail from a recorded clip (platform/clip_detail.c): clips made here by the ffmpeg command
 * from its built-in sources in several containers and codecs decode to the luma the ffmpeg
 * command itself gives; missing, garbage, truncated, audio-only and one-frame files are errors
 * naming the file; the loop's seam is no larger than the clip's own frame steps. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "video/clip_detail.h"
#include "video/luma.h"

#define S 32          /* slice side */
#define SLICES 32     /* the module's default ring */
#define MAX_FRAMES 64

static char dir[64];

/* A scratch folder with the clips (made once per test: each test runs in its own process). */
static void make_dir(void)
{
    if (system("command -v ffmpeg >/dev/null 2>&1") != 0)
        CHECK_SKIP("the ffmpeg command is not installed (tools/deps.sh test)");
    snprintf(dir, sizeof(dir), "/tmp/sbfx-clip-XXXXXX");
    if (!mkdtemp(dir)) CHECK_SKIP("cannot make a scratch folder: %s", strerror(errno));
}

static void remove_dir(void)
{
    char cmd[128];
    snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
    if (system(cmd) != 0) printf("# could not remove %s\n", dir);
}

/* ffmpeg -f lavfi -i SOURCE ARGS dir/NAME; the path in out. */
static bool make_clip(const char *source, const char *args, const char *name, char *out, size_t n)
{
    char cmd[1024];
    snprintf(out, n, "%s/%s", dir, name);
    snprintf(cmd, sizeof(cmd), "ffmpeg -hide_banner -loglevel error -nostdin -y -f lavfi -i '%s' %s '%s'",
             source, args, out);
    int rc = system(cmd);
    CHECK(rc == 0, "%s: exit %d", cmd, rc);
    return rc == 0;
}

static bool has_encoder(const char *name)
{
    char cmd[256];
    snprintf(cmd, sizeof(cmd), "ffmpeg -hide_banner -encoders 2>/dev/null | grep -qw '%s'", name);
    return system(cmd) == 0;
}

/* The ffmpeg command's own luma of the clip's frames (rawvideo gray), box-filtered as ours. */
static int reference_means(const char *path, int width, int height, float *out, int max_frames)
{
    char raw[128], cmd[512];
    snprintf(raw, sizeof(raw), "%s/ref.gray", dir);
    snprintf(cmd, sizeof(cmd), "ffmpeg -hide_banner -loglevel error -nostdin -y -i '%s' -frames:v %d "
             "-f rawvideo -pix_fmt gray '%s'", path, max_frames, raw);
    if (system(cmd) != 0) return -1;
    FILE *f = fopen(raw, "rb");
    if (!f) return -1;
    size_t bytes = (size_t)width * height;
    uint8_t *frame = malloc(bytes);
    static float values[S * S];
    struct luma_resampler r;
    char err[256];
    int frames = 0;
    if (luma_resampler_init(&r, S, width, height, values, err, sizeof(err)) != 0) frames = -1;
    while (frames >= 0 && frames < max_frames && fread(frame, 1, bytes, f) == bytes) {
        struct luma_view v = {.data = frame, .bytes = bytes, .width = width, .height = height,
                              .stride = width, .step = 1};
        r.values = out + (size_t)frames * S * S;
        if (luma_box_means(&r, &v) != 0) frames = -1;
        else frames++;
    }
    free(frame);
    fclose(f);
    return frames;
}

struct clip_case {
    const char *source, *args, *name, *codec;
    int frames;        /* expected decoded (at most MAX_FRAMES) */
    double tolerance;  /* luma levels between our decode and the ffmpeg command's */
};

static void check_case(const struct clip_case *c)
{
    static float ours[MAX_FRAMES * S * S], theirs[MAX_FRAMES * S * S];
    char path[128], err[512];
    if (!make_clip(c->source, c->args, c->name, path, sizeof(path))) return;
    struct clip_info info;
    int frames = 0;
    int rc = clip_decode(path, S, MAX_FRAMES, ours, &frames, &info, err, sizeof(err));
    CHECK(rc == 0, "%s: %s", c->name, err);
    if (rc) return;
    printf("# %-10s %s in %s %dx%d, %.2f fps, %d frames, %.1f ms\n", c->name, info.codec, info.container,
           info.width, info.height, info.fps, frames, info.decode_ms);
    CHECK(frames == c->frames, "%s: %d frames, want %d", c->name, frames, c->frames);
    CHECK(strcmp(info.codec, c->codec) == 0, "%s: codec %s, want %s", c->name, info.codec, c->codec);
    int ref = reference_means(path, info.width, info.height, theirs, MAX_FRAMES);
    CHECK(ref == frames, "%s: the ffmpeg command gives %d frames, we %d", c->name, ref, frames);
    double worst = 0.0;
    for (size_t i = 0; ref == frames && i < (size_t)frames * S * S; i++)
        worst = fmax(worst, fabs((double)ours[i] - theirs[i]));
    printf("#   largest difference to the ffmpeg command's luma: %.3f levels\n", worst);
    CHECK(worst <= c->tolerance, "%s: luma differs by %.3f levels", c->name, worst);
}

CHECK_TEST(containers_and_codecs_decode_to_ffmpegs_luma)
{
    make_dir();
    const char *h264 = has_encoder("libx264") ? "-c:v libx264 -pix_fmt yuv420p" : "-c:v mpeg4 -q:v 2";
    const char *h264_name = has_encoder("libx264") ? "h264" : "mpeg4";
    const struct clip_case cases[] = {
        {"testsrc2=size=160x120:rate=25", NULL, "a.mp4", NULL, 50, 0.0},
        {"mandelbrot=size=128x96:rate=25", "-frames:v 30 -c:v ffv1", "b.mkv", "ffv1", 30, 0.0},
        {"cellauto=size=96x96:rate=25", "-frames:v 20 -pix_fmt gray", "c.y4m", "rawvideo", 20, 0.0},
        {"color=gray:size=120x90:rate=25,noise=alls=100:allf=t", "-frames:v 12 -c:v mjpeg -q:v 3",
         "d.avi", "mjpeg", 12, 0.0},
        {"testsrc2=size=100x140:rate=25", "-frames:v 70 -c:v rawvideo -pix_fmt rgb24", "e.nut", "rawvideo",
         MAX_FRAMES, 0.0},
    };
    char args[128];
    snprintf(args, sizeof(args), "-frames:v 50 %s", h264);
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        struct clip_case c = cases[i];
        if (i == 0) c.args = args, c.codec = h264_name;
        check_case(&c);
    }
    remove_dir();
}

static void check_refused(const char *path, const char *why)
{
    static float out[MAX_FRAMES * S * S];
    char err[512] = "";
    int frames = -1;
    int rc = clip_decode(path, S, MAX_FRAMES, out, &frames, NULL, err, sizeof(err));
    printf("# %s: %s\n", why, err);
    CHECK(rc < 0, "%s: decoded %d frames", why, frames);
    CHECK(strstr(err, path) != NULL, "%s: the message does not name %s: %s", why, path, err);
}

CHECK_TEST(bad_files_are_errors_naming_them)
{
    make_dir();
    char path[128], cut[160], cmd[512];
    snprintf(path, sizeof(path), "%s/missing.mp4", dir);
    check_refused(path, "missing file");
    snprintf(path, sizeof(path), "%s/garbage.mp4", dir);
    FILE *f = fopen(path, "wb");
    for (unsigned i = 0, x = 12345; i < 100000; i++) x = x * 1103515245u + 12345u, fputc((int)(x >> 16) & 255, f);
    fclose(f);
    check_refused(path, "garbage");
    if (make_clip("testsrc2=size=160x120:rate=25", "-frames:v 50 -c:v mpeg4", "whole.mp4", path, sizeof(path))) {
        snprintf(cut, sizeof(cut), "%s/cut.mp4", dir);
        snprintf(cmd, sizeof(cmd), "head -c 20000 '%s' > '%s'", path, cut);
        CHECK(system(cmd) == 0);
        check_refused(cut, "truncated mp4 (no index)");
    }
    if (make_clip("sine=frequency=440:duration=1", "", "audio.wav", path, sizeof(path)))
        check_refused(path, "audio only");
    if (make_clip("testsrc2=size=64x64:rate=25", "-frames:v 1 -c:v ffv1", "one.mkv", path, sizeof(path)))
        check_refused(path, "one frame");
    snprintf(path, sizeof(path), "%s", dir);
    check_refused(path, "a folder");
    remove_dir();
}

/* A truncated stream decodes what it holds (a shorter clip) or fails naming the file: never
 * more frames than were written, never a crash. */
CHECK_TEST(truncated_streams_give_fewer_frames_or_an_error)
{
    make_dir();
    static float out[MAX_FRAMES * S * S];
    char path[128], cut[160], cmd[512], err[512];
    const char *kinds[][3] = {{"-frames:v 40 -c:v ffv1", "t.mkv", "mkv/ffv1"},
                              {"-frames:v 40 -pix_fmt gray", "t.y4m", "y4m"},
                              {"-frames:v 40 -c:v mpeg4 -f mpegts", "t.ts", "mpegts/mpeg4"}};
    for (int k = 0; k < 3; k++) {
        if (!make_clip("mandelbrot=size=96x96:rate=25", kinds[k][0], kinds[k][1], path, sizeof(path))) continue;
        snprintf(cut, sizeof(cut), "%s.cut", path);
        snprintf(cmd, sizeof(cmd), "head -c $(( $(stat -c %%s '%s') / 2 + 77 )) '%s' > '%s'", path, path, cut);
        CHECK(system(cmd) == 0);
        int frames = 0;
        int rc = clip_decode(cut, S, MAX_FRAMES, out, &frames, NULL, err, sizeof(err));
        printf("# %s cut in half: %s\n", kinds[k][2], rc ? err : "decoded");
        if (rc == 0) printf("#   %d of 40 frames\n", frames);
        if (rc == 0) CHECK(frames >= CLIP_MIN_FRAMES && frames < 40, "%s: %d frames", kinds[k][2], frames);
        else CHECK(strstr(err, cut) != NULL, "%s: %s", kinds[k][2], err);
    }
    remove_dir();
}

/* ---- the loop ---- */

CHECK_TEST(loop_crossfades_the_tail_into_the_head)
{
    enum { N = 40, T = 2 };
    static float frames[N * T * T], out[SLICES * T * T];
    for (int k = 0; k < N; k++)
        for (int i = 0; i < T * T; i++) frames[k * T * T + i] = (float)(k * 10 + i);
    int lc = 0, c = 0;
    CHECK(clip_loop(frames, N, T, SLICES, out, &lc, &c) == 0);
    CHECK(lc == SLICES && c == SLICES / 4, "loop %d, crossfade %d", lc, c);
    for (int s = 0; s < SLICES; s++) {
        double w = s < c ? (double)s / c : 1.0;
        double want = w * (s * 10) + (1.0 - w) * ((lc + s) * 10);
        CHECK_NEAR(out[s * T * T], want, 1e-4);
        CHECK_NEAR(out[s * T * T + 3], want + 3, 1e-4);
    }
    /* the step across the loop point is the clip's own step from frame Lc - 1 to frame Lc */
    CHECK_NEAR(out[0] - out[(SLICES - 1) * T * T], 10.0, 1e-4);
    /* a short clip: a loop of n - n/5 frames resampled in time to every slice */
    CHECK(clip_loop(frames, 10, T, SLICES, out, &lc, &c) == 0);
    CHECK(lc == 8 && c == 2, "loop %d, crossfade %d", lc, c);
    CHECK_NEAR(out[0], 80.0, 1e-4);             /* slice 0 = frame Lc */
    CHECK_NEAR(out[2 * T * T], 0.5 * 80.0 + 0.5 * 90.0 * 0.5 + 0.5 * 0.5 * 10.0, 1e-4); /* t = 0.5 */
    CHECK(clip_loop(frames, 1, T, SLICES, out, &lc, &c) == -EINVAL);
}

/* Seam and steps of a loop built from the clip, against the clip's own steps over its first
 * Lc + C frames; both through the same curve (one normalisation over both), so they compare. */
static void seam_of(const char *name, const float *frames, int n, double *seam, double *own_median,
                    double *own_max, double *naive)
{
    static float both[(SLICES + MAX_FRAMES) * S * S];
    static uint16_t halves[(SLICES + MAX_FRAMES) * S * S];
    const size_t texels = (size_t)S * S;
    int lc = 0, c = 0;
    CHECK(clip_loop(frames, n, S, SLICES, both, &lc, &c) == 0);
    memcpy(both + SLICES * texels, frames, (size_t)(lc + c) * texels * sizeof(float));
    clip_normalise(both, (size_t)(SLICES + lc + c) * texels, halves);
    double median, max, own_seam, naive_median, naive_max;
    clip_seam(halves, S, SLICES, seam, &median, &max);
    clip_seam(halves + SLICES * texels, S, lc + c, &own_seam, own_median, own_max);
    clip_seam(halves + SLICES * texels, S, SLICES, naive, &naive_median, &naive_max); /* a plain cut */
    printf("# %-10s loop %d + crossfade %d: seam %.4f; loop steps median %.4f max %.4f; the clip's own "
           "steps median %.4f max %.4f; a plain cut's seam %.4f\n", name, lc, c, *seam, median, max,
           *own_median, *own_max, *naive);
}

CHECK_TEST(loop_has_no_seam)
{
    make_dir();
    static float frames[MAX_FRAMES * S * S];
    struct { const char *source, *name; bool moving; } sources[] = {
        {"testsrc2=size=160x120:rate=25", "testsrc2", true},
        {"mandelbrot=size=128x128:rate=25", "mandelbrot", true},
        {"cellauto=size=128x128:rate=25:seed=7", "cellauto", false},
        {"color=gray:size=128x128:rate=25,noise=alls=100:allf=t", "noise", false},
        /* colours and end points given: with only a seed, FFmpeg's gradients still varied from run
         * to run, and once drew a clip that never moved (the control below then failed) */
        {"gradients=size=128x128:rate=25:speed=0.05:nb_colors=2:c0=black:c1=white:x0=0:y0=0:x1=127:y1=127",
         "gradients", true},
    };
    for (size_t i = 0; i < sizeof(sources) / sizeof(sources[0]); i++) {
        char path[128], err[512];
        char name[64];
        snprintf(name, sizeof(name), "%s.mkv", sources[i].name);
        if (!make_clip(sources[i].source, "-frames:v 40 -c:v ffv1", name, path, sizeof(path))) continue;
        int n = 0;
        CHECK(clip_decode(path, S, SLICES + SLICES / 4, frames, &n, NULL, err, sizeof(err)) == 0, "%s", err);
        double seam, own_median, own_max, naive;
        seam_of(sources[i].name, frames, n, &seam, &own_median, &own_max, &naive);
        CHECK(seam <= own_max + 1e-3, "%s: seam %.4f, the clip's largest step %.4f", sources[i].name, seam, own_max);
        CHECK(seam <= 1.5 * own_median + 1e-3, "%s: seam %.4f, the clip's median step %.4f", sources[i].name,
              seam, own_median);
        /* the control: where the picture moves a plain cut jumps, so the check above can fail */
        if (sources[i].moving)
            CHECK(naive > 2.0 * own_median, "%s: a plain cut's seam %.4f is no jump (median %.4f)",
                  sources[i].name, naive, own_median);
    }
    remove_dir();
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
