/* Presentation feedback -> presented, discarded, missed refreshes, latency. */
#include "wayland/present_feedback.h"

/* Refresh cycles between two presentations that showed no new frame: from the refresh counter
 * where the compositor keeps one, else from the times and the period (rounded: a presentation
 * time jitters by a fraction of a period). */
static uint64_t missed_between(const struct present_feedback *f, int64_t t_ns, uint64_t seq,
                               int64_t refresh_ns)
{
    if (seq && f->last_seq && seq > f->last_seq) return seq - f->last_seq - 1;
    if (refresh_ns <= 0 || t_ns <= f->last_ns) return 0;
    int64_t cycles = (t_ns - f->last_ns + refresh_ns / 2) / refresh_ns;
    return cycles > 1 ? (uint64_t)(cycles - 1) : 0;
}

void present_feedback_presented(struct present_feedback *f, struct display_counts *c, int64_t t_ns,
                                uint64_t seq, int64_t refresh_ns, int64_t commit_ns)
{
    if (f->have_last) c->missed += missed_between(f, t_ns, seq, refresh_ns);
    f->have_last = true;
    f->last_seq = seq;
    f->last_ns = t_ns;
    c->feedback_presented++;
    int64_t latency = t_ns > commit_ns ? t_ns - commit_ns : 0;
    c->latency_ns_sum += latency;
    if (latency > c->latency_ns_max) c->latency_ns_max = latency;
}

void present_feedback_discarded(struct display_counts *c)
{
    c->feedback_discarded++;
}
