/* The GPIO backend (platform/gpio/gpio.h) against a real gpio-sim chip, in the VM tier: built once
 * against libgpiod 1.6 and once against 2.x (tools/libgpiod2.sh), the same checks for both.
 *
 *   gpio_backend NAME CHIP LABEL SYSFS CONFIGFS
 *
 * NAME prefixes the result lines ("ok - vm/NAME/lookup-label"); CHIP is the chip's name
 * ("gpiochip1"), LABEL its label, SYSFS its folder with sim_gpioN/pull, CONFIGFS the gpio-sim
 * device's configfs folder (its "live" switch: the chip is taken away and created again at the
 * end). Lines 1-5 of the chip are used. Exit status 1 if a check failed. */
#include <errno.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "gpio/gpio.h"

static const char *name, *chip, *label, *sysfs, *configfs;
static int failures;

static void result(bool ok, const char *check, const char *fmt, ...)
{
    if (ok) {
        printf("ok - vm/%s/%s\n", name, check);
    } else {
        char why[512];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(why, sizeof(why), fmt, ap);
        va_end(ap);
        printf("not ok - vm/%s/%s: %s\n", name, check, why);
        failures++;
    }
    fflush(stdout);
}

static int write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f) return -1;
    int rc = fputs(text, f) < 0 ? -1 : 0;
    return fclose(f) != 0 ? -1 : rc;
}

static void pull(int line, bool up)
{
    char path[512];
    snprintf(path, sizeof(path), "%s/sim_gpio%d/pull", sysfs, line);
    if (write_text(path, up ? "pull-up" : "pull-down") != 0) fprintf(stderr, "# %s: %s\n", path, strerror(errno));
}

static int64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

/* Reads what arrives on the line within ms (polling its descriptor) into ev; their count. */
static int collect(struct gpio_line *l, struct gpio_event *ev, int max, int ms)
{
    int count = 0;
    int64_t end = now_ns() + (int64_t)ms * 1000000;
    while (count < max && now_ns() < end) {
        struct pollfd p = {.fd = gpio_line_fd(l), .events = POLLIN};
        if (poll(&p, 1, 50) <= 0) continue;
        int got = gpio_line_read(l, ev + count, max - count);
        if (got < 0) return got;
        count += got;
    }
    return count;
}

static void check_lookup(void)
{
    char number[16], path[64], err[512];
    snprintf(number, sizeof(number), "%s", chip + strlen("gpiochip"));
    snprintf(path, sizeof(path), "/dev/%s", chip);
    const char *forms[][2] = {{"name", chip}, {"path", path}, {"label", label}, {"number", number}};
    for (int i = 0; i < 4; i++) {
        struct gpio_line *l;
        char check[32];
        snprintf(check, sizeof(check), "lookup-%s", forms[i][0]);
        int rc = gpio_line_open(&l, forms[i][1], 1, SBFX_EDGE_RISING, "sbfx-test", err, sizeof(err));
        result(rc == 0 && strcmp(gpio_line_chip_name(l), chip) == 0 && gpio_line_fd(l) >= 0, check,
               "'%s': %d %s (chip name '%s')", forms[i][1], rc, rc ? err : "", rc ? "" : gpio_line_chip_name(l));
        if (rc == 0) gpio_line_close(l);
    }
}

static void check_errors(void)
{
    struct gpio_line *l, *holder;
    char err[512], want[128];
    int rc = gpio_line_open(&l, "sbfx-no-such-chip", 1, SBFX_EDGE_RISING, "sbfx-test", err, sizeof(err));
    snprintf(want, sizeof(want), "%s [%s] (8 lines)", chip, label);
    result(rc == -ENOENT && strstr(err, "sbfx-no-such-chip") && strstr(err, want), "missing-chip",
           "%d %s (expected -ENOENT listing '%s')", rc, err, want);
    rc = gpio_line_open(&l, chip, 99, SBFX_EDGE_RISING, "sbfx-test", err, sizeof(err));
    result(rc == -ERANGE && strstr(err, "no line 99 (the chip has 8 lines, 0..7)"), "missing-line", "%d %s", rc, err);
    rc = gpio_line_open(&l, "/dev/null", 1, SBFX_EDGE_RISING, "sbfx-test", err, sizeof(err));
    result(rc == -ENOTTY, "not-a-chip", "/dev/null: %d %s (expected -ENOTTY)", rc, err);
    if (gpio_line_open(&holder, chip, 1, SBFX_EDGE_RISING, "sbfx-holder", err, sizeof(err)) != 0) {
        result(false, "busy-line", "holding line 1: %s", err);
        return;
    }
    rc = gpio_line_open(&l, label, 1, SBFX_EDGE_RISING, "sbfx-test", err, sizeof(err));
    snprintf(want, sizeof(want), "GPIO %s line 1 is in use by 'sbfx-holder'", chip);
    result(rc == -EBUSY && strstr(err, want), "busy-line", "%d %s", rc, err);
    gpio_line_close(holder);
}

/* Edges of each kind: both (rising then falling, kernel timestamps in order, on the monotonic
 * clock), rising only, falling only; an empty line reads 0 without blocking. */
static void check_edges(void)
{
    const struct { int line; sbfx_edge edge; const char *check; bool first_rising, second_rising; } cases[] = {
        {2, SBFX_EDGE_BOTH, "edges-both", true, false},
        {3, SBFX_EDGE_RISING, "edges-rising", true, true},
        {4, SBFX_EDGE_FALLING, "edges-falling", false, false},
    };
    for (int c = 0; c < 3; c++) {
        struct gpio_line *l;
        struct gpio_event ev[GPIO_KERNEL_FIFO];
        char err[512];
        if (gpio_line_open(&l, chip, cases[c].line, cases[c].edge, "sbfx-test", err, sizeof(err)) != 0) {
            result(false, cases[c].check, "%s", err);
            continue;
        }
        int idle = gpio_line_read(l, ev, GPIO_KERNEL_FIFO);
        int64_t t0 = now_ns();
        int presses = cases[c].edge == SBFX_EDGE_BOTH ? 1 : 2;
        for (int i = 0; i < presses; i++) { /* 50 ms apart: gpio-sim's simulated interrupt merges
                                               * edges that come faster (one event, the last level) */
            pull(cases[c].line, true);
            usleep(50000);
            pull(cases[c].line, false);
            usleep(50000);
        }
        int got = collect(l, ev, GPIO_KERNEL_FIFO, 2000);
        int64_t t1 = now_ns();
        bool ok = idle == 0 && got == 2 && ev[0].rising == cases[c].first_rising &&
                  ev[1].rising == cases[c].second_rising && ev[0].timestamp_ns >= t0 &&
                  ev[1].timestamp_ns >= ev[0].timestamp_ns && ev[1].timestamp_ns <= t1;
        result(ok, cases[c].check, "idle read %d, %d events (expected 2): %s %lld, %s %lld ns (window %lld..%lld)",
               idle, got, got > 0 && ev[0].rising ? "rising" : "falling", got > 0 ? (long long)ev[0].timestamp_ns : 0,
               got > 1 && ev[1].rising ? "rising" : "falling", got > 1 ? (long long)ev[1].timestamp_ns : 0,
               (long long)t0, (long long)t1);
        gpio_line_close(l);
    }
}

/* 40 edges before anything reads: the kernel keeps GPIO_KERNEL_FIFO of them with either libgpiod
 * (the trigger code counts a full batch as an overflow). */
static void check_fifo(void)
{
    struct gpio_line *l;
    struct gpio_event ev[GPIO_KERNEL_FIFO];
    char err[512];
    if (gpio_line_open(&l, chip, 5, SBFX_EDGE_BOTH, "sbfx-test", err, sizeof(err)) != 0) {
        result(false, "kernel-fifo", "%s", err);
        return;
    }
    for (int i = 0; i < 20; i++) { /* 20 ms apart, so that gpio-sim does not merge them */
        pull(5, true);
        usleep(20000);
        pull(5, false);
        usleep(20000);
    }
    usleep(200000);
    int first = gpio_line_read(l, ev, GPIO_KERNEL_FIFO), more = 0, got;
    while ((got = gpio_line_read(l, ev, GPIO_KERNEL_FIFO)) > 0) more += got;
    result(first == GPIO_KERNEL_FIFO && more == 0, "kernel-fifo",
           "40 edges unread: the first read gave %d, then %d more (expected %d, then 0)", first, more,
           GPIO_KERNEL_FIFO);
    gpio_line_close(l);
}

/* The chip taken away under a requested line: the check says -ENODEV; the chip comes back. */
static void check_loss(void)
{
    struct gpio_line *l;
    struct gpio_event ev[GPIO_KERNEL_FIFO];
    char err[512], live[512];
    snprintf(live, sizeof(live), "%s/live", configfs);
    if (gpio_line_open(&l, label, 2, SBFX_EDGE_BOTH, "sbfx-test", err, sizeof(err)) != 0) {
        result(false, "chip-loss", "%s", err);
        return;
    }
    int before = gpio_line_check(l);
    int down = write_text(live, "0");
    int after = gpio_line_check(l);
    int read = gpio_line_read(l, ev, GPIO_KERNEL_FIFO);
    gpio_line_close(l);
    int up = write_text(live, "1");
    result(before == 0 && down == 0 && after == -ENODEV && read <= 0 && up == 0, "chip-loss",
           "check %d before, %d after the chip went (expected -ENODEV); a read then %d; live 0/1: %d/%d",
           before, after, read, down, up);
}

int main(int argc, char **argv)
{
    if (argc != 6) {
        fprintf(stderr, "usage: gpio_backend NAME CHIP LABEL SYSFS CONFIGFS\n");
        return 2;
    }
    name = argv[1], chip = argv[2], label = argv[3], sysfs = argv[4], configfs = argv[5];
    check_lookup();
    check_errors();
    check_edges();
    check_fifo();
    check_loss();
    return failures ? 1 : 0;
}
