/* A channel's view on the command line and in board files (options.h): --frustum, --view-offset
 * and the board's view group share these parsers, so their values mean the same everywhere. */
#include <math.h>
#include <stdlib.h>

#include "player/options/options.h"

/* count comma-separated finite numbers, no more, no less; false otherwise */
static bool parse_list(const char *text, double *out, int count)
{
    const char *s = text;
    for (int i = 0; i < count; i++) {
        char *end = NULL;
        out[i] = strtod(s, &end);
        if (end == s || !isfinite(out[i])) return false;
        if (i + 1 < count && *end != ',') return false;
        if (i + 1 == count && *end != '\0') return false;
        s = end + 1;
    }
    return true;
}

const char *player_channel_check_frustum(const float f[4])
{
    for (int i = 0; i < 4; i++)
        if (!(f[i] > -89.0f && f[i] < 89.0f)) return "each angle must be within -89..89 degrees";
    if (!(f[0] < f[1])) return "LEFT must be less than RIGHT";
    if (!(f[2] < f[3])) return "BOTTOM must be less than TOP";
    return NULL;
}

const char *player_parse_frustum(const char *text, struct player_channel *c)
{
    double v[4];
    if (!parse_list(text, v, 4)) return "four numbers separated by commas";
    float f[4] = {(float)v[0], (float)v[1], (float)v[2], (float)v[3]};
    const char *why = player_channel_check_frustum(f);
    if (why) return why;
    for (int i = 0; i < 4; i++) c->frustum[i] = f[i];
    c->have_frustum = true;
    return NULL;
}

const char *player_parse_view_offset(const char *text, struct player_channel *c)
{
    double v[3];
    if (!parse_list(text, v, 3)) return "three numbers separated by commas";
    for (int i = 0; i < 3; i++)
        if (!(v[i] >= -360.0 && v[i] <= 360.0)) return "each angle must be within -360..360 degrees";
    for (int i = 0; i < 3; i++) c->offset[i] = (float)v[i];
    c->have_offset = true;
    return NULL;
}
