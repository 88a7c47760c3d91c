/* The GPIO backend the build chose (platform/gpio/gpio_gpiod1.c or gpio_gpiod2.c, from
 * pkg-config's libgpiod version; docs/gpio.md) where no chip is needed: the errors for a chip that
 * is not there or a path that is not a chip, and calls on no line. Runs in make test (libgpiod 1.6
 * on Debian 12, 2.x on Debian 13) and, built against Debian 13's libgpiod, in the VM tier; the
 * checks with a real chip are tests/vm/gpio_backend.c. */
#include <errno.h>
#include <glob.h>
#include <string.h>

#include "check.h"
#include "gpio/gpio.h"

static bool have_chips(void)
{
    glob_t g;
    bool any = glob("/dev/gpiochip*", 0, NULL, &g) == 0 && g.gl_pathc > 0;
    globfree(&g);
    return any;
}

CHECK_TEST(missing_chip_is_enoent_and_lists_the_chips)
{
    struct gpio_line *l = (struct gpio_line *)&l; /* not NULL: the call must clear it */
    char err[512];
    int rc = gpio_line_open(&l, "sbfx-no-such-chip", 3, SBFX_EDGE_RISING, "sbfx-test", err, sizeof(err));
    CHECK(rc == -ENOENT && l == NULL, "rc %d (%s)", rc, strerror(-rc));
    CHECK(strstr(err, "GPIO chip 'sbfx-no-such-chip': cannot open it") && strstr(err, "; chips: "), "%s", err);
    if (!have_chips()) CHECK(strstr(err, "chips: none in /dev"), "no /dev/gpiochip* here: %s", err);
    else CHECK(strstr(err, "gpiochip") && strstr(err, " lines)"), "the chips listed: %s", err);
}

CHECK_TEST(missing_chip_by_number_and_path)
{
    struct gpio_line *l;
    char err[512];
    int rc = gpio_line_open(&l, "987", 0, SBFX_EDGE_BOTH, "sbfx-test", err, sizeof(err));
    CHECK(rc == -ENOENT && l == NULL && strstr(err, "'987'"), "number: %d %s", rc, err);
    rc = gpio_line_open(&l, "/dev/gpiochip987", 0, SBFX_EDGE_FALLING, "sbfx-test", err, sizeof(err));
    CHECK(rc == -ENOENT && l == NULL && strstr(err, "'/dev/gpiochip987'"), "path: %d %s", rc, err);
}

/* A character device that is not a GPIO chip is a wrong path (an error), not a chip that has not
 * appeared yet: -ENOTTY with both libgpiod versions. */
CHECK_TEST(not_a_chip_is_enotty)
{
    struct gpio_line *l;
    char err[512];
    int rc = gpio_line_open(&l, "/dev/null", 0, SBFX_EDGE_RISING, "sbfx-test", err, sizeof(err));
    CHECK(rc == -ENOTTY && l == NULL && strstr(err, "GPIO chip '/dev/null'"), "%d %s", rc, err);
}

CHECK_TEST(calls_on_no_line)
{
    struct gpio_event ev[GPIO_KERNEL_FIFO];
    CHECK(gpio_line_fd(NULL) == -1, "fd");
    CHECK(gpio_line_read(NULL, ev, GPIO_KERNEL_FIFO) == -EINVAL, "read");
    CHECK(gpio_line_check(NULL) == -EINVAL, "check");
    CHECK(strcmp(gpio_line_chip_name(NULL), "?") == 0, "chip name");
    gpio_line_close(NULL);
}

int main(int argc, char **argv)
{
    return check_main_args(argc, argv);
}
