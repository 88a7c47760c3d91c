/* sbfx_effect_name() joined into one line. */
#include "gpio/effect_names.h"

#include <stdio.h>
#include <string.h>

const char *effect_names(const sbfx *fx, char *out, size_t n)
{
    if (!n) return out;
    out[0] = '\0';
    size_t used = 0;
    const char *name;
    for (int i = 0; (name = sbfx_effect_name(fx, i)) != NULL; i++) {
        int w = snprintf(out + used, n - used, "%s%s", i ? ", " : "", name);
        if (w < 0 || (size_t)w >= n - used) {
            if (n >= 4) strcpy(out + n - 4, "...");
            return out;
        }
        used += (size_t)w;
    }
    if (!used) snprintf(out, n, "none");
    return out;
}
