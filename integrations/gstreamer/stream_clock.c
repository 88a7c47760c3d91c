/* Running time -> the module's steps (stream_clock.h). */
#include "stream_clock.h"

void stream_clock_reset(struct stream_clock *c)
{
    uint64_t frame_ns = c->frame_ns, untimed = c->untimed, clamped = c->clamped;
    *c = (struct stream_clock){.frame_ns = frame_ns, .untimed = untimed, .clamped = clamped};
}

void stream_clock_set_rate(struct stream_clock *c, int num, int den)
{
    c->frame_ns = num > 0 && den > 0 ? (uint64_t)den * UINT64_C(1000000000) / (uint64_t)num : 0;
}

/* What a buffer without a running time stands for. */
static uint64_t untimed_step(const struct stream_clock *c, uint64_t duration_ns)
{
    if (duration_ns != STREAM_CLOCK_NONE && duration_ns > 0) return duration_ns;
    return c->frame_ns ? c->frame_ns : STREAM_CLOCK_FALLBACK_NS;
}

uint64_t stream_clock_advance(struct stream_clock *c, uint64_t running_ns, uint64_t duration_ns)
{
    if (running_ns == STREAM_CLOCK_NONE) {
        c->untimed++;
        if (!c->started) { /* the module's zero, wherever the stream's clock is */
            c->started = true;
            c->first_ns = c->last_ns = 0;
            return 0;
        }
        running_ns = c->last_ns + untimed_step(c, duration_ns);
    }
    if (!c->started) {
        c->started = true;
        c->first_ns = c->last_ns = running_ns;
        return 0;
    }
    if (running_ns <= c->last_ns) return 0;
    uint64_t step = running_ns - c->last_ns;
    if (step > STREAM_CLOCK_MAX_STEP_NS) {
        step = STREAM_CLOCK_MAX_STEP_NS;
        c->clamped++;
        c->first_ns += running_ns - c->last_ns - step; /* the module's zero moves with the cut */
    }
    c->last_ns = running_ns;
    return step;
}

double stream_clock_seconds(const struct stream_clock *c)
{
    return c->started ? (double)(c->last_ns - c->first_ns) * 1e-9 : 0.0;
}
