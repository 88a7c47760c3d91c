/* GPIO lines as a trigger source (inputs.h): the lines the scene, the board profile and --gpio
 * name (a later one replaces an earlier one's spec for the same chip and line: --gpio over the
 * board, the board over the scene), each debounced and rate limited, queueing its effect on its
 * edges (platform/gpio/gpio_triggers.h does the lines; this is the player's side of them). */
#ifndef SBFX_PLAYER_GPIO_SOURCE_H
#define SBFX_PLAYER_GPIO_SOURCE_H

#include "gpio/gpio_triggers.h"
#include "player/inputs/inputs.h"
#include "player/options/board.h"
#include "player/options/options.h"

struct gpio_source {
    struct trigger_source source;       /* what the loop sees */
    struct gpio_trigger_spec specs[GPIO_TRIGGERS_MAX];
    int spec_count;
    struct gpio_triggers lines;         /* its counters are --stats' gpio_* keys */
    bool on;                            /* the lines are requested */
    input_log_fn log;
    void *log_user;
};

/* The scene's lines (before the scene is freed; the board's rate limit applies to them). */
int gpio_source_add_scene(struct gpio_source *g, const sbfx_scene *scene, const struct board_profile *b, char *err,
                          size_t n);
/* The board's lines, then --gpio's (rising edges, the board's debounce and rate limit). */
int gpio_source_add_options(struct gpio_source *g, const struct board_profile *b, const struct player_options *opt,
                            char *err, size_t n);
/* Requests the lines when there are any (fx checks their effects' names) and then adds the
 * source to the run's; nothing stays requested on failure. */
int gpio_source_open(struct gpio_source *g, struct trigger_sources *all, const sbfx *fx, int64_t now_ns,
                     input_log_fn log, void *user, char *err, size_t n);

#endif
