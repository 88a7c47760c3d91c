/* Board profiles (platform/player/options/board.c): every boards/NAME.cfg loads; errors name file, line and key. */
#include <errno.h>
#include <glob.h>
#include <stdio.h>
#include <string.h>

#include "player/options/board.h"
#include "check.h"

static const char *write_temp(const char *text)
{
    static char path[64];
    snprintf(path, sizeof(path), "/tmp/sbfx-board-%d.cfg", (int)getpid());
    FILE *f = fopen(path, "w");
    if (!f) return NULL;
    fputs(text, f);
    fclose(f);
    return path;
}

/* Loads text as a profile; returns the error message ("" when it loaded). */
static const char *load_text(const char *text, struct board_profile *b)
{
    static char err[512];
    err[0] = '\0';
    const char *path = write_temp(text);
    if (!path) return "cannot write a temporary file";
    board_load(path, b, err, sizeof(err));
    remove(path);
    return err;
}

CHECK_TEST(every_board_profile_loads)
{
    glob_t g;
    CHECK(glob("boards/*.cfg", 0, NULL, &g) == 0, "no boards/*.cfg (run from the repository root)");
    CHECK(g.gl_pathc >= 4, "%zu profiles", g.gl_pathc);
    for (size_t i = 0; i < g.gl_pathc; i++) {
        struct board_profile b;
        char err[512] = "";
        CHECK(board_load(g.gl_pathv[i], &b, err, sizeof(err)) == 0, "%s", err);
        CHECK(b.name[0] && b.description[0], "%s: no name or description", g.gl_pathv[i]);
        CHECK(b.target_scale && b.max_particles, "%s: no render budget", g.gl_pathv[i]);
    }
    globfree(&g);
}

CHECK_TEST(values_arrive)
{
    struct board_profile b;
    const char *err = load_text(
        "board = \"t\";\n"
        "display = { device = \"/dev/dri/card3\"; connector = \"DSI-1\"; mode = \"800x480@60\"; modeset = \"legacy\";\n"
        "  backend = \"wayland\"; };\n"
        "video = { device = \"/dev/video7\"; size = [320, 240]; };\n"
        "gpio = { debounce_ms = 12; min_interval_ms = 900;\n"
        "  lines = ( { chip = \"gpiochip2\"; line = 5; edge = \"both\"; effect = \"boom\"; position = [1.0, 2.0, 3.5]; },\n"
        "            { chip = \"gpiochip2\"; line = 6; debounce_ms = 1; } ); };\n"
        "render = { target_scale = 8; max_particles = 512; };\n", &b);
    CHECK(!err[0], "%s", err);
    CHECK(strcmp(b.drm_device, "/dev/dri/card3") == 0 && strcmp(b.connector, "DSI-1") == 0);
    CHECK(strcmp(b.mode, "800x480@60") == 0 && b.modeset == MODESET_LEGACY);
    CHECK(strcmp(b.backend, "wayland") == 0, "backend '%s'", b.backend);
    CHECK(strcmp(b.video_device, "/dev/video7") == 0 && b.video_width == 320 && b.video_height == 240);
    CHECK(b.gpio_count == 2);
    CHECK(b.gpio[0].line == 5 && b.gpio[0].edge == SBFX_EDGE_BOTH && strcmp(b.gpio[0].effect, "boom") == 0);
    CHECK(b.gpio[0].debounce_ms == 12 && b.gpio[0].min_interval_ms == 900);
    CHECK(b.gpio[0].position[2] == 3.5f);
    CHECK(b.gpio[1].debounce_ms == 1 && b.gpio[1].edge == SBFX_EDGE_RISING);
    CHECK(strcmp(b.gpio[1].effect, "explosion") == 0, "the default effect");
    CHECK(b.target_scale == 8 && b.max_particles == 512);
}

CHECK_TEST(errors_name_file_line_and_key)
{
    struct board_profile b;
    const char *err = load_text("board = \"t\";\ndisplay = {\n  conector = \"HDMI-A-1\"; };\n", &b);
    CHECK(strstr(err, ".cfg:3: unknown key 'conector' in display") != NULL, "%s", err);
    err = load_text("display = { mode = \"wide\"; };\n", &b);
    CHECK(strstr(err, ":1: 'mode' = \"wide\" is not WxH") != NULL, "%s", err);
    err = load_text("render = { target_scale = 3; };\n", &b);
    CHECK(strstr(err, "'target_scale' must be 1, 2, 4 or 8") != NULL, "%s", err);
    err = load_text("gpio = { lines = ( { chip = \"gpiochip0\"; } ); };\n", &b);
    CHECK(strstr(err, "needs 'chip' and 'line'") != NULL, "%s", err);
    err = load_text("gpio = { lines = ( { chip = \"gpiochip0\"; line = 70000; } ); };\n", &b);
    CHECK(strstr(err, "'line' = 70000 is out of range") != NULL, "%s", err);
    err = load_text("display = { modeset = \"fast\"; };\n", &b);
    CHECK(strstr(err, "'modeset' = \"fast\" is not one of") != NULL, "%s", err);
    err = load_text("display = { backend = \"x11\"; };\n", &b);
    CHECK(strstr(err, "'backend' = \"x11\" is not one of") != NULL, "%s", err);
    err = load_text("video = { size = [640]; };\n", &b);
    CHECK(strstr(err, "'size' must be an array of 2 numbers") != NULL, "%s", err);
    err = load_text("board = ;\n", &b);
    CHECK(strstr(err, ".cfg:1: ") != NULL, "a syntax error names the line: %s", err);
    CHECK(b.gpio_count == 0 && !b.drm_device[0], "a failed load leaves the defaults");
}

CHECK_TEST(channel_group)
{
    struct board_profile b;
    const char *err = load_text("channel = { frustum = [-30.0, -10.0, -15.0, 15.0]; view_offset = [5.0, 0.0, -1.0]; };\n", &b);
    CHECK(!err[0], "%s", err);
    CHECK(b.channel.have_frustum && b.channel.frustum[0] == -30.0f && b.channel.frustum[1] == -10.0f);
    CHECK(b.channel.have_offset && b.channel.offset[0] == 5.0f && b.channel.offset[2] == -1.0f);
    err = load_text("channel = { frustum = [10.0, -10.0, -15.0, 15.0]; };\n", &b);
    CHECK(strstr(err, ":1: 'frustum' [left, right, bottom, top]: LEFT must be less than RIGHT") != NULL, "%s", err);
    err = load_text("channel = { fov = 40.0; };\n", &b);
    CHECK(strstr(err, "unknown key 'fov' in channel") != NULL, "%s", err);
}

CHECK_TEST(missing_file)
{
    struct board_profile b;
    char err[256];
    CHECK(board_load("/nonexistent/board.cfg", &b, err, sizeof(err)) == -ENOENT);
    CHECK(strstr(err, "/nonexistent/board.cfg: cannot open") != NULL, "%s", err);
}

CHECK_TEST(mode_spec)
{
    int w, h, hz;
    CHECK(mode_spec_parse("1920x1080", &w, &h, &hz) == 0 && w == 1920 && h == 1080 && hz == 0);
    CHECK(mode_spec_parse("1280x720@60", &w, &h, &hz) == 0 && w == 1280 && h == 720 && hz == 60);
    const char *bad[] = {"", "x", "1920", "1920x", "x1080", "1920x1080@", "1920x1080@0",
                         "0x1080", "1920x1080p", "-1x5", "1920 x1080", "99999x1", "1x1@60Hz", NULL};
    for (int i = 0; bad[i]; i++) CHECK(mode_spec_parse(bad[i], &w, &h, &hz) == -EINVAL, "'%s'", bad[i]);
    CHECK(mode_spec_parse(NULL, &w, &h, &hz) == -EINVAL);
}

int main(int argc, char **argv)
{
    return check_main_args(argc, argv);
}
