/* GPIO trigger lines whose chip goes away and comes back (platform/gpio/gpio_triggers.c) against a
 * fake gpio.h backend defined here: the loss is logged once, the other line keeps firing, the
 * lost line is requested again with back-off (no attempt per frame, no log per attempt) and
 * fires again once it is back. sbfx_has_effect and sbfx_trigger are stubs counting triggers. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "gpio/gpio_triggers.h"

#define MS INT64_C(1000000)

/* ---- the fake chips: "a" and "b", 8 lines each; a chip can be unplugged ------------------ */

struct gpio_line {
    char chip;
    int line;
    int pending;      /* rising edges waiting */
    int64_t ts;
};

static bool chip_present[2] = {true, true};
static struct gpio_line *opened[2][8];
static int open_calls, check_calls, triggers, logs, loss_logs, back_logs;

static int chip_index(const char *chip)
{
    return chip[0] == 'a' ? 0 : chip[0] == 'b' ? 1 : -1;
}

int gpio_line_open(struct gpio_line **out, const char *chip, int line, sbfx_edge edge,
                   const char *consumer, char *err, size_t n)
{
    (void)edge, (void)consumer;
    open_calls++;
    *out = NULL;
    int c = chip_index(chip);
    if (c < 0 || !chip_present[c]) {
        snprintf(err, n, "GPIO chip '%s': cannot open it", chip);
        return -ENOENT;
    }
    struct gpio_line *l = calloc(1, sizeof(*l));
    l->chip = chip[0];
    l->line = line;
    opened[c][line] = l;
    *out = l;
    return 0;
}

int gpio_line_fd(const struct gpio_line *line) { return line ? 100 + line->line : -1; }
const char *gpio_line_chip_name(const struct gpio_line *line) { return line->chip == 'a' ? "a" : "b"; }

int gpio_line_read(struct gpio_line *line, struct gpio_event *events, int max)
{
    int c = chip_index(&line->chip);
    if (!chip_present[c]) return 0; /* like Linux 6.1's v1 event fd: quiet, no error */
    int count = 0;
    for (; line->pending > 0 && count < max; line->pending--)
        events[count++] = (struct gpio_event){.timestamp_ns = line->ts, .rising = true};
    return count;
}

int gpio_line_check(struct gpio_line *line)
{
    check_calls++;
    return chip_present[chip_index(&line->chip)] ? 0 : -ENODEV;
}

void gpio_line_close(struct gpio_line *line)
{
    if (!line) return;
    int c = chip_index(&line->chip);
    if (opened[c][line->line] == line) opened[c][line->line] = NULL;
    free(line);
}

/* ---- sbfx stubs ------------------------------------------------------------------------ */

bool sbfx_has_effect(const sbfx *fx, const char *name)
{
    (void)fx, (void)name;
    return true;
}

sbfx_result sbfx_trigger(sbfx *fx, const char *effect, const float position[3])
{
    (void)fx, (void)effect, (void)position;
    triggers++;
    return SBFX_OK;
}

static void on_log(const char *message, void *user)
{
    (void)user;
    logs++;
    if (strstr(message, "went away")) loss_logs++;
    if (strstr(message, "is back")) back_logs++;
}

/* ---- the timeline ---------------------------------------------------------------------- */

static void press(char chip, int line, int64_t t)
{
    struct gpio_line *l = opened[chip_index(&chip)][line];
    if (!l) return;
    l->pending++;
    l->ts = t;
}

/* Services the lines every 16 ms (a 60 Hz kiosk) from t0 to t1. */
static void frames(struct gpio_triggers *t, int64_t t0, int64_t t1)
{
    for (int64_t now = t0; now < t1; now += 16 * MS) gpio_triggers_service(t, NULL, now, on_log, NULL);
}

static void open_two(struct gpio_triggers *t)
{
    struct gpio_trigger_spec specs[2] = {
        {.chip = "a", .line = 3, .debounce_ms = 30, .min_interval_ms = 250, .effect = "x", .origin = "test"},
        {.chip = "b", .line = 1, .debounce_ms = 30, .min_interval_ms = 250, .effect = "x", .origin = "test"},
    };
    char err[256];
    CHECK(gpio_triggers_open(t, specs, 2, NULL, err, sizeof(err)) == 0, "%s", err);
}

CHECK_TEST(chip_lost_logged_once_other_line_fires_line_back)
{
    static struct gpio_triggers t;
    open_two(&t);
    press('a', 3, 100 * MS);
    frames(&t, 100 * MS, 500 * MS);
    CHECK(triggers == 1, "a press before the loss fired %d", triggers);

    chip_present[0] = false; /* chip a unplugged at 0.5 s */
    int calls_before = open_calls;
    frames(&t, 500 * MS, 1600 * MS);
    CHECK(t.counts.losses == 1 && loss_logs == 1, "losses %llu, logged %d",
          (unsigned long long)t.counts.losses, loss_logs);
    press('b', 1, 1700 * MS);
    frames(&t, 1600 * MS, 10600 * MS); /* 9 s without the chip */
    CHECK(triggers == 2, "the other chip's line fired %d (expected 1 more)", triggers - 1);
    int attempts = open_calls - calls_before;
    /* back-off 0.5, 1, 2, 4, 8 s: about 4 attempts in 9 s, not one per frame (560 frames) */
    CHECK(attempts >= 3 && attempts <= 6, "%d attempts to request the lost line in 9 s", attempts);
    CHECK(logs == 1, "%d log lines while the chip was gone (expected the loss only)", logs);

    chip_present[0] = true; /* back at 10.6 s: picked up within the longest back-off */
    frames(&t, 10600 * MS, 19000 * MS);
    CHECK(t.counts.returns == 1 && back_logs == 1, "returns %llu, 'is back' logged %d",
          (unsigned long long)t.counts.returns, back_logs);
    press('a', 3, 19100 * MS);
    frames(&t, 19000 * MS, 19500 * MS);
    CHECK(triggers == 3, "a press after the return fired %d", triggers - 2);
    CHECK(t.counts.losses == 1 && logs == 2, "losses %llu, log lines %d",
          (unsigned long long)t.counts.losses, logs);
    gpio_triggers_close(&t);
}

CHECK_TEST(live_chips_checked_once_a_second)
{
    static struct gpio_triggers t;
    open_two(&t);
    int calls = open_calls;
    frames(&t, 0, 5000 * MS); /* 313 frames */
    CHECK(open_calls == calls && t.counts.losses == 0 && logs == 0, "nothing lost, nothing logged");
    CHECK(check_calls == 2 * 5, "%d chip checks for 2 lines in 5 s (expected 10)", check_calls);
    gpio_triggers_close(&t);
}

int main(int argc, char **argv)
{
    return check_main_args(argc, argv);
}
