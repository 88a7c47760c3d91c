/* GPIO lines -> debounce and rate limit -> sbfx_trigger. */
#include "gpio/gpio_triggers.h"

#include "gpio/effect_names.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#define CONSUMER "sbfx-play"
#define CLOCK_SKEW_NS INT64_C(10000000000) /* an event 10 s off "now" is on another clock */

static int check_spec(const struct gpio_trigger_spec *s, const struct gpio_triggers *t,
                      const sbfx *fx, char *err, size_t n)
{
    if (!sbfx_has_effect(fx, s->effect)) {
        char names[256];
        snprintf(err, n, "%s: GPIO %s line %d fires '%s', but the scene has no effect of that name "
                 "(its effects: %s)", s->origin, s->chip, s->line, s->effect,
                 effect_names(fx, names, sizeof(names)));
        return -EINVAL;
    }
    for (int i = 0; i < t->count; i++) {
        const struct gpio_trigger_spec *o = &t->lines[i].spec;
        if (o->line == s->line && strcmp(o->chip, s->chip) == 0) {
            snprintf(err, n, "%s: GPIO %s line %d is already a trigger (from %s)", s->origin,
                     s->chip, s->line, o->origin);
            return -EINVAL;
        }
    }
    return 0;
}

/* A chip or line that is not there (yet): logged, and requested with back-off like a lost one. */
static void absent_at_start(struct gpio_triggers *t, struct gpio_trigger_line *l, const char *why,
                            int64_t now_ns, gpio_log_fn log, void *user)
{
    char msg[512];
    snprintf(msg, sizeof(msg), "%s: %s; its trigger is off until it appears (requested again with "
             "back-off)", l->spec.origin, why);
    if (log) log(msg, user);
    l->gpio = NULL;
    l->retry_ms = GPIO_RETRY_MIN_MS;
    l->retry_at_ns = now_ns + (int64_t)l->retry_ms * 1000000;
    t->counts.absent++;
}

static int open_one(struct gpio_triggers *t, const struct gpio_trigger_spec *s, const sbfx *fx,
                    int64_t now_ns, gpio_log_fn log, void *user, char *err, size_t n)
{
    int rc = check_spec(s, t, fx, err, n);
    if (rc) return rc;
    struct gpio_trigger_line *l = &t->lines[t->count];
    memset(l, 0, sizeof(*l));
    l->spec = *s;
    char why[384];
    rc = gpio_line_open(&l->gpio, s->chip, s->line, s->edge, CONSUMER, why, sizeof(why));
    if (rc == -ENOENT || rc == -ERANGE) {
        absent_at_start(t, l, why, now_ns, log, user);
    } else if (rc) {
        snprintf(err, n, "%s: %s", s->origin, why);
        return rc;
    } else {
        l->seen = true;
    }
    trigger_filter_init(&l->filter, s->debounce_ms, s->min_interval_ms);
    t->count++;
    return 0;
}

int gpio_triggers_open(struct gpio_triggers *t, const struct gpio_trigger_spec *specs, int count,
                       const sbfx *fx, int64_t now_ns, gpio_log_fn log, void *user, char *err,
                       size_t n)
{
    memset(t, 0, sizeof(*t));
    if (count > GPIO_TRIGGERS_MAX) {
        snprintf(err, n, "%d GPIO triggers, at most %d", count, GPIO_TRIGGERS_MAX);
        return -EINVAL;
    }
    for (int i = 0; i < count; i++) {
        int rc = open_one(t, &specs[i], fx, now_ns, log, user, err, n);
        if (rc) {
            gpio_triggers_close(t);
            return rc;
        }
    }
    return 0;
}

int gpio_triggers_pollfds(const struct gpio_triggers *t, struct pollfd *fds, int max)
{
    int used = 0;
    for (int i = 0; i < t->count && used < max; i++) {
        int fd = gpio_line_fd(t->lines[i].gpio);
        if (fd < 0) continue;
        fds[used++] = (struct pollfd){.fd = fd, .events = POLLIN};
    }
    return used;
}

static void lose_line(struct gpio_trigger_line *l, int rc, int64_t now_ns,
                      struct gpio_trigger_counts *counts, gpio_log_fn log, void *user)
{
    char msg[256];
    snprintf(msg, sizeof(msg), "GPIO %s line %d: %s (%s); its trigger is off, requesting it again "
             "with back-off", l->spec.chip, l->spec.line,
             rc == -ENODEV ? "the chip went away" : "reading events failed", strerror(-rc));
    if (log) log(msg, user);
    gpio_line_close(l->gpio);
    l->gpio = NULL;
    l->retry_ms = GPIO_RETRY_MIN_MS;
    l->retry_at_ns = now_ns + (int64_t)l->retry_ms * 1000000;
    counts->losses++;
}

/* One attempt to request a lost line again; quiet unless it worked. */
static void retry_line(struct gpio_trigger_line *l, int64_t now_ns,
                       struct gpio_trigger_counts *counts, gpio_log_fn log, void *user)
{
    char why[384];
    counts->retries++;
    if (gpio_line_open(&l->gpio, l->spec.chip, l->spec.line, l->spec.edge, CONSUMER, why,
                       sizeof(why)) != 0) {
        l->gpio = NULL;
        l->retry_ms = l->retry_ms * 2 < GPIO_RETRY_MAX_MS ? l->retry_ms * 2 : GPIO_RETRY_MAX_MS;
        l->retry_at_ns = now_ns + (int64_t)l->retry_ms * 1000000;
        return;
    }
    char msg[256];
    if (l->seen) {
        counts->returns++;
        snprintf(msg, sizeof(msg), "GPIO %s line %d is back (%s): its trigger is on again",
                 l->spec.chip, l->spec.line, gpio_line_chip_name(l->gpio));
    } else {
        counts->appeared++;
        snprintf(msg, sizeof(msg), "GPIO %s line %d appeared (%s): its trigger is on",
                 l->spec.chip, l->spec.line, gpio_line_chip_name(l->gpio));
    }
    l->seen = true;
    if (log) log(msg, user);
}

/* Once a second: is every live line's chip still there; is a lost line due for a retry. */
static void check_lines(struct gpio_triggers *t, int64_t now_ns, gpio_log_fn log, void *user)
{
    bool check = now_ns >= t->next_check_ns;
    if (check) t->next_check_ns = now_ns + (int64_t)GPIO_CHECK_INTERVAL_MS * 1000000;
    for (int i = 0; i < t->count; i++) {
        struct gpio_trigger_line *l = &t->lines[i];
        if (!l->gpio) {
            if (now_ns >= l->retry_at_ns) retry_line(l, now_ns, &t->counts, log, user);
            continue;
        }
        int rc = check ? gpio_line_check(l->gpio) : 0;
        if (rc == -ENODEV) lose_line(l, rc, now_ns, &t->counts, log, user);
    }
}

static int fire(struct gpio_triggers *t, struct gpio_trigger_line *l, sbfx *fx, int64_t at_ns)
{
    bool taken = t->fire ? t->fire(l->spec.effect, l->spec.position, at_ns, t->fire_user)
                         : sbfx_trigger(fx, l->spec.effect, l->spec.position) == SBFX_OK;
    if (!taken) {
        t->counts.refused++;
        return 0;
    }
    t->counts.fired++;
    return 1;
}

/* One batch of events; true when the batch filled the kernel's FIFO (there may be more). */
static int service_batch(struct gpio_triggers *t, struct gpio_trigger_line *l, sbfx *fx,
                         int64_t now_ns, int *fired)
{
    struct gpio_event events[GPIO_KERNEL_FIFO];
    int count = gpio_line_read(l->gpio, events, GPIO_KERNEL_FIFO);
    if (count <= 0) return count;
    t->counts.edges += (uint64_t)count;
    for (int i = 0; i < count; i++) {
        int64_t ts = events[i].timestamp_ns;
        if (ts > now_ns + CLOCK_SKEW_NS || ts < now_ns - CLOCK_SKEW_NS) ts = now_ns;
        if (trigger_filter_edge(&l->filter, ts)) *fired += fire(t, l, fx, ts);
        else t->counts.filtered++;
    }
    if (count < GPIO_KERNEL_FIFO) return 0;
    /* A full FIFO may have dropped edges since its last event: not quiet until now. */
    t->counts.overflows++;
    trigger_filter_busy_until(&l->filter, now_ns);
    return 1;
}

int gpio_triggers_service(struct gpio_triggers *t, sbfx *fx, int64_t now_ns, gpio_log_fn log,
                          void *user)
{
    int fired = 0;
    for (int i = 0; i < t->count; i++) {
        struct gpio_trigger_line *l = &t->lines[i];
        for (int batch = 0; l->gpio && batch < 64; batch++) {
            int rc = service_batch(t, l, fx, now_ns, &fired);
            if (rc < 0) lose_line(l, rc, now_ns, &t->counts, log, user);
            if (rc <= 0) break;
        }
    }
    check_lines(t, now_ns, log, user);
    return fired;
}

void gpio_triggers_close(struct gpio_triggers *t)
{
    for (int i = 0; i < t->count; i++) {
        gpio_line_close(t->lines[i].gpio);
        t->lines[i].gpio = NULL;
    }
    t->count = 0;
}
