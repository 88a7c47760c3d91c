/* The quality level's public entry points (docs/quality-and-budgets.md): a host sets one, or the
 * frame budget chooses (budget.c); what switching builds and points: gl/levels.c. */
#include "budget/budget.h"

sbfx_result sbfx_set_quality(sbfx *fx, const sbfx_quality *q)
{
    if (!fx || !q) return SBFX_ERR_INVALID_ARGUMENT;
    sbfx_quality r = *q;
    char why[128];
    if (!sbfx_quality_resolve(&r, why, sizeof(why))) return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "sbfx_set_quality: %s", why);
    if (r.opacity == SBFX_OPACITY_FLOOR)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "sbfx_set_quality: the floor opacity is for benchmarks only");
    if (sbfx_budget_active(fx))
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "sbfx_set_quality: the frame budget chooses the level "
                         "(create the module without frame_budget_ms to choose it yourself)");
    if (sbfx_quality_equal(&r, &fx->scene->current)) return SBFX_OK;
    sbfx_gl_enter(fx);
    sbfx_result result = sbfx_quality_apply(fx, &r);
    sbfx_gl_leave(fx, "sbfx_set_quality");
    return result;
}

sbfx_result sbfx_get_quality(const sbfx *fx, sbfx_quality *out)
{
    if (!fx || !out) return SBFX_ERR_INVALID_ARGUMENT;
    *out = fx->scene->current;
    return SBFX_OK;
}
