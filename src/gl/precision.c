/* GPU precision on any renderer (issue 25, docs/testing.md "Precision diagnostics"). Two
 * environment variables, read once by sbfx_create, make a software rasteriser compute the way
 * GPUs do, so accuracy measured here holds there:
 *   SBFX_MEDIUMP=native   compile mediump as written, also on llvmpipe/softpipe (which then
 *                         emulate half precision; context.c otherwise compiles it as highp)
 *   SBFX_FILTER_BITS=N    every fetch left to the texture filter is filtered in the shader,
 *                         its weights rounded to N fractional bits (shaders_es/filtered.frag)
 * Each one honoured is logged at info level by name; an invalid value fails sbfx_create. */
#include <stdlib.h>
#include <string.h>
#include "gl/gl.h"

/* 1..16: Vulkan's subTexelPrecisionBits is at least 4 and typically 8; past 16 the rounding is
 * below half precision's own and shows nothing. */
#define FILTER_BITS_MIN 1
#define FILTER_BITS_MAX 16

static sbfx_result read_mediump(sbfx *fx)
{
    const char *v = getenv("SBFX_MEDIUMP");
    if (!v) return SBFX_OK;
    if (strcmp(v, "native") != 0)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT,
                         "SBFX_MEDIUMP=\"%s\" is not understood: the only value is \"native\" (compile mediump "
                         "as written, also on a software rasteriser); unset it for the default", v);
    fx->gl->context.mediump_native = true;
    sbfx_log(fx, SBFX_LOG_INFO, "SBFX_MEDIUMP=native honoured: shaders compile mediump as written on every "
             "renderer, software rasterisers included");
    return SBFX_OK;
}

static sbfx_result read_filter_bits(sbfx *fx)
{
    const char *v = getenv("SBFX_FILTER_BITS");
    if (!v) return SBFX_OK;
    char *end = NULL;
    long bits = strtol(v, &end, 10);
    if (end == v || *end != '\0' || bits < FILTER_BITS_MIN || bits > FILTER_BITS_MAX)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT,
                         "SBFX_FILTER_BITS=\"%s\" is not a whole number of bits from %d to %d (the texture "
                         "filter's weight precision to emulate, 8 on most GPUs); unset it for the default",
                         v, FILTER_BITS_MIN, FILTER_BITS_MAX);
    fx->gl->context.filter_bits = (int)bits;
    sbfx_log(fx, SBFX_LOG_INFO, "SBFX_FILTER_BITS=%d honoured: every filtered texture fetch is filtered in the "
             "shader with its weights rounded to %d bits", fx->gl->context.filter_bits, fx->gl->context.filter_bits);
    return SBFX_OK;
}

sbfx_result sbfx_precision_from_env(sbfx *fx)
{
    sbfx_result r = read_mediump(fx);
    return r == SBFX_OK ? read_filter_bits(fx) : r;
}

/* The library's body, after its #version line (gl_util.c inserts it with FILTER_LIBRARY). */
const char *sbfx_filter_library(void)
{
    const char *text = sbfx_shader_source("filtered.frag");
    const char *body = text ? strchr(text, '\n') : NULL;
    return body ? body + 1 : NULL;
}
