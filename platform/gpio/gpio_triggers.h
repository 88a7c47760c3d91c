/* GPIO lines that fire sbfx effects: each line's edges go through its debounce and rate limit
 * (trigger_filter.h) and a passing edge goes to the fire hook (sbfx-play's trigger queue) or sbfx_trigger.
 *
 * The lines come from the scene (sbfx_scene_gpio_triggers), the board profile and --gpio; the
 * player merges them into specs. Everything is requested at start: a line in use or an effect
 * the module does not have is an error naming them (the effects there are, too); a chip or a line
 * that is not there is logged and requested again with the back-off below, rendering goes on and
 * the trigger arms when it appears (an I/O board late at boot, a board profile tried on a PC;
 * docs/gpio.md). While running,
 * reads never block and allocate nothing. A chip that disappears (an I/O board unplugged, its
 * driver unbound) is noticed by a failed read or by the check once a second, logged once per line,
 * and its lines go quiet while the rest keep working; each lost line is requested again with
 * back-off (0.5 s doubling up to 8 s, silently: no log per attempt) and logged once when it is
 * back. Opening a line again allocates (libgpiod), only then. */
#ifndef SBFX_GPIO_TRIGGERS_H
#define SBFX_GPIO_TRIGGERS_H

#include <poll.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "gpio/gpio.h"
#include "sbfx.h"
#include "gpio/trigger_filter.h"

#define GPIO_TRIGGERS_MAX 32
#define GPIO_DEFAULT_DEBOUNCE_MS 30
#define GPIO_DEFAULT_MIN_INTERVAL_MS 250
#define GPIO_CHECK_INTERVAL_MS 1000 /* how often live lines' chips are checked */
#define GPIO_RETRY_MIN_MS 500       /* first retry after a loss; doubles up to */
#define GPIO_RETRY_MAX_MS 8000

struct gpio_trigger_spec {
    char chip[64];         /* "gpiochip0", "/dev/gpiochip0", a label or a number */
    int line;
    sbfx_edge edge;
    int debounce_ms;       /* quiet time before an edge fires */
    int min_interval_ms;   /* per-line rate limit */
    char effect[64];
    float position[3];
    const char *origin;    /* where the spec came from, for messages: "--gpio", "scene"... */
};

struct gpio_trigger_line {
    struct gpio_trigger_spec spec;
    struct gpio_line *gpio;      /* NULL while its chip is gone */
    struct trigger_filter filter;
    int64_t retry_at_ns;         /* while gone: the next attempt to request it again */
    int retry_ms;                /* the back-off after that attempt */
    bool seen;                   /* requested at least once (a loss, not an absence at start) */
};

struct gpio_trigger_counts {
    uint64_t edges;     /* events read from the kernel */
    uint64_t fired;     /* edges that passed the filters and started an effect */
    uint64_t filtered;  /* edges debounced or rate limited */
    uint64_t refused;   /* passed, but sbfx_trigger refused (pool full) */
    uint64_t overflows; /* reads that found the kernel's FIFO full (edges may be lost) */
    uint64_t losses;    /* lines whose chip went away */
    uint64_t returns;   /* lost lines requested again */
    uint64_t retries;   /* attempts to request a lost or absent line (the successful ones included) */
    uint64_t absent;    /* lines whose chip or line was not there at start */
    uint64_t appeared;  /* lines absent at start that were requested once they appeared */
};

struct gpio_triggers {
    struct gpio_trigger_line lines[GPIO_TRIGGERS_MAX];
    int count;
    struct gpio_trigger_counts counts;
    int64_t next_check_ns;
    /* Where a passing edge goes (set after open): the player's trigger queue, which returns false
     * when it refuses it (at_ns: the edge's time); NULL: sbfx_trigger at once. */
    bool (*fire)(const char *effect, const float position[3], int64_t at_ns, void *user);
    void *fire_user;
};

typedef void (*gpio_log_fn)(const char *message, void *user);

/* Requests every line; on failure nothing stays requested. fx checks the effect names. A line
 * whose chip or line is absent (-ENOENT, -ERANGE) is logged through log and left to
 * gpio_triggers_service's retries (first at now_ns + GPIO_RETRY_MIN_MS); not a failure. */
int gpio_triggers_open(struct gpio_triggers *t, const struct gpio_trigger_spec *specs, int count,
                       const sbfx *fx, int64_t now_ns, gpio_log_fn log, void *user, char *err,
                       size_t n);
/* Fills up to max pollfds (POLLIN) for the live lines; returns how many. */
int gpio_triggers_pollfds(const struct gpio_triggers *t, struct pollfd *fds, int max);
/* Reads whatever waits on every line and fires what passes (to the fire hook where it is set:
 * fx may be NULL then); checks the chips once a second and requests lost lines again when their
 * back-off is over; never blocks. now_ns: the monotonic clock now. Returns the number of effects
 * started (or queued). */
int gpio_triggers_service(struct gpio_triggers *t, sbfx *fx, int64_t now_ns, gpio_log_fn log,
                          void *user);
void gpio_triggers_close(struct gpio_triggers *t);

#endif
