/* GPIO input lines that deliver edge events: the contract the trigger code uses, so that the
 * libgpiod backend can change (gpio_gpiod1.c: libgpiod 1.6, Debian 12; a gpio_gpiod2.c for the
 * 2.x API would fill the same functions) without touching its users.
 *
 * A line is requested for edge events (rising, falling or both) under a consumer name; its file
 * descriptor is polled by the caller's loop (POLLIN: events are waiting) and gpio_line_read()
 * never blocks. Timestamps are the kernel's, in nanoseconds of CLOCK_MONOTONIC.
 *
 * Errors: 0 or a negative errno, with a message in err that names the chip and the line:
 *   -ENOENT  no such chip (the message lists the chips there are)
 *   -ERANGE  the chip has no such line (the message gives the chip's line count)
 *   -EBUSY   the line is used by another consumer (named)
 *   others   what the kernel said, with the call that failed */
#ifndef SBFX_GPIO_H
#define SBFX_GPIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sbfx.h" /* sbfx_edge */

#define GPIO_KERNEL_FIFO 16 /* events the kernel holds per line (uAPI v1); more are dropped */

struct gpio_line;

struct gpio_event {
    int64_t timestamp_ns;
    bool rising;
};

/* chip: a name ("gpiochip0"), a path ("/dev/gpiochip0"), a label or a number. */
int gpio_line_open(struct gpio_line **out, const char *chip, int line, sbfx_edge edge,
                   const char *consumer, char *err, size_t n);
int gpio_line_fd(const struct gpio_line *line);
/* The chip's name as the kernel knows it ("gpiochip0"). */
const char *gpio_line_chip_name(const struct gpio_line *line);
/* Reads up to max (at most GPIO_KERNEL_FIFO) waiting events: their count, 0 when none wait,
 * or a negative errno (-ENODEV when the chip went away). */
int gpio_line_read(struct gpio_line *line, struct gpio_event *events, int max);
/* 0 while the line's chip is there, -ENODEV once it went away (a chip removed from under a
 * requested line does not always make its event reads fail: the uAPI v1 event descriptor of
 * Linux 6.1 just stays quiet). One ioctl on the chip, nothing allocated. */
int gpio_line_check(struct gpio_line *line);
void gpio_line_close(struct gpio_line *line);

#endif
