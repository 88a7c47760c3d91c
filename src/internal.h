/* Private to sbfx and its own tools and tests (probe, GL tests, bench): the module's block and
 * every room's header (module.h), with the entry points each room offers them. Not installed. */
#ifndef SBFX_INTERNAL_H
#define SBFX_INTERNAL_H

#include "module.h"

#endif
