/* gpio.h on libgpiod 1.6 (Debian 12): chip lookup, an edge-event request per line, reads from
 * the request's file descriptor into the caller's buffer (libgpiod 1.6 reads the kernel's
 * events into a stack array: nothing is allocated per read). */
#include "gpio/gpio.h"

#include <errno.h>
#include <fcntl.h>
#include <gpiod.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct gpio_line {
    struct gpiod_chip *chip;
    struct gpiod_line *line;
    int fd;
};

/* "gpiochip0 [label] (8 lines), ..." of every chip there is, for "no such chip" messages. */
static void list_chips(char *out, size_t n)
{
    out[0] = '\0';
    struct gpiod_chip_iter *iter = gpiod_chip_iter_new();
    if (!iter) {
        snprintf(out, n, "none found (%s)", strerror(errno));
        return;
    }
    struct gpiod_chip *chip;
    size_t used = 0;
    gpiod_foreach_chip(iter, chip) {
        int w = snprintf(out + used, n - used, "%s%s [%s] (%u lines)", used ? ", " : "",
                         gpiod_chip_name(chip), gpiod_chip_label(chip), gpiod_chip_num_lines(chip));
        if (w < 0 || (size_t)w >= n - used) break;
        used += (size_t)w;
    }
    gpiod_chip_iter_free(iter);
    if (!used) snprintf(out, n, "none in /dev");
}

static int open_chip(struct gpio_line *g, const char *chip, char *err, size_t n)
{
    g->chip = gpiod_chip_open_lookup(chip);
    if (g->chip) return 0;
    int rc = -errno;
    char chips[256];
    list_chips(chips, sizeof(chips));
    snprintf(err, n, "GPIO chip '%s': cannot open it (%s); chips: %s", chip, strerror(errno), chips);
    return rc == -ENODEV || rc == 0 ? -ENOENT : rc;
}

static int request_edges(struct gpiod_line *line, sbfx_edge edge, const char *consumer)
{
    switch (edge) {
    case SBFX_EDGE_FALLING: return gpiod_line_request_falling_edge_events(line, consumer);
    case SBFX_EDGE_BOTH: return gpiod_line_request_both_edges_events(line, consumer);
    default: return gpiod_line_request_rising_edge_events(line, consumer);
    }
}

static int request_line(struct gpio_line *g, int offset, sbfx_edge edge, const char *consumer,
                        char *err, size_t n)
{
    const char *name = gpiod_chip_name(g->chip);
    unsigned count = gpiod_chip_num_lines(g->chip);
    if (offset < 0 || (unsigned)offset >= count) {
        snprintf(err, n, "GPIO %s: no line %d (the chip has %u lines, 0..%u)", name, offset, count,
                 count ? count - 1 : 0);
        return -ERANGE;
    }
    g->line = gpiod_chip_get_line(g->chip, (unsigned)offset);
    if (!g->line) {
        int rc = -errno;
        snprintf(err, n, "GPIO %s line %d: gpiod_chip_get_line: %s", name, offset, strerror(errno));
        return rc;
    }
    if (request_edges(g->line, edge, consumer) != 0) {
        int rc = -errno;
        const char *user = gpiod_line_consumer(g->line);
        if (rc == -EBUSY)
            snprintf(err, n, "GPIO %s line %d is in use by '%s'", name, offset, user ? user : "?");
        else
            snprintf(err, n, "GPIO %s line %d: requesting edge events: %s", name, offset,
                     strerror(errno));
        g->line = NULL;
        return rc;
    }
    return 0;
}

/* The loop polls the descriptor, but a read must not block even if it is called anyway. */
static int make_nonblocking(struct gpio_line *g, int offset, char *err, size_t n)
{
    g->fd = gpiod_line_event_get_fd(g->line);
    int flags = g->fd >= 0 ? fcntl(g->fd, F_GETFL) : -1;
    if (flags < 0 || fcntl(g->fd, F_SETFL, flags | O_NONBLOCK) != 0) {
        int rc = -errno;
        snprintf(err, n, "GPIO %s line %d: event descriptor: %s", gpiod_chip_name(g->chip), offset,
                 strerror(errno));
        return rc;
    }
    return 0;
}

int gpio_line_open(struct gpio_line **out, const char *chip, int line, sbfx_edge edge,
                   const char *consumer, char *err, size_t n)
{
    *out = NULL;
    struct gpio_line *g = calloc(1, sizeof(*g));
    if (!g) {
        snprintf(err, n, "GPIO %s line %d: out of memory", chip, line);
        return -ENOMEM;
    }
    g->fd = -1;
    int rc = open_chip(g, chip, err, n);
    if (rc == 0) rc = request_line(g, line, edge, consumer, err, n);
    if (rc == 0) rc = make_nonblocking(g, line, err, n);
    if (rc) {
        gpio_line_close(g);
        return rc;
    }
    *out = g;
    return 0;
}

int gpio_line_fd(const struct gpio_line *line)
{
    return line ? line->fd : -1;
}

const char *gpio_line_chip_name(const struct gpio_line *line)
{
    return line && line->chip ? gpiod_chip_name(line->chip) : "?";
}

int gpio_line_read(struct gpio_line *line, struct gpio_event *events, int max)
{
    struct gpiod_line_event raw[GPIO_KERNEL_FIFO];
    if (max > GPIO_KERNEL_FIFO) max = GPIO_KERNEL_FIFO;
    if (!line || line->fd < 0 || max < 1) return -EINVAL;
    int count = gpiod_line_event_read_fd_multiple(line->fd, raw, (unsigned)max);
    if (count < 0) return errno == EAGAIN || errno == EWOULDBLOCK ? 0 : -errno;
    for (int i = 0; i < count; i++) {
        events[i].timestamp_ns = (int64_t)raw[i].ts.tv_sec * 1000000000 + raw[i].ts.tv_nsec;
        events[i].rising = raw[i].event_type == GPIOD_LINE_EVENT_RISING_EDGE;
    }
    return count;
}

int gpio_line_check(struct gpio_line *line)
{
    if (!line || !line->line) return -EINVAL;
    /* GPIO_GET_LINEINFO_IOCTL on the chip's descriptor: the kernel fails every chip ioctl with
     * ENODEV once the chip is gone */
    if (gpiod_line_update(line->line) == 0) return 0;
    return errno == ENODEV || errno == ENXIO ? -ENODEV : -errno;
}

void gpio_line_close(struct gpio_line *line)
{
    if (!line) return;
    if (line->line) gpiod_line_release(line->line);
    if (line->chip) gpiod_chip_close(line->chip);
    free(line);
}
