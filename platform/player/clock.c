/* The player's monotonic clock and its messages ("sbfx-play: ..." on stderr), for every file of
 * the player and the inputs' log callbacks. */
#include <stdio.h>
#include <time.h>

#include "player/player.h"

int64_t player_now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

void player_log(const char *message, void *user)
{
    (void)user;
    fprintf(stderr, "sbfx-play: %s\n", message);
}
