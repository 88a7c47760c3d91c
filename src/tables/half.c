/* Floats to half floats in bulk (tables.h): the detail volume at load. */
#include <string.h>
#include "base/float16.h"
#include "tables/tables.h"

static inline void store_half(const float *in, uint16_t *out, size_t i)
{
    sbfx_float16 h = (sbfx_float16)in[i];
    memcpy(&out[i], &h, sizeof(h));
}

static void convert(const float *in, uint16_t *out, size_t n)
{
    for (size_t i = 0; i < n; i++) store_half(in, out, i);
}

#if defined(__x86_64__) || defined(__i386__)
/* The same loop compiled for F16C (vcvtps2ph in the current rounding mode, round to nearest even
 * as the software conversion): called only where the CPU says it has the instruction. */
__attribute__((target("f16c"))) static void convert_f16c(const float *in, uint16_t *out, size_t n)
{
    for (size_t i = 0; i < n; i++) store_half(in, out, i);
}
#endif

void sbfx_floats_to_halves(const float *in, uint16_t *out, size_t n)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("f16c")) {
        convert_f16c(in, out, n);
        return;
    }
#endif
    convert(in, out, n);
}
