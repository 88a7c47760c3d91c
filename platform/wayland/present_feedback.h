/* presentation-time feedback (wp_presentation) turned into the display's counters: when each
 * frame reached the screen, how long after its commit (latency) and how many refresh cycles
 * passed without a new frame (missed, the Wayland counterpart of drm's missed vblanks). Pure
 * logic: tests/platform/test_present_feedback.c drives it with made-up reports.
 *
 *   present_feedback_presented  one frame on screen at t_ns (the compositor's presentation
 *                               clock), committed at commit_ns (the same clock); seq is the
 *                               output's refresh counter (0: the compositor does not count),
 *                               refresh_ns its period (0: unknown)
 *   present_feedback_discarded  one frame the compositor never showed */
#ifndef SBFX_PRESENT_FEEDBACK_H
#define SBFX_PRESENT_FEEDBACK_H

#include <stdbool.h>
#include <stdint.h>

#include "display/display.h"

struct present_feedback {
    bool have_last;
    uint64_t last_seq;
    int64_t last_ns;
};

void present_feedback_presented(struct present_feedback *f, struct display_counts *c, int64_t t_ns,
                                uint64_t seq, int64_t refresh_ns, int64_t commit_ns);
void present_feedback_discarded(struct display_counts *c);

#endif
