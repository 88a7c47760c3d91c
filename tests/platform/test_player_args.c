/* sbfx-play's platform flags (platform/player/options/args.c): --gpio syntax, display conflicts. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "player/options/options.h"

static int parse(struct player_options *opt, char *err, size_t n, const char *a, const char *b,
                 const char *c, const char *d)
{
    char *argv[] = {"sbfx-play", (char *)a, (char *)b, (char *)c, (char *)d, NULL};
    int argc = 1;
    while (argc < 5 && argv[argc]) argc++;
    player_options_defaults(opt);
    return player_parse_args(opt, argc, argv, err, n);
}

CHECK_TEST(gpio_good)
{
    struct player_gpio g;
    char err[512];
    CHECK(player_parse_gpio("gpiochip0:17=explosion", &g, err, sizeof(err)) == 0, "%s", err);
    CHECK(strcmp(g.chip, "gpiochip0") == 0 && g.line == 17 && strcmp(g.effect, "explosion") == 0);
    CHECK(g.position[0] == 0 && g.position[1] == 0 && g.position[2] == 0);
    CHECK(player_parse_gpio("/dev/gpiochip2:3=boom@1.5,-2,3e1", &g, err, sizeof(err)) == 0, "%s", err);
    CHECK(strcmp(g.chip, "/dev/gpiochip2") == 0 && g.line == 3 && g.position[2] == 30.0f);
    CHECK(player_parse_gpio("my:label:4=x", &g, err, sizeof(err)) == 0, "the last ':' splits");
    CHECK(strcmp(g.chip, "my:label") == 0 && g.line == 4);
}

CHECK_TEST(gpio_bad)
{
    const char *bad[] = {"gpiochip0", "gpiochip0:17", ":17=explosion", "gpiochip0=explosion",
                         "gpiochip0:x=explosion", "gpiochip0:-1=explosion", "gpiochip0:65536=e",
                         "gpiochip0:17=", "gpiochip0:17=a b", "gpiochip0:17=e@1,2",
                         "gpiochip0:17=e@1,2,z", "gpiochip0:17=e@nan,0,0", "gpiochip0: 1=e", NULL};
    for (int i = 0; bad[i]; i++) {
        struct player_gpio g;
        char err[512] = "";
        CHECK(player_parse_gpio(bad[i], &g, err, sizeof(err)) == -EINVAL, "'%s' accepted", bad[i]);
        CHECK(strstr(err, "--gpio: expected CHIP:LINE=EFFECT") != NULL, "'%s': %s", bad[i], err);
    }
}

CHECK_TEST(display_flags)
{
    static struct player_options opt;
    char err[512];
    CHECK(parse(&opt, err, sizeof(err), "--display", "drm", NULL, NULL) == 0, "%s", err);
    CHECK(opt.display == PLAYER_DISPLAY_DRM && !opt.frames_set);
    CHECK(parse(&opt, err, sizeof(err), "--display=drm", "--mode", "640x480@60", NULL) == 0, "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--display", "drm", "--size", "64x64") == -EINVAL);
    CHECK(strstr(err, "--size applies to --display headless") != NULL, "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--headless", "--display", "drm", NULL) == -EINVAL);
    CHECK(parse(&opt, err, sizeof(err), "--device", "/dev/dri/card0", NULL, NULL) == -EINVAL);
    CHECK(strstr(err, "--device applies to --display drm") != NULL, "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--display", "kms", NULL, NULL) == -EINVAL);
    CHECK(strstr(err, "--display: expected one of drm|headless") != NULL, "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--display", "drm", "--mode", "big") == -EINVAL);
    CHECK(strstr(err, "--mode: expected WxH") != NULL, "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--display", "drm", "--modeset", "fast") == -EINVAL);
    CHECK(parse(&opt, err, sizeof(err), "--video", "/dev/video0", "--board", "b.cfg") == 0, "%s", err);
    CHECK(strcmp(opt.video, "/dev/video0") == 0 && strcmp(opt.board_path, "b.cfg") == 0);
    CHECK(parse(&opt, err, sizeof(err), "--gpio", "a:1=x", "--gpio", "a:2=y") == 0, "%s", err);
    CHECK(opt.gpio_count == 2 && opt.gpio[1].line == 2);
}

/* --display wayland and auto (WAYLAND_DISPLAY decides), their flags, and a board's display. */
CHECK_TEST(wayland_display)
{
    static struct player_options opt;
    char err[512];
    CHECK(parse(&opt, err, sizeof(err), "--display", "wayland", "--size", "640x360") == 0, "%s", err);
    CHECK(opt.display == PLAYER_DISPLAY_WAYLAND && player_on_screen(&opt) && opt.width == 640);
    CHECK(parse(&opt, err, sizeof(err), "--display", "wayland", "--out", "x") == -EINVAL);
    CHECK(strstr(err, "--out applies to --display headless, not wayland") != NULL, "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--display", "wayland", "--mode", "640x480") == -EINVAL);
    CHECK(strstr(err, "--mode applies to --display drm (the display is wayland)") != NULL, "%s", err);
    setenv("WAYLAND_DISPLAY", "wayland-1", 1);
    CHECK(parse(&opt, err, sizeof(err), "--display", "auto", NULL, NULL) == 0, "%s", err);
    CHECK(opt.display == PLAYER_DISPLAY_WAYLAND && opt.display_auto);
    CHECK(parse(&opt, err, sizeof(err), "--display", "auto", "--device", "/dev/dri/card0") == -EINVAL);
    CHECK(strstr(err, "auto chose it, WAYLAND_DISPLAY is set") != NULL, "%s", err);
    setenv("WAYLAND_DISPLAY", "", 1);
    CHECK(parse(&opt, err, sizeof(err), "--display", "auto", NULL, NULL) == 0, "%s", err);
    CHECK(opt.display == PLAYER_DISPLAY_DRM, "an empty WAYLAND_DISPLAY is no compositor");
    unsetenv("WAYLAND_DISPLAY");
    CHECK(parse(&opt, err, sizeof(err), "--display", "auto", NULL, NULL) == 0 && opt.display == PLAYER_DISPLAY_DRM);
    /* a board's display.backend: only where the command line named none */
    CHECK(parse(&opt, err, sizeof(err), "--board", "b.cfg", NULL, NULL) == 0, "%s", err);
    CHECK(player_board_display(&opt, "wayland", err, sizeof(err)) == 0 && opt.display == PLAYER_DISPLAY_WAYLAND);
    CHECK(parse(&opt, err, sizeof(err), "--board", "b.cfg", "--headless", NULL) == 0, "%s", err);
    CHECK(player_board_display(&opt, "wayland", err, sizeof(err)) == 0 && opt.display == PLAYER_DISPLAY_HEADLESS);
    CHECK(parse(&opt, err, sizeof(err), "--board", "b.cfg", "--out", "x") == 0, "%s", err);
    CHECK(player_board_display(&opt, "drm", err, sizeof(err)) == -EINVAL);
    CHECK(strstr(err, "--out applies to --display headless, not drm") != NULL, "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--board", "b.cfg", NULL, NULL) == 0, "%s", err);
    CHECK(player_board_display(&opt, "", err, sizeof(err)) == 0 && opt.display == PLAYER_DISPLAY_HEADLESS);
}

/* The authoring loop's flags (issue 29): --watch needs a scene file; --loop's period. */
CHECK_TEST(watch_and_loop_flags)
{
    static struct player_options opt;
    char err[512];
    CHECK(parse(&opt, err, sizeof(err), "--scene", "s.cfg", "--watch", NULL) == 0, "%s", err);
    CHECK(opt.watch && opt.loop_seconds == 0.0);
    CHECK(parse(&opt, err, sizeof(err), "--watch", "--display", "drm", NULL) == -EINVAL);
    CHECK(strstr(err, "--watch reloads the scene file: give it with --scene FILE") != NULL, "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--loop", "2.5", NULL, NULL) == 0, "%s", err);
    CHECK(opt.loop_seconds == 2.5);
    const char *bad[] = {"0", "0.05", "-1", "1e7", "x", "nan"};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
        CHECK(parse(&opt, err, sizeof(err), "--loop", bad[i], NULL, NULL) == -EINVAL, "--loop %s accepted", bad[i]);
        CHECK(strstr(err, "--loop: expected a period in seconds from 0.1 to 1e6") != NULL, "%s", err);
    }
}
/* One world, many channels: --trigger's #ID, --world-time, the channel's frustum and offset. */
CHECK_TEST(channel_flags)
{
    struct player_options opt;
    char err[512];
    struct player_trigger t;
    CHECK(player_parse_trigger("explosion@1.5:2,0,-1#17", &t, err, sizeof(err)) == 0, "%s", err);
    CHECK(t.id == 17 && t.seconds == 1.5 && t.position[0] == 2.0f && t.position[2] == -1.0f);
    CHECK(player_parse_trigger("explosion@1#9223372036854775807", &t, err, sizeof(err)) == 0 &&
          t.id == UINT64_C(9223372036854775807) && t.position[0] == 0.0f, "%s", err);
    CHECK(player_parse_trigger("explosion@1", &t, err, sizeof(err)) == 0 && t.id == 0, "no #ID: the order");
    CHECK(player_parse_trigger("explosion@1#0", &t, err, sizeof(err)) == -EINVAL);
    CHECK(player_parse_trigger("explosion@1#", &t, err, sizeof(err)) == -EINVAL);
    CHECK(player_parse_trigger("explosion@1#-3", &t, err, sizeof(err)) == -EINVAL);
    CHECK(parse(&opt, err, sizeof(err), "--world-time", "2.5", "--frustum=-30,-10,-15,15", NULL) == 0, "%s", err);
    CHECK(opt.world_time_set && opt.world_time == 2.5 && opt.channel.have_frustum && opt.channel.frustum[1] == -10.0f);
    CHECK(parse(&opt, err, sizeof(err), "--view-offset", "-40,2.5,0", "--world-clock", "system") == 0, "%s", err);
    CHECK(opt.channel.have_offset && opt.channel.offset[0] == -40.0f && opt.channel.offset[1] == 2.5f &&
          opt.world_clock == PLAYER_CLOCK_SYSTEM && !opt.channel.have_frustum);
    CHECK(parse(&opt, err, sizeof(err), "--frustum=-30,30,15,-15", NULL, NULL, NULL) == -EINVAL &&
          strstr(err, "BOTTOM must be less than TOP"), "%s", err);
    CHECK(parse(&opt, err, sizeof(err), "--frustum=-30,30,-15,15,1", NULL, NULL, NULL) == -EINVAL);
    CHECK(parse(&opt, err, sizeof(err), "--view-offset", "400,0,0", NULL, NULL) == -EINVAL);
}

int main(int argc, char **argv)
{
    return check_main_args(argc, argv);
}
