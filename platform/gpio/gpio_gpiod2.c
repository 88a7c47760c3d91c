/* gpio.h on libgpiod 2.x (Debian 13, Buildroot, Yocto): the same contract as gpio_gpiod1.c
 * (libgpiod 1.6), chosen by the build from pkg-config's libgpiod version (docs/gpio.md).
 *
 * libgpiod 2 opens chips by path only: the lookup by name, path, label or number that 1.6's
 * gpiod_chip_open_lookup() did is done here, in the same order. Everything is allocated at open
 * (the chip, the request, an edge-event buffer of GPIO_KERNEL_FIFO events); a read fills that
 * buffer from the request's descriptor and allocates nothing, and the chip check is one ioctl. */
#include "gpio/gpio.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <gpiod.h>
#include <linux/gpio.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>

struct gpio_line {
    struct gpiod_chip *chip;
    struct gpiod_line_request *request;
    struct gpiod_edge_event_buffer *events;
    char name[32]; /* "gpiochip0" */
    int fd;
};

/* ---- chips ---------------------------------------------------------------------------------- */

static int is_chip_entry(const struct dirent *d)
{
    return strncmp(d->d_name, "gpiochip", 8) == 0;
}

/* Calls visit(path, info, user) for every chip in /dev in name order until it returns true. */
static void each_chip(bool (*visit)(const char *, struct gpiod_chip_info *, void *), void *user)
{
    struct dirent **names;
    int count = scandir("/dev", &names, is_chip_entry, alphasort);
    bool done = false;
    for (int i = 0; i < count; i++) {
        char path[288];
        snprintf(path, sizeof(path), "/dev/%s", names[i]->d_name);
        struct gpiod_chip *chip = !done && gpiod_is_gpiochip_device(path) ? gpiod_chip_open(path) : NULL;
        struct gpiod_chip_info *info = chip ? gpiod_chip_get_info(chip) : NULL;
        if (info) done = visit(path, info, user);
        if (info) gpiod_chip_info_free(info);
        if (chip) gpiod_chip_close(chip);
        free(names[i]);
    }
    if (count >= 0) free(names);
}

struct chip_list {
    char *out;
    size_t n, used;
};

static bool list_one(const char *path, struct gpiod_chip_info *info, void *user)
{
    (void)path;
    struct chip_list *l = user;
    int w = snprintf(l->out + l->used, l->n - l->used, "%s%s [%s] (%zu lines)", l->used ? ", " : "",
                     gpiod_chip_info_get_name(info), gpiod_chip_info_get_label(info),
                     gpiod_chip_info_get_num_lines(info));
    if (w < 0 || (size_t)w >= l->n - l->used) return true;
    l->used += (size_t)w;
    return false;
}

/* "gpiochip0 [label] (8 lines), ..." of every chip there is, for "no such chip" messages. */
static void list_chips(char *out, size_t n)
{
    struct chip_list l = {out, n, 0};
    out[0] = '\0';
    each_chip(list_one, &l);
    if (!l.used) snprintf(out, n, "none in /dev");
}

struct label_search {
    const char *label;
    char path[288];
};

static bool match_label(const char *path, struct gpiod_chip_info *info, void *user)
{
    struct label_search *s = user;
    if (strcmp(gpiod_chip_info_get_label(info), s->label) != 0) return false;
    snprintf(s->path, sizeof(s->path), "%s", path);
    return true;
}

static bool all_digits(const char *s)
{
    if (!*s) return false;
    for (; *s; s++)
        if (!isdigit((unsigned char)*s)) return false;
    return true;
}

/* 1.6's gpiod_chip_open_lookup(): a number ("3": /dev/gpiochip3), else a label, else a path
 * ("/dev/...") or a name in /dev. */
static struct gpiod_chip *lookup_chip(const char *chip)
{
    char path[288];
    if (all_digits(chip)) {
        snprintf(path, sizeof(path), "/dev/gpiochip%s", chip);
        return gpiod_chip_open(path);
    }
    struct label_search s = {chip, ""};
    each_chip(match_label, &s);
    if (s.path[0]) return gpiod_chip_open(s.path);
    if (strncmp(chip, "/dev/", 5) == 0) return gpiod_chip_open(chip);
    snprintf(path, sizeof(path), "/dev/%s", chip);
    return gpiod_chip_open(path);
}

static int open_chip(struct gpio_line *g, const char *chip, char *err, size_t n)
{
    g->chip = lookup_chip(chip);
    if (g->chip) return 0;
    /* libgpiod 2 says ENODEV for a character device that is not a GPIO chip, 1.6 ENOTTY: kept
     * as 1.6 has it (a wrong path is an error; ENODEV would read as a chip not there yet) */
    int rc = errno == ENODEV ? -ENOTTY : -errno;
    char chips[256];
    list_chips(chips, sizeof(chips));
    snprintf(err, n, "GPIO chip '%s': cannot open it (%s); chips: %s", chip, strerror(-rc), chips);
    return rc == -ENODEV || rc == 0 ? -ENOENT : rc;
}

/* The chip's name and its line count (0 if the kernel would not say). */
static unsigned chip_lines(struct gpio_line *g)
{
    struct gpiod_chip_info *info = gpiod_chip_get_info(g->chip);
    if (!info) return 0;
    snprintf(g->name, sizeof(g->name), "%s", gpiod_chip_info_get_name(info));
    unsigned count = (unsigned)gpiod_chip_info_get_num_lines(info);
    gpiod_chip_info_free(info);
    return count;
}

/* ---- the request ------------------------------------------------------------------------------ */

static enum gpiod_line_edge edge_detection(sbfx_edge edge)
{
    switch (edge) {
    case SBFX_EDGE_FALLING: return GPIOD_LINE_EDGE_FALLING;
    case SBFX_EDGE_BOTH: return GPIOD_LINE_EDGE_BOTH;
    default: return GPIOD_LINE_EDGE_RISING;
    }
}

/* Input with edge detection on one offset, under consumer, with a kernel buffer of
 * GPIO_KERNEL_FIFO events (what uAPI v1 holds per line: the same overflow as with 1.6). */
static struct gpiod_line_request *request_edges(struct gpiod_chip *chip, unsigned offset,
                                                sbfx_edge edge, const char *consumer)
{
    struct gpiod_line_settings *settings = gpiod_line_settings_new();
    struct gpiod_line_config *line_cfg = gpiod_line_config_new();
    struct gpiod_request_config *req_cfg = gpiod_request_config_new();
    struct gpiod_line_request *request = NULL;
    if (settings && line_cfg && req_cfg &&
        gpiod_line_settings_set_direction(settings, GPIOD_LINE_DIRECTION_INPUT) == 0 &&
        gpiod_line_settings_set_edge_detection(settings, edge_detection(edge)) == 0 &&
        gpiod_line_config_add_line_settings(line_cfg, &offset, 1, settings) == 0) {
        gpiod_request_config_set_consumer(req_cfg, consumer);
        gpiod_request_config_set_event_buffer_size(req_cfg, GPIO_KERNEL_FIFO);
        request = gpiod_chip_request_lines(chip, req_cfg, line_cfg);
    }
    int saved = errno;
    gpiod_request_config_free(req_cfg);
    gpiod_line_config_free(line_cfg);
    gpiod_line_settings_free(settings);
    errno = saved;
    return request;
}

/* Who holds a line that is busy (allocates: only on this error path). */
static void busy_message(struct gpio_line *g, int offset, char *err, size_t n)
{
    struct gpiod_line_info *info = gpiod_chip_get_line_info(g->chip, (unsigned)offset);
    const char *user = info ? gpiod_line_info_get_consumer(info) : NULL;
    snprintf(err, n, "GPIO %s line %d is in use by '%s'", g->name, offset, user ? user : "?");
    if (info) gpiod_line_info_free(info);
}

static int request_line(struct gpio_line *g, int offset, sbfx_edge edge, const char *consumer,
                        char *err, size_t n)
{
    unsigned count = chip_lines(g);
    if (offset < 0 || (unsigned)offset >= count) {
        snprintf(err, n, "GPIO %s: no line %d (the chip has %u lines, 0..%u)", g->name, offset, count,
                 count ? count - 1 : 0);
        return -ERANGE;
    }
    g->request = request_edges(g->chip, (unsigned)offset, edge, consumer);
    if (g->request) return 0;
    int rc = errno ? -errno : -EIO;
    if (rc == -EBUSY)
        busy_message(g, offset, err, n);
    else
        snprintf(err, n, "GPIO %s line %d: requesting edge events: %s", g->name, offset, strerror(-rc));
    return rc;
}

/* The loop polls the descriptor, but a read must not block even if it is called anyway. */
static int make_nonblocking(struct gpio_line *g, int offset, char *err, size_t n)
{
    g->events = gpiod_edge_event_buffer_new(GPIO_KERNEL_FIFO);
    g->fd = gpiod_line_request_get_fd(g->request);
    int flags = g->fd >= 0 && g->events ? fcntl(g->fd, F_GETFL) : -1;
    if (flags < 0 || fcntl(g->fd, F_SETFL, flags | O_NONBLOCK) != 0) {
        int rc = errno ? -errno : -ENOMEM;
        snprintf(err, n, "GPIO %s line %d: event descriptor: %s", g->name, offset, strerror(-rc));
        return rc;
    }
    return 0;
}

/* ---- gpio.h ----------------------------------------------------------------------------------- */

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
    snprintf(g->name, sizeof(g->name), "%s", chip);
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
    return line && line->chip ? line->name : "?";
}

int gpio_line_read(struct gpio_line *line, struct gpio_event *events, int max)
{
    if (max > GPIO_KERNEL_FIFO) max = GPIO_KERNEL_FIFO;
    if (!line || !line->request || max < 1) return -EINVAL;
    int count = gpiod_line_request_read_edge_events(line->request, line->events, (size_t)max);
    if (count < 0) return errno == EAGAIN || errno == EWOULDBLOCK ? 0 : -errno;
    for (int i = 0; i < count; i++) {
        struct gpiod_edge_event *e = gpiod_edge_event_buffer_get_event(line->events, (unsigned long)i);
        events[i].timestamp_ns = (int64_t)gpiod_edge_event_get_timestamp_ns(e);
        events[i].rising = gpiod_edge_event_get_event_type(e) == GPIOD_EDGE_EVENT_RISING_EDGE;
    }
    return count;
}

int gpio_line_check(struct gpio_line *line)
{
    if (!line || !line->chip) return -EINVAL;
    /* GPIO_GET_CHIPINFO_IOCTL on the chip's descriptor, straight to the kernel: the kernel fails
     * every chip ioctl with ENODEV once the chip is gone, and libgpiod's own info call would
     * allocate (this runs once a second in the render loop) */
    struct gpiochip_info info;
    if (ioctl(gpiod_chip_get_fd(line->chip), GPIO_GET_CHIPINFO_IOCTL, &info) == 0) return 0;
    return errno == ENODEV || errno == ENXIO ? -ENODEV : -errno;
}

void gpio_line_close(struct gpio_line *line)
{
    if (!line) return;
    if (line->request) gpiod_line_request_release(line->request);
    if (line->events) gpiod_edge_event_buffer_free(line->events);
    if (line->chip) gpiod_chip_close(line->chip);
    free(line);
}
