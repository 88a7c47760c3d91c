/* The module's effect names as one line ("explosion, smoke, sparks"), for errors about an
 * effect name that is not there (--trigger, --gpio, a scene's or a board's GPIO lines). */
#ifndef SBFX_EFFECT_NAMES_H
#define SBFX_EFFECT_NAMES_H

#include <stddef.h>

#include "sbfx.h"

/* Writes the names into out (truncated with "..." when they do not fit); returns out. */
const char *effect_names(const sbfx *fx, char *out, size_t n);

#endif
